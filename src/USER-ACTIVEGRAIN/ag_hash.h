// Counter-based random numbers: a value is a hash of what identifies it (a seed, a lattice cell, a
// step, an atom tag), so it is the same on any number of ranks and in any visiting order, and no
// generator state has to travel with atoms or restarts. No LAMMPS in here.
#pragma once

#include <cstdint>
#include <initializer_list>

namespace ActiveGrain {

// splitmix64's finalizer: a well-mixed 64-bit hash of one word.
inline std::uint64_t mix64(std::uint64_t z)
{
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// A hash of several words, order-sensitive.
inline std::uint64_t hash_words(std::initializer_list<std::uint64_t> words)
{
  std::uint64_t h = 0;
  for (const std::uint64_t w : words) h = mix64(h ^ w);
  return h;
}

// A uniform number in [-1, 1) from a hash (its top 53 bits).
inline double uniform_symmetric(std::uint64_t h)
{
  return 2.0 * static_cast<double>(h >> 11) * 0x1.0p-53 - 1.0;
}

}    // namespace ActiveGrain
