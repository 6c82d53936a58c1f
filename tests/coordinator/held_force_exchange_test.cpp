// A channel in force control beside a structure's channel in displacement control: the held
// force is sent in force mode on the link channel after the structure's, its command ramps
// from the force at rest at the stated rate (f(t) = f0 + sign(F - f0) min(r t, |F - f0|),
// written out here), it never reaches the integrator, and its load cell, its piston's stroke
// and its force's tracking error each stop the test under its own limit, named.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "exchange_row.h"
#include "rpsd/compensation/compensator_factory.h"
#include "rpsd/coordinator/experimental_exchange.h"
#include "rpsd/coordinator/limit_stop_text.h"
#include "rpsd/coordinator/recorder.h"

namespace rpsd::coordinator {
namespace {

constexpr double kAtRestN = -1000.0, kHeldN = -200.0e3, kRateNPerS = 100.0e3;
constexpr double kJackStiffnessNPerM = 50.0e6;  // what the jack pushes on: stroke = force / k

// Channel 0 follows its displacement; channel 1, in force control, measures the force it is
// sent plus `force_error_n`, its piston at force / k plus `stroke_shift_m`. Channel 0 reads a
// fixed force.
class MixedLink final : public transport::Link {
 public:
  transport::LinkStatus send(const transport::CommandSample& command) override {
    sent.push_back(command);
    return transport::LinkStatus::kOk;
  }
  transport::LinkStatus receive(transport::FeedbackSample& feedback) override {
    const transport::CommandSample& c = sent.back();
    feedback.step = c.step;
    feedback.channels = c.channels;
    feedback.displacement_m[0] = c.displacement_m[0];
    feedback.force_n[0] = 250.0;
    feedback.force_n[1] = c.force_n[1] + force_error_n;
    feedback.displacement_m[1] = feedback.force_n[1] / kJackStiffnessNPerM + stroke_shift_m;
    return transport::LinkStatus::kOk;
  }
  std::vector<transport::CommandSample> sent;
  double force_error_n = 0.0, stroke_shift_m = 0.0;
};

HeldForceChannel axial() {
  HeldForceChannel h;
  std::snprintf(h.name.data(), h.name.size(), "site 1 held force axial");
  h.channel = 1;
  h.force_n = kHeldN;
  h.max_force_rate_n_per_s = kRateNPerS;
  h.force_at_rest_n = kAtRestN;
  h.limits.max_force_n = 300.0e3;
  h.limits.max_stroke_m = 0.01;
  h.limits.max_force_error_n = 20.0e3;
  return h;
}

struct MixedExchange {
  MixedLink link;
  std::unique_ptr<compensation::CommandCompensator> compensator =
      compensation::make_compensator(compensation::PassThroughParameters{}, 1.0 / 1024);
  std::unique_ptr<ExperimentalExchange> exchange;

