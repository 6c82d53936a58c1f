#include "rpsd/config/closest_name.h"

#include <gtest/gtest.h>

namespace rpsd::config {
namespace {

// Levenshtein's textbook pairs.
TEST(ClosestName, EditDistanceOfKnownPairs) {
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("flaw", "lawn"), 2u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("same", "same"), 0u);
}

// A likely typo is named; a different word is not (at most a third of the letters differ).
TEST(ClosestName, NamesOnlyALikelyTypo) {
  const std::vector<std::string_view> keys{"floor_masses_kg", "storey_stiffness_n_per_m", "kind"};
  EXPECT_EQ(closest_name("floor_mass_kg", keys), "floor_masses_kg");
  EXPECT_EQ(did_you_mean("storey_stifness_n_per_m", keys), " (did you mean \"storey_stiffness_n_per_m\"?)");
  EXPECT_EQ(closest_name("damping", keys), std::nullopt);
  EXPECT_EQ(closest_name("kid", keys), "kind");
  EXPECT_EQ(closest_name("xy", keys), std::nullopt);
  EXPECT_EQ(did_you_mean("kind", keys), "");  // not misspelt at all
}

}  // namespace
}  // namespace rpsd::config
