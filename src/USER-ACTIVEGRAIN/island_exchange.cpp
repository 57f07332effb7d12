#include "island_exchange.h"

#include "comm.h"
#include "error.h"
#include "solver_bodies.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <type_traits>

using namespace LAMMPS_NS;
using ActiveGrain::ContactSolver;

static_assert(std::is_trivially_copyable<ActiveGrain::RigidBodyState>::value &&
                  std::is_trivially_copyable<ActiveGrain::SolverContact>::value,
              "island contacts travel as bytes");

void IslandExchange::split(ContactSolver &solver, const SolverBodies &bodies, const ContactAssembly &assembly)
{
  crossing.clear();
  crossing_index.clear();
  any_crossing = comm->nprocs > 1 && share_away_bodies(solver, bodies);
  if (any_crossing) mark_crossing_islands(solver, bodies, assembly);
}

// Every rank learns the keys of the movable bodies that some rank's contacts hold while another
// rank decides them: false if there are none anywhere.
bool IslandExchange::share_away_bodies(const ContactSolver &solver, const SolverBodies &bodies)
{
  away_keys.clear();
  for (int c = 0; c < solver.num_contacts(); c++)
    for (int b : {solver.contact(c).body1, solver.contact(c).body2})
      if (bodies.decided_elsewhere(b) && !solver.body(b).is_static()) away_keys.push_back(bodies.key_of(b));
  std::sort(away_keys.begin(), away_keys.end());
  away_keys.erase(std::unique(away_keys.begin(), away_keys.end()), away_keys.end());
  const int mine = static_cast<int>(away_keys.size());
  counts.resize(comm->nprocs);
  displacements.resize(comm->nprocs);
  MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  std::exclusive_scan(counts.begin(), counts.end(), displacements.begin(), 0);
  const int total = displacements.back() + counts.back();
  if (total == 0) return false;
  all_away_keys.resize(total);
  MPI_Allgatherv(away_keys.data(), mine, MPI_UINT64_T, all_away_keys.data(), counts.data(), displacements.data(),
                 MPI_UINT64_T, world);
  shared.clear();
  for (std::uint64_t key : all_away_keys) shared.find_or_insert(key, [] { return 1; });
  return true;
}

// The islands (contacts joined by movable bodies) that hold a shared body: their contacts are
// solved elsewhere, and packed to travel.
void IslandExchange::mark_crossing_islands(ContactSolver &solver, const SolverBodies &bodies,
                                           const ContactAssembly &assembly)
{
  const int num_bodies = solver.num_bodies();
  root.resize(num_bodies);
  std::iota(root.begin(), root.end(), 0);
  auto find = [&](int b) {
    while (root[b] != b) b = root[b] = root[root[b]];
    return b;
  };
  auto movable = [&](int b) { return !solver.body(b).is_static(); };
  for (int c = 0; c < solver.num_contacts(); c++) {
    const ContactSolver::Contact &contact = solver.contact(c);
    if (movable(contact.body1) && movable(contact.body2)) root[find(contact.body1)] = find(contact.body2);
  }
  crossing_root.assign(num_bodies, 0);
  for (int b = 0; b < num_bodies; b++)
    if (movable(b) && shared.find(bodies.key_of(b)) >= 0) crossing_root[find(b)] = 1;
  for (int c = 0; c < solver.num_contacts(); c++) {
    const ContactSolver::Contact &contact = solver.contact(c);
    if (!crossing_root[find(movable(contact.body1) ? contact.body1 : contact.body2)]) continue;
    const ContactAssembly::OrderKey &order = assembly.order_key(c);
    CrossingContact packed;
    packed.key1 = movable(contact.body1) ? bodies.key_of(contact.body1) : 0;
    packed.key2 = movable(contact.body2) ? bodies.key_of(contact.body2) : 0;
    packed.body1 = solver.body(contact.body1);
    packed.body2 = solver.body(contact.body2);
    packed.contact = contact;
    packed.shuffle = order.shuffle;
    packed.identity[0] = std::get<0>(order.identity);
    packed.identity[1] = std::get<1>(order.identity);
    packed.identity[2] = std::get<2>(order.identity);
    packed.identity[3] = std::get<3>(order.identity);
    crossing.push_back(packed);
    crossing_index.push_back(c);
    solver.solve_elsewhere(c);
  }
}

