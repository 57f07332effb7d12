// The contact solver's settings (ag_contact_solver.h): its resolution and every threshold that
// changes the outcome, in one place. No LAMMPS in here.
#pragma once

#include <limits>

namespace ActiveGrain {

struct SolverSettings {
  int resolution = 150;    // sub-steps per half oscillation of the stiffest engaged contact
  int max_substeps = 1000000;    // per island; then the island's impact stops where it is
  // Island contacts that close within window of the first are one compliant impact; the rest
  // follow in order. Infinite: all contacts of an island are one impact, whenever they close.
  double window = std::numeric_limits<double>::infinity();
  double step = std::numeric_limits<double>::infinity();    // contacts closing later wait
  // A compliant impact ends once no spring is loaded and no contact approaches faster than this
  // fraction of the fastest approach before it: a dense cluster's slow re-collisions are left to
  // the next step, which finds them as contacts again. Smaller: longer impacts, less left over.
  double settled_approach = 1.0e-2;
  // A contact approaching at most this many times as fast as its gain makes it (a rod lying on a
  // plate under gravity) is resting: nanometres of gap set when it closes, so it counts as
  // touching from the start instead of taking a place in the order of impacts.
  double resting_gain = 2.0;
  // Impacts in order an island takes within a step at most; contacts that would close after them
  // wait for the next step. Bounds the work of rods bouncing between base and lid with little play.
  int max_impacts_in_order = 64;
  // The overlap correction's Jacobi sweeps stop once every overlap opens within this fraction of
  // its minimum separation velocity, or after max_overlap_sweeps: overlaps squeezed from opposite
  // sides (a rod tilted between base and lid) cannot all open at once, and each step removes only
  // a fraction of an overlap anyway. Smaller or more: overlaps open more exactly, at more cost.
  double overlap_tolerance = 1.0e-2;
  int max_overlap_sweeps = 100;
  // Island contacts approaching no faster than this are resting (ag_resting_solve.h): solved
  // together, after the impacts of the others. 0: every contact is an impact. With
  // resting_from_acceleration, set_step() sets it from the velocity that gravity and the plates
  // give within a step (resting_gain times that).
  double resting_speed = 0.0;
  bool resting_from_acceleration = false;
  // The resting solve keeps the restitution of every contact that approaches faster than
  // resting_gain times its gain (a collision in the plane, not a body settling under gravity), as
  // Newton's law at the velocity level; false: every resting contact is plastic. Either way it
  // gains no more energy than the plastic solve of the same contacts (ag_resting_solve.h).
  bool resting_restitution = false;
  // The resting solve's sweeps stop once none changes a contact's velocity by more than this
  // fraction of resting_speed, or after max_resting_sweeps. It also bounds how much slower than
  // its minimum separation velocity an overlap of a resting-solved island opens.
  double resting_tolerance = 1.0e-2;
  int max_resting_sweeps = 1000;

  // The step's length and the largest acceleration of gravity or a plate in it.
  void set_step(double dt, double largest_acceleration)
  {
    step = dt;
    if (resting_from_acceleration) resting_speed = resting_gain * dt * largest_acceleration;
  }
};

}    // namespace ActiveGrain