  explicit MixedExchange(std::vector<HeldForceChannel> held = {axial()}) {
    ExchangeParts parts;
    parts.link = &link;
    parts.compensators = {compensator.get()};
    parts.force_paths.resize(1);
    parts.run_id = 9;
    parts.held_forces = std::move(held);
    exchange = std::make_unique<ExperimentalExchange>(std::move(parts));
    const double zero[1] = {0.0};
    exchange->start(Eigen::VectorXd::Zero(1), zero);
  }
  StepOutcome to(double x_m, double time_s) { return exchange->exchange(Eigen::VectorXd::Constant(1, x_m), time_s); }
};

double ramp_n(double time_s) {
  const double to_go = kHeldN - kAtRestN;
  return std::abs(to_go) <= kRateNPerS * time_s ? kHeldN : kAtRestN + std::copysign(kRateNPerS * time_s, to_go);
}

TEST(HeldForceExchange, IsSentInForceModeOnTheChannelAfterTheStructuresAndRampsAtItsRate) {
  MixedExchange e;
  EXPECT_EQ(e.exchange->channels(), 1);
  EXPECT_EQ(e.exchange->held_forces(), 1);
  for (const double t : {0.0, 0.25, 1.0, 1.989, 1.99, 2.5, 10.0}) {
    ASSERT_EQ(e.to(0.002, t), StepOutcome::kOk) << t;
    const transport::CommandSample& c = e.link.sent.back();
    EXPECT_EQ(c.channels, 2);
    EXPECT_EQ(c.control_mode[0], transport::kDisplacementControl);
    EXPECT_EQ(c.control_mode[1], transport::kForceControl);
    EXPECT_DOUBLE_EQ(c.displacement_m[0], 0.002);
    EXPECT_NEAR(c.force_n[1], ramp_n(t), 1e-9) << t;
  }
  EXPECT_EQ(e.link.sent.back().force_n[1], kHeldN);  // held once ramped (1.99 s), not beyond
}

TEST(HeldForceExchange, TheHeldForceIsNotARestoringForceOfTheStructure) {
  MixedExchange e;
  ASSERT_EQ(e.to(0.001, 5.0), StepOutcome::kOk);
  ASSERT_EQ(e.exchange->specimen_forces().size(), 1);
  EXPECT_EQ(e.exchange->specimen_forces()[0], 250.0);
  StepRecord r;
  e.exchange->fill_channels(r);
  EXPECT_EQ(r.channels, 1);
  ASSERT_EQ(r.held, 1);
  EXPECT_EQ(r.held_force_command_n[0], kHeldN);
  EXPECT_EQ(r.held_measured_force_n[0], kHeldN);
  EXPECT_NEAR(r.held_measured_m[0], kHeldN / kJackStiffnessNPerM, 1e-15);
}

// The loop writes the channels' part of its row in place (RecordLayout::Row): unpacked, the
// row carries the held force's command, stroke and load cell as fill_channels writes them.
TEST(HeldForceExchange, ARowWrittenInPlaceCarriesTheHeldForceAsARecordDoes) {
  MixedExchange e;
  ASSERT_EQ(e.to(0.001, 5.0), StepOutcome::kOk);
  const StepRecord got = expect_row_carries_the_record(*e.exchange);
  EXPECT_EQ(got.held, 1);
  EXPECT_NE(got.held_force_command_n[0], 0.0);
}

TEST(HeldForceExchange, ALoadCellBeyondItsForceLimitStopsNamingTheHeldForce) {
  HeldForceChannel h = axial();
  h.limits.max_force_error_n = 1.0e6;
  MixedExchange wide({h});
  wide.link.force_error_n = -350.0e3;  // the first command (the force at rest) reads -351 kN
  EXPECT_EQ(wide.to(0.0, 0.0), StepOutcome::kLimit);
  const LimitStop& l = wide.exchange->limit_stop();
  EXPECT_EQ(l.kind, LimitStop::Kind::kForce);
  EXPECT_EQ(l.held, 0);
  EXPECT_EQ(l.channel, 1);
  EXPECT_STREQ(l.name.data(), "site 1 held force axial");
  const std::string text = describe_limit_stop(l);
  EXPECT_NE(text.find("site 1 held force axial"), std::string::npos) << text;
  EXPECT_NE(text.find("max_force_n"), std::string::npos) << text;
}

TEST(HeldForceExchange, APistonThatRunsUnderTheHeldForceStopsTheTest) {
  MixedExchange e;
  ASSERT_EQ(e.to(0.0, 0.5), StepOutcome::kOk);
  e.link.stroke_shift_m = 0.012;  // the specimen gives way: the piston runs past 10 mm (-1 mm + 12 mm)
  EXPECT_EQ(e.to(0.0, 0.51), StepOutcome::kRunAway);
  const LimitStop& l = e.exchange->limit_stop();
  EXPECT_EQ(l.kind, LimitStop::Kind::kStroke);
  EXPECT_STREQ(l.unit, "m");
  EXPECT_NE(describe_limit_stop(l).find("measured stroke"), std::string::npos);
}

TEST(HeldForceExchange, AForceThatDoesNotFollowItsCommandStopsTheTest) {
  MixedExchange e;
  e.link.force_error_n = 19.9e3;
  ASSERT_EQ(e.to(0.0, 0.5), StepOutcome::kOk);
  e.link.force_error_n = 20.1e3;
  EXPECT_EQ(e.to(0.0, 0.51), StepOutcome::kRunAway);
  const LimitStop& l = e.exchange->limit_stop();
  EXPECT_EQ(l.kind, LimitStop::Kind::kTrackingError);
  EXPECT_NEAR(l.value, -20.1e3, 1e-6);
  EXPECT_STREQ(l.unit, "N");
  EXPECT_NE(describe_limit_stop(l).find("max_force_error_n"), std::string::npos);
}

TEST(HeldForceExchange, AForceCommandBeyondTheLimitIsNeverSent) {
  HeldForceChannel h = axial();
  h.force_at_rest_n = -400.0e3;  // what the jack already carries is beyond the limit
  MixedExchange e({h});
  EXPECT_EQ(e.to(0.0, 0.0), StepOutcome::kLimit);
  EXPECT_TRUE(e.link.sent.empty());
  EXPECT_EQ(e.exchange->limit_stop().kind, LimitStop::Kind::kForce);
}

TEST(HeldForceExchange, ANonFiniteReadingOfTheHeldChannelStopsTheTest) {
  MixedExchange e;
  e.link.stroke_shift_m = std::nan("");
  EXPECT_EQ(e.to(0.0, 0.1), StepOutcome::kNonFinite);
}

TEST(HeldForceExchange, AHeldForceOffItsChannelOrWithoutARateIsRefused) {
  HeldForceChannel h = axial();
  h.channel = 2;
  EXPECT_THROW(MixedExchange({h}), std::invalid_argument);
  h = axial();
  h.max_force_rate_n_per_s = 0.0;
  EXPECT_THROW(MixedExchange({h}), std::invalid_argument);
  std::vector<HeldForceChannel> many;
  for (int k = 0; k < transport::kMaxChannels; ++k) {
    many.push_back(axial());
    many.back().channel = 1 + k;
  }
  EXPECT_THROW(MixedExchange{many}, std::invalid_argument);  // 1 + 8 link channels
}

TEST(HeldForceExchange, TheRecorderWritesTheHeldColumnsOnlyWhenThereAreAny) {
  const auto header_of = [](RecorderOptions options, const StepRecord& r) {
    const std::filesystem::path csv =
        std::filesystem::temp_directory_path() / ("held_" + std::to_string(::getpid()) + ".csv");
    {
      Recorder recorder(csv, 1, 0, std::move(options));
      recorder.record_or_wait(r);
      recorder.finish();
    }
    std::ifstream in(csv);
    std::string header, row;
    std::getline(in, header);
    std::getline(in, row);
    std::filesystem::remove(csv);
    return std::make_pair(header, row);
  };
  MixedExchange e;
  ASSERT_EQ(e.to(0.0, 5.0), StepOutcome::kOk);
  StepRecord r;
  e.exchange->fill_channels(r);
  const auto [plain, plain_row] = header_of({}, r);
  EXPECT_EQ(plain.find("held"), std::string::npos);
  RecorderOptions options;
  options.held_channels = {1};
  const auto [held, held_row] = header_of(options, r);
  EXPECT_EQ(held, plain + ",held_force_command_n_ch1,held_measured_m_ch1,held_measured_force_n_ch1");
  EXPECT_EQ(held_row, plain_row + ",-200000,-0.004,-200000");
}

}  // namespace
}  // namespace rpsd::coordinator
