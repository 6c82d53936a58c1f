// What a node reports decides when a test has run away: a stroke or force limit acting, or a
// piston on its end stop, stops it on that feedback; a servovalve fully open only after
// run_away.max_valve_saturation_s. A rate limit (velocity, increment, acceleration) shapes
// the commands the node applies, as it must after every command lost or late in real time,
// and never stops the test by itself.
#include <gtest/gtest.h>

#include <memory>
#include <set>

#include "rpsd/transport/messages.h"
#include "specimen_runs.h"

namespace rpsd::coordinator {
namespace {

using namespace hybrid_test;  // whole runs go through the assembly above the loop

// Adds the given node flags to the feedback of chosen exchanges.
class FlaggingLink final : public transport::Link {
 public:
  FlaggingLink(transport::Link& inner, std::set<std::int64_t> steps, std::uint32_t limit_flags, std::uint32_t status)
      : inner_(inner), steps_(std::move(steps)), limit_flags_(limit_flags), status_(status) {}
  transport::LinkStatus send(const transport::CommandSample& command) override { return inner_.send(command); }
  transport::LinkStatus receive(transport::FeedbackSample& feedback) override {
    const transport::LinkStatus status = inner_.receive(feedback);
    if (steps_.count(feedback.step)) {
      feedback.limit_flags |= limit_flags_;
      feedback.status |= status_;
    }
    return status;
  }

 private:
  transport::Link& inner_;
  std::set<std::int64_t> steps_;
  std::uint32_t limit_flags_, status_;
};

std::set<std::int64_t> range(std::int64_t first, std::int64_t count) {
  std::set<std::int64_t> steps;
  for (std::int64_t s = first; s < first + count; ++s) steps.insert(s);
  return steps;
}

testing::SdofRun run_with(std::set<std::int64_t> steps, std::uint32_t limit_flags, std::uint32_t status = 0) {
  SpecimenSdof sdof;
  sdof.duration_s = 1.0;  // 1024 steps
  AssemblyOptions options;
  options.wrap_link = [=](transport::Link& inner) {
    return std::make_unique<FlaggingLink>(inner, steps, limit_flags, status);
  };
  return testing::run_steps(specimen_sdof_test(sdof), options);
}

TEST(RunAway, AStrokeOrForceLimitActingStopsTheTestOnThatFeedback) {
  for (const std::uint32_t flag : {transport::kLimitStroke, transport::kLimitForce}) {
    const auto r = run_with({300}, flag);
    EXPECT_EQ(r.outcome, StepOutcome::kRunAway) << flag;
    EXPECT_EQ(r.limit_stop.kind, LimitStop::Kind::kNodeLimit);
    EXPECT_EQ(r.records.size(), 300u) << flag;  // no step after the one that reported it
  }
}

TEST(RunAway, ARateLimitShapesCommandsAndDoesNotStopTheTest) {
  for (const std::uint32_t flag :
       {transport::kLimitVelocity, transport::kLimitIncrement, transport::kLimitAcceleration}) {
    const auto r = run_with(range(100, 600), flag);
    EXPECT_EQ(r.outcome, StepOutcome::kOk) << flag;
    EXPECT_EQ(r.records.size(), 1024u) << flag;
  }
}

TEST(RunAway, APistonOnItsEndStopStopsTheTest) {
  const auto r = run_with({500}, 0, transport::kNodeEndStop);
  EXPECT_EQ(r.outcome, StepOutcome::kRunAway);
  EXPECT_EQ(r.limit_stop.kind, LimitStop::Kind::kEndStop);
}

TEST(RunAway, AServovalveFullyOpenLongerThanItsTimeStopsTheTest) {
  // 0.25 s at 1024 Hz: 256 exchanges tolerated.
  EXPECT_EQ(run_with(range(100, 256), 0, transport::kNodeValveSaturated).outcome, StepOutcome::kOk);
  const auto r = run_with(range(100, 257), 0, transport::kNodeValveSaturated);
  EXPECT_EQ(r.outcome, StepOutcome::kRunAway);
  EXPECT_EQ(r.limit_stop.kind, LimitStop::Kind::kValveSaturation);
}

}  // namespace
}  // namespace rpsd::coordinator
