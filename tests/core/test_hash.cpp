// KeyIndex (ag_hash.h): the per-step map from body keys to solver bodies in pair gran/impulse.
#include "ag_hash.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <unordered_map>

using ActiveGrain::KeyIndex;

TEST(KeyIndex, FindsWhatWasInsertedAcrossGrowthAndClears)
{
  KeyIndex index;
  for (int round = 0; round < 3; ++round) {
    std::unordered_map<std::uint64_t, int> reference;
    int made = 0;
    // Keys as pair gran/impulse makes them (2 tag, 2 body + 1), with repeats, past several growths.
    for (std::uint64_t n = 0; n < 5000; ++n) {
      const std::uint64_t key = (n * 7919 + round) % 3001 * 2 + (n % 3 == 0);
      const int value = index.find_or_insert(key, [&] { return made++; });
      const auto found = reference.emplace(key, value);
      EXPECT_EQ(value, found.first->second) << "key " << key;
    }
    EXPECT_EQ(made, static_cast<int>(reference.size()));    // make() once per new key
    index.clear();
    EXPECT_EQ(index.find_or_insert(4, [] { return 123; }), 123);    // nothing left after a clear
    index.clear();
  }
}
