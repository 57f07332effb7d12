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
  const int mine = static_cast<int>(crossing.size());
  MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  std::exclusive_scan(counts.begin(), counts.end(), displacements.begin(), 0);
  const long long total = std::accumulate(counts.begin(), counts.end(), 0LL);
  // MPI counts bytes in an int: millions of contacts in islands across cuts are beyond this solve.
  if (total > static_cast<long long>(std::numeric_limits<int>::max() / sizeof(CrossingContact)))
    error->all(FLERR, "Pair gran/impulse: islands across sub-domains hold {} contacts, too many to exchange whole",
               total);
  gathered.resize(total);
  for (auto *v : {&send_bytes, &byte_offsets, &recv_bytes, &recv_offsets}) v->resize(nprocs);
  for (int r = 0; r < nprocs; r++) {
    send_bytes[r] = counts[r] * static_cast<int>(sizeof(CrossingContact));
    byte_offsets[r] = displacements[r] * static_cast<int>(sizeof(CrossingContact));
  }
  MPI_Allgatherv(crossing.data(), send_bytes[me], MPI_BYTE, gathered.data(), send_bytes.data(), byte_offsets.data(),
                 MPI_BYTE, world);
  const ContactSolver::Result result = solve_own_islands(settings, order);
  return_solutions(solver);
  return result;
}

// Every rank holds every crossing contact; each island goes to one rank, by the position of its
// first contact in the global order (the same on all ranks), so that the islands' work is shared.
// That rank solves it: its contacts in their global order, each movable body once (by its key,
// from whichever rank sent it: its state is the same on all), each wall's body its own.
ContactSolver::Result IslandExchange::solve_own_islands(const ActiveGrain::SolverSettings &settings,
                                                        ContactOrder order)
{
  const int total = static_cast<int>(gathered.size());
  gather_order.resize(total);
  std::iota(gather_order.begin(), gather_order.end(), 0);
  auto order_key = [&](int k) {
    const CrossingContact &c = gathered[k];
    return ContactAssembly::OrderKey{
        c.shuffle, ContactAssembly::ContactIdentity(static_cast<int>(c.identity[0]), static_cast<int>(c.identity[1]),
                                                    c.identity[2], c.identity[3])};
  };
  std::sort(gather_order.begin(), gather_order.end(),
            [&](int a, int b) { return ContactAssembly::precedes(order_key(a), order_key(b), order); });
  // The islands: movable bodies (by key) joined by contacts.
  merged.clear();
  root.clear();
  auto node = [&](std::uint64_t key) {
    return merged.find_or_insert(key, [&] {
      root.push_back(static_cast<int>(root.size()));
      return static_cast<int>(root.size()) - 1;
    });
  };
  auto find = [&](int b) {
    while (root[b] != b) b = root[b] = root[root[b]];
    return b;
  };
  contact_node.resize(total);
  for (int k = 0; k < total; k++) {
    const CrossingContact &c = gathered[k];
    const int n1 = c.key1 ? node(c.key1) : -1, n2 = c.key2 ? node(c.key2) : -1;
    if (n1 >= 0 && n2 >= 0) root[find(n1)] = find(n2);
    contact_node[k] = n1 >= 0 ? n1 : n2;
  }
  first_position.assign(root.size(), -1);
  owner.resize(total);
  for (int p = 0; p < total; p++) {
    const int k = gather_order[p], island = find(contact_node[k]);
    if (first_position[island] < 0) first_position[island] = p;
    owner[k] = first_position[island] % comm->nprocs;
  }
  gathered_solver.clear();
  merged.clear();
  auto body = [&](std::uint64_t key, const ActiveGrain::RigidBodyState &state) {
    if (key == 0) return gathered_solver.add_body(state);
    return merged.find_or_insert(key, [&] { return gathered_solver.add_body(state); });
  };
  own_contacts.clear();
  for (int k : gather_order) {
    if (owner[k] != comm->me) continue;
    const CrossingContact &packed = gathered[k];
    const ActiveGrain::SolverContact &c = packed.contact;
    const int b1 = body(packed.key1, packed.body1), b2 = body(packed.key2, packed.body2);
    const int added = gathered_solver.add_contact_arms(b1, b2, c.r1, c.r2, c.n, c.model, c.min_separation,
                                                       c.gain, c.time);
    gathered_solver.set_key(added, c.key);
    own_contacts.push_back(k);
  }
  const ContactSolver::Result result = gathered_solver.solve(settings);
  gathered_solutions.resize(total);
  for (std::size_t added = 0; added < own_contacts.size(); added++) {
    const ContactSolver::Contact &c = gathered_solver.contact(static_cast<int>(added));
    gathered_solutions[own_contacts[added]] = {c.impulse, c.late, c.velocity_after};
  }
  return result;
}

// Each rank's solutions go to the ranks whose contacts they are (both sides know who solved what),
// in the order of those ranks' crossing contacts.
void IslandExchange::return_solutions(ContactSolver &solver)
{
  const int me = comm->me, nprocs = comm->nprocs;
  outgoing.clear();
  for (int r = 0; r < nprocs; r++) {
    send_bytes[r] = recv_bytes[r] = 0;
    for (int k = displacements[r]; k < displacements[r] + counts[r]; k++)
      if (owner[k] == me) {
        outgoing.push_back(gathered_solutions[k]);
        send_bytes[r] += sizeof(Solution);
      }
  }
  for (int k = displacements[me]; k < displacements[me] + counts[me]; k++) recv_bytes[owner[k]] += sizeof(Solution);
  std::exclusive_scan(send_bytes.begin(), send_bytes.end(), byte_offsets.begin(), 0);
  std::exclusive_scan(recv_bytes.begin(), recv_bytes.end(), recv_offsets.begin(), 0);
  incoming.resize(crossing.size());
  MPI_Alltoallv(outgoing.data(), send_bytes.data(), byte_offsets.data(), MPI_BYTE, incoming.data(), recv_bytes.data(),
                recv_offsets.data(), MPI_BYTE, world);
  // From each solving rank in turn, in this rank's order.
  for (int r = 0, received = 0; r < nprocs; r++)
    for (int k = 0; k < static_cast<int>(crossing.size()); k++) {
      if (owner[displacements[me] + k] != r) continue;
      const Solution &solution = incoming[received++];
      solver.set_solution(crossing_index[k], solution.impulse, solution.late, solution.velocity_after);
    }
}

double IslandExchange::memory_usage() const
{
  return (double) (crossing.capacity() + gathered.capacity()) * sizeof(CrossingContact) +
      (double) (incoming.capacity() + outgoing.capacity() + gathered_solutions.capacity()) * sizeof(Solution) +
      (double) (away_keys.capacity() + all_away_keys.capacity()) * sizeof(std::uint64_t);
}
