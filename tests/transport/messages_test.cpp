// The check that stops a test on a failed transducer looks at the used channels only, and at
// both the displacement and the force of each.
#include <gtest/gtest.h>

#include <limits>

#include "rpsd/transport/messages.h"

namespace rpsd::transport {
namespace {

TEST(Messages, ANonFiniteDisplacementOrForceInAUsedChannelIsFound) {
  FeedbackSample sample;
  EXPECT_FALSE(has_non_finite_measurement(sample, 2));
  sample.displacement_m[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(has_non_finite_measurement(sample, 2));
  sample.displacement_m[1] = 0.01;
  sample.force_n[0] = -std::numeric_limits<double>::infinity();
  EXPECT_TRUE(has_non_finite_measurement(sample, 2));
}

TEST(Messages, AChannelBeyondTheUsedOnesIsNotLookedAt) {
  FeedbackSample sample;
  sample.force_n[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(has_non_finite_measurement(sample, 2));
  EXPECT_TRUE(has_non_finite_measurement(sample, 3));
}

}  // namespace
}  // namespace rpsd::transport
