// The host program's compensator behind the loop's interface: its calls forwarded, its state
// its own per channel, its failures caught and kept, and no source refused.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "rpsd/compensation/compensator_factory.h"
#include "test_time_step.h"

namespace rpsd::compensation {
namespace {

// A running sum of its targets (state between calls), throwing on its `throw_at`-th command.
class SummingHost final : public HostCompensator {
 public:
  explicit SummingHost(long throw_at, std::vector<double>* observed) : throw_at_(throw_at), observed_(observed) {}
  void configure(double dt_s) override { dt_s_ = dt_s; }
  void reset(double x0) override { sum_ = x0; }
  double command(double target_m) override {
    if (++calls_ == throw_at_) throw std::runtime_error("no command at call " + std::to_string(calls_));
    return sum_ += target_m;
  }
  void observe(double target_m, double measured_m) override { observed_->push_back(measured_m - target_m); }
  double dt_s_ = 0.0;

 private:
  long throw_at_, calls_ = 0;
  double sum_ = 0.0;
  std::vector<double>* observed_;
};

struct SummingSource final : ExternalCompensatorSource {
  std::unique_ptr<HostCompensator> make(int channel) const override {
    channels.push_back(channel);
    return std::make_unique<SummingHost>(channel == 1 ? throw_at : 0, &observed);
  }
  long throw_at = 0;
  mutable std::vector<int> channels;
  mutable std::vector<double> observed;
};

ExternalCompensatorParameters named(std::shared_ptr<const ExternalCompensatorSource> source) {
  return {"summing", std::move(source)};
}

TEST(ExternalCompensator, EachChannelHasItsOwnHostCompensatorThatKeepsItsStateBetweenCalls) {
  auto source = std::make_shared<SummingSource>();
  const auto a = make_compensator(named(source), kDt, 0);
  const auto b = make_compensator(named(source), kDt, 1);
  EXPECT_EQ(source->channels, (std::vector<int>{0, 1}));
  EXPECT_EQ(a->name(), "external");
  a->reset(1.0);
  b->reset(0.0);
  EXPECT_EQ(a->command(0.5), 1.5);
  EXPECT_EQ(b->command(2.0), 2.0);
  EXPECT_EQ(a->command(0.25), 1.75);  // a's own sum, untouched by b's call
  EXPECT_EQ(b->command(2.0), 4.0);
  a->observe(0.25, 0.5);
  EXPECT_EQ(source->observed, (std::vector<double>{0.25}));
}

TEST(ExternalCompensator, AHostCallThatThrowsIsKeptAndEveryLaterCommandIsNaN) {
  auto source = std::make_shared<SummingSource>();
  source->throw_at = 3;
  const auto made = make_compensator(named(source), kDt, 1);
  auto& c = dynamic_cast<ExternalCompensator&>(*made);
  EXPECT_FALSE(c.failed());
  EXPECT_EQ(c.command(1.0), 1.0);
  EXPECT_EQ(c.command(1.0), 2.0);
  EXPECT_TRUE(std::isnan(c.command(1.0)));  // the throw, caught: the loop's stroke check stops the step
  EXPECT_TRUE(c.failed());
  EXPECT_STREQ(c.failure(), "command(): no command at call 3");
  EXPECT_TRUE(std::isnan(c.command(1.0)));  // nothing more reaches the host
  c.observe(1.0, 1.0);
  EXPECT_TRUE(source->observed.empty());
  EXPECT_EQ(c.channel(), 1);
  EXPECT_EQ(c.host_name(), "summing");
}

TEST(ExternalCompensator, WithoutASourceItIsRefusedNamingTheKindAndTheHost) {
  try {
    (void)make_compensator(ExternalCompensatorParameters{"my_controller", nullptr}, kDt);
    FAIL() << "made";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "compensation.kind external `my_controller`: given only by a host program (rpsd.run(..., "
                 "callables=...)); the command line cannot run it");
  }
}

TEST(ExternalCompensator, AHostThatCannotMakeItsCompensatorRefusesTheRunWithItsMessage) {
  struct Failing final : ExternalCompensatorSource {
    std::unique_ptr<HostCompensator> make(int) const override { throw std::runtime_error("no such controller"); }
  };
  try {
    (void)make_compensator(named(std::make_shared<Failing>()), kDt, 2);
    FAIL() << "made";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "compensation external `summing`: the host could not make channel 2's compensator: no such "
                 "controller");
  }
}

}  // namespace
}  // namespace rpsd::compensation
