// CompensatorCall, the exchange's per-step call of a channel's compensator: a phase lead called
// directly gives the digits of the same network called through its interface, and any other
// kind is reached through its interface, command and observe alike.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rpsd/compensation/compensator_call.h"
#include "rpsd/compensation/discrete_phase_lead.h"
#include "test_time_step.h"

namespace rpsd::compensation {
namespace {

// Another kind: doubles the target and keeps what it observes.
class Doubling final : public CommandCompensator {
 public:
  void configure(double) override {}
  void reset(double) noexcept override {}
  double command(double target_m) noexcept override { return 2.0 * target_m; }
  void observe(double target_m, double measured_m) noexcept override {
    observed.push_back(target_m);
    observed.push_back(measured_m);
  }
  double compensated_delay_s() const noexcept override { return 0.0; }
  std::string_view name() const noexcept override { return "doubling"; }
  std::vector<double> observed;
};

TEST(CompensatorCall, APhaseLeadCalledDirectlyGivesTheDigitsOfItsInterface) {
  const auto p = DiscretePhaseLeadParameters::for_delay(0.09, 20.0);
  DiscretePhaseLeadCompensator direct(p), through_interface(p);
  direct.configure(kDt);
  through_interface.configure(kDt);
  direct.reset(0.001);
  through_interface.reset(0.001);
  CompensatorCall call(&direct);
  CommandCompensator& any = through_interface;
  for (int n = 0; n < 200; ++n) {
    const double target = 0.01 * std::sin(0.05 * n) + 0.001;
    const double got = call.command(target), want = any.command(target);
    ASSERT_EQ(got, want) << "step " << n;
    ASSERT_NE(got, target) << "step " << n << ": the network acted";  // a lead, not a pass-through
    call.observe(target, 0.5 * target);
    any.observe(target, 0.5 * target);
  }
}

TEST(CompensatorCall, AnyOtherKindIsCalledThroughItsInterface) {
  Doubling doubling;
  CompensatorCall call(&doubling);
  EXPECT_EQ(call.command(0.25), 0.5);
  call.observe(0.25, 0.125);
  EXPECT_EQ(doubling.observed, (std::vector<double>{0.25, 0.125}));
}

}  // namespace
}  // namespace rpsd::compensation
