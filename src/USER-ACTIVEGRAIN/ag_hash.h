// Counter-based random numbers: a value is a hash of what identifies it (a seed, a lattice cell, a
// step, an atom tag), so it is the same on any number of ranks and in any visiting order, and no
// generator state has to travel with atoms or restarts. No LAMMPS in here.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <vector>

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

// A double holds 53 significant bits: the top 53 bits of a 64-bit hash, times 2^-53, are exactly
// representable and uniform in [0, 1).
constexpr int HASH_BITS = 64;
constexpr int SIGNIFICAND_BITS = 53;
constexpr double SIGNIFICAND_SCALE = 0x1.0p-53;    // 2^-SIGNIFICAND_BITS

// A uniform number in [-1, 1) from a hash (its top SIGNIFICAND_BITS bits).
inline double uniform_symmetric(std::uint64_t h)
{
  return 2.0 * static_cast<double>(h >> (HASH_BITS - SIGNIFICAND_BITS)) * SIGNIFICAND_SCALE - 1.0;
}

// A map from 64-bit keys to non-negative ints that keeps its storage from one use to the next
// (open addressing, linear probing): clear() takes time in proportion to what it holds, and it
// allocates only when it grows. For per-step lookups, where std::unordered_map allocates a node
// per entry.
class KeyIndex {
 public:
  // The value stored at key; if there is none, make() is stored and returned.
  template <class Make> int find_or_insert(std::uint64_t key, Make make)
  {
    if (SLOTS_PER_KEY * (used.size() + 1) > keys.size()) grow();
    std::size_t slot = mix64(key) & (keys.size() - 1);
    while (values[slot] >= 0) {
      if (keys[slot] == key) return values[slot];
      slot = (slot + 1) & (keys.size() - 1);
    }
    const int value = make();
    keys[slot] = key;
    values[slot] = value;
    used.push_back(slot);
    return value;
  }
  // The value stored at key, -1 if there is none.
  int find(std::uint64_t key) const
  {
    if (keys.empty()) return FREE;
    for (std::size_t slot = mix64(key) & (keys.size() - 1); values[slot] >= 0; slot = (slot + 1) & (keys.size() - 1))
      if (keys[slot] == key) return values[slot];
    return FREE;
  }
  void clear()
  {
    for (const std::size_t slot : used) values[slot] = FREE;
    used.clear();
  }

 private:
  // The table is at most half full, so probe runs stay short; its size is a power of two (it
  // doubles from INITIAL_SLOTS), so a slot is found by masking.
  static constexpr std::size_t SLOTS_PER_KEY = 2;
  static constexpr std::size_t INITIAL_SLOTS = 64;
  static constexpr int FREE = -1;    // marks an empty slot: stored values are >= 0

  void grow()
  {
    std::vector<std::uint64_t> old_keys;
    std::vector<int> old_values;
    old_keys.swap(keys);
    old_values.swap(values);
    const std::size_t size = old_keys.empty() ? INITIAL_SLOTS : 2 * old_keys.size();
    keys.assign(size, 0);
    values.assign(size, FREE);
    used.clear();
    for (std::size_t slot = 0; slot < old_keys.size(); slot++)
      if (old_values[slot] >= 0) find_or_insert(old_keys[slot], [&] { return old_values[slot]; });
  }

  std::vector<std::uint64_t> keys;
  std::vector<int> values;
  std::vector<std::size_t> used;    // the slots in use
};

}    // namespace ActiveGrain