ContactSolver::Result IslandExchange::solve(ContactSolver &solver, const ActiveGrain::SolverSettings &settings,
                                            ContactOrder order)
{
  if (!any_crossing) return ContactSolver::Result();
  const int me = comm->me, nprocs = comm->nprocs;
  const int bytes = static_cast<int>(crossing.size() * sizeof(CrossingContact));
  MPI_Gather(&bytes, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, world);
  if (me == 0) {
    // MPI counts bytes in an int: millions of contacts in islands across cuts are beyond this solve.
    if (std::accumulate(counts.begin(), counts.end(), 0LL) > std::numeric_limits<int>::max())
      error->one(FLERR, "Pair gran/impulse: islands across sub-domains hold more than {} contacts, too many to "
                 "solve whole on one rank", std::numeric_limits<int>::max() / sizeof(CrossingContact));
    std::exclusive_scan(counts.begin(), counts.end(), displacements.begin(), 0);
    gathered.resize((displacements.back() + counts.back()) / sizeof(CrossingContact));
  }
  MPI_Gatherv(crossing.data(), bytes, MPI_BYTE, gathered.data(), counts.data(), displacements.data(), MPI_BYTE, 0,
              world);
  ContactSolver::Result result;
  if (me == 0) {
    result = solve_gathered(settings, order);
    for (int r = 0; r < nprocs; r++) {
      counts[r] = counts[r] / sizeof(CrossingContact) * sizeof(Solution);
      displacements[r] = displacements[r] / sizeof(CrossingContact) * sizeof(Solution);
    }
  }
  solutions.resize(crossing.size());
  MPI_Scatterv(gathered_solutions.data(), counts.data(), displacements.data(), MPI_BYTE, solutions.data(),
               static_cast<int>(solutions.size() * sizeof(Solution)), MPI_BYTE, 0, world);
  for (std::size_t k = 0; k < crossing.size(); k++)
    solver.set_solution(crossing_index[k], solutions[k].impulse, solutions[k].late, solutions[k].velocity_after);
  return result;
}

// Rank 0: the gathered contacts in their global order, each movable body once (by its key, from
// whichever rank sent it: its state is the same on all), each wall's body its own.
ContactSolver::Result IslandExchange::solve_gathered(const ActiveGrain::SolverSettings &settings, ContactOrder order)
{
  gather_order.resize(gathered.size());
  std::iota(gather_order.begin(), gather_order.end(), 0);
  auto order_key = [&](int k) {
    const CrossingContact &c = gathered[k];
    return ContactAssembly::OrderKey{
        c.shuffle, ContactAssembly::ContactIdentity(static_cast<int>(c.identity[0]), static_cast<int>(c.identity[1]),
                                                    c.identity[2], c.identity[3])};
  };
  std::sort(gather_order.begin(), gather_order.end(),
            [&](int a, int b) { return ContactAssembly::precedes(order_key(a), order_key(b), order); });
  gathered_solver.clear();
  merged.clear();
  auto body = [&](std::uint64_t key, const ActiveGrain::RigidBodyState &state) {
    if (key == 0) return gathered_solver.add_body(state);
    return merged.find_or_insert(key, [&] { return gathered_solver.add_body(state); });
  };
  for (int k : gather_order) {
    const CrossingContact &packed = gathered[k];
    const ActiveGrain::SolverContact &c = packed.contact;
    const int b1 = body(packed.key1, packed.body1), b2 = body(packed.key2, packed.body2);
    const int added = gathered_solver.add_contact_arms(b1, b2, c.r1, c.r2, c.n, c.material, c.min_separation,
                                                       c.gain, c.time);
    gathered_solver.set_key(added, c.key);
  }
  const ContactSolver::Result result = gathered_solver.solve(settings);
  gathered_solutions.resize(gathered.size());
  for (std::size_t added = 0; added < gathered.size(); added++) {
    const ContactSolver::Contact &c = gathered_solver.contact(static_cast<int>(added));
    gathered_solutions[gather_order[added]] = {c.impulse, c.late, c.velocity_after};
  }
  return result;
}

double IslandExchange::memory_usage() const
{
  return (double) (crossing.capacity() + gathered.capacity()) * sizeof(CrossingContact) +
      (double) (solutions.capacity() + gathered_solutions.capacity()) * sizeof(Solution) +
      (double) (away_keys.capacity() + all_away_keys.capacity()) * sizeof(std::uint64_t);
}
