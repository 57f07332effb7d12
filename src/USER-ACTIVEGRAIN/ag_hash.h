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

// A uniform number in [-1, 1) from a hash (its top 53 bits).
inline double uniform_symmetric(std::uint64_t h)
{
  return 2.0 * static_cast<double>(h >> 11) * 0x1.0p-53 - 1.0;
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
    if (2 * (used_.size() + 1) > keys_.size()) grow();
    std::size_t slot = mix64(key) & (keys_.size() - 1);
    while (values_[slot] >= 0) {
      if (keys_[slot] == key) return values_[slot];
      slot = (slot + 1) & (keys_.size() - 1);
    }
    const int value = make();
    keys_[slot] = key;
    values_[slot] = value;
    used_.push_back(slot);
    return value;
  }
  void clear()
  {
    for (const std::size_t slot : used_) values_[slot] = -1;
    used_.clear();
  }

 private:
  void grow()
  {
    std::vector<std::uint64_t> keys;
    std::vector<int> values;
    keys.swap(keys_);
    values.swap(values_);
    const std::size_t size = keys.empty() ? 64 : 2 * keys.size();
    keys_.assign(size, 0);
    values_.assign(size, -1);
    used_.clear();
    for (std::size_t slot = 0; slot < keys.size(); slot++)
      if (values[slot] >= 0) find_or_insert(keys[slot], [&] { return values[slot]; });
  }

  std::vector<std::uint64_t> keys_;
  std::vector<int> values_;    // -1: free
  std::vector<std::size_t> used_;
};

}    // namespace ActiveGrain
