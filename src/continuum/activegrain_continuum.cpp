// The C interface: argument checks, exceptions turned into status codes and a message.
#include "activegrain_continuum.h"

#include "continuum_solver.h"

#include <new>
#include <stdexcept>
#include <string>

using ActiveGrain::Continuum::Grid;
using ActiveGrain::Continuum::ModelParameters;
using ActiveGrain::Continuum::Solver;

struct ag_continuum {
  Solver solver;
};

namespace {

thread_local std::string last_error;

int fail(int status, const std::string &message)
{
  last_error = message;
  return status;
}

// Runs body, mapping the solver's exceptions to status codes.
template <class Body> int guarded(Body body)
{
  try {
    body();
  } catch (const std::logic_error &e) {   // std::invalid_argument, or no state yet
    return fail(AG_CONTINUUM_BAD_ARGUMENT, e.what());
  } catch (const ActiveGrain::Continuum::StateNotFinite &e) {
    return fail(AG_CONTINUUM_NOT_FINITE, e.what());
  } catch (const std::bad_alloc &) {
    return fail(AG_CONTINUUM_FAILURE, "out of memory");
  } catch (const std::exception &e) {
    return fail(AG_CONTINUUM_FAILURE, e.what());
  }
  last_error.clear();
  return AG_CONTINUUM_OK;
}

}  // namespace

extern "C" {

int ag_continuum_abi_version(void) { return AG_CONTINUUM_ABI_VERSION; }

const char *ag_continuum_last_error(void) { return last_error.c_str(); }

int ag_continuum_create(const ag_continuum_config *c, ag_continuum **out)
{
  if (!out) return fail(AG_CONTINUUM_BAD_ARGUMENT, "out: must not be NULL");
  *out = nullptr;
  if (!c) return fail(AG_CONTINUUM_BAD_ARGUMENT, "config: must not be NULL");
  return guarded([&] {
    Grid grid;
    grid.dim = c->dim;
    grid.nx = c->nx;
    grid.ny = c->ny;
    grid.lx = c->lx;
    grid.ly = c->ly;
    ModelParameters p;
    p.D_rho = c->D_rho;
    p.D_sigma = c->D_sigma;
    p.D_rho_sigma = c->D_rho_sigma;
    p.D_sigma_rho = c->D_sigma_rho;
    p.alpha = c->alpha;
    p.u0 = c->u0;
    p.A = c->A;
    p.B = c->B;
    p.a = c->a;
    p.K = c->K;
    p.tau = c->tau;
    p.proportional_cross_diffusion = c->proportional_cross_diffusion != 0;
    p.rho_close = c->rho_close;
    *out = new ag_continuum{Solver(grid, p, c->dt)};
  });
}

void ag_continuum_destroy(ag_continuum *solver) { delete solver; }

int ag_continuum_set_state(ag_continuum *s, const double *rho, const double *sigma, const double *P)
{
  if (!s) return fail(AG_CONTINUUM_BAD_ARGUMENT, "solver: must not be NULL");
  return guarded([&] { s->solver.set_state(rho, sigma, P); });
}

int ag_continuum_get_state(const ag_continuum *s, double *rho, double *sigma, double *P)
{
  if (!s) return fail(AG_CONTINUUM_BAD_ARGUMENT, "solver: must not be NULL");
  return guarded([&] { s->solver.get_state(rho, sigma, P); });
}

int ag_continuum_step(ag_continuum *s, int steps)
{
  if (!s) return fail(AG_CONTINUUM_BAD_ARGUMENT, "solver: must not be NULL");
  return guarded([&] { s->solver.step(steps); });
}

int ag_continuum_time(const ag_continuum *s, double *time)
{
  if (!s || !time) return fail(AG_CONTINUUM_BAD_ARGUMENT, "solver, time: must not be NULL");
  *time = s->solver.time();
  last_error.clear();
  return AG_CONTINUUM_OK;
}

}  // extern "C"
