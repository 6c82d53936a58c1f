// The exchange with a site an experimental setup drives, against hand-derived geometry: two
// horizontal actuators at heights 0 and h on a control point that translates (x) and
// rotates (θ). Linear: strokes s1 = x, s2 = x - h θ, and the DOF forces Jᵀ f = (f1 + f2, -h f2).
// Large displacement: s2 = |(x - h sin θ + L2, h cos θ - h)| - L2. Each actuator's limits act on
// its own stroke and force, each DOF's on the DOF; a geometry that fails stops the exchange.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "exchange_row.h"
#include "rpsd/compensation/compensator_factory.h"
#include "rpsd/coordinator/experimental_exchange.h"
#include "rpsd/coordinator/limit_stop_text.h"

namespace rpsd::coordinator {
namespace {

constexpr double kH = 0.8, kL1 = 1.5, kL2 = 1.2;  // m

// Answers each command with the commanded readings (plus `reading_shift`) and fixed forces,
// and keeps every command it was sent.
class PerfectLink final : public transport::Link {
 public:
  transport::LinkStatus send(const transport::CommandSample& command) override {
    sent.push_back(command);
    return transport::LinkStatus::kOk;
  }
  transport::LinkStatus receive(transport::FeedbackSample& feedback) override {
    const transport::CommandSample& c = sent.back();
    feedback.step = c.step;
    feedback.channels = c.channels;
    for (int i = 0; i < c.channels; ++i) {
      feedback.displacement_m[i] = c.displacement_m[i] + reading_shift[i];
      feedback.force_n[i] = force_n[i];
    }
    return transport::LinkStatus::kOk;
  }
  std::vector<transport::CommandSample> sent;
  std::array<double, transport::kMaxChannels> force_n{}, reading_shift{};
};

setups::PlanarGeometry two_actuators(setups::Geometry geometry) {
  setups::PlanarGeometry g;
  g.geometry = geometry;
  g.dof_count = 2;
  g.dofs = {setups::DofMotion::kTranslationX, setups::DofMotion::kRotation, setups::DofMotion::kTranslationX};
  g.actuators[0] = {"west", {-kL1, 0.0}, {0.0, 0.0}};
  g.actuators[1] = {"east", {-kL2, kH}, {0.0, kH}};
  return g;
}

struct Exchange {
  PerfectLink link;
  std::vector<std::unique_ptr<compensation::CommandCompensator>> owned;
  std::unique_ptr<ExperimentalExchange> exchange;

  explicit Exchange(SetupGroup group, std::vector<CoordinatorLimits> dof_limits = {},
                    std::vector<RestoringForcePath> paths = {},
                    const compensation::CompensatorConfig& compensator = compensation::PassThroughParameters{}) {
    ExchangeParts parts;
    parts.link = &link;
    for (int c = 0; c < 2; ++c) {
      owned.push_back(compensation::make_compensator(compensator, 1.0 / 1024));
      parts.compensators.push_back(owned.back().get());
    }
    parts.force_paths = paths.empty() ? std::vector<RestoringForcePath>(2) : paths;
    parts.limits = std::move(dof_limits);
    parts.run_id = 7;
    group.channels = {0, 1};
    parts.setups.push_back(std::move(group));
    exchange = std::make_unique<ExperimentalExchange>(std::move(parts));
    const double zero[2] = {0.0, 0.0};
    exchange->start(Eigen::VectorXd::Zero(2), zero);
  }
  StepOutcome to(double x, double theta) {
    Eigen::VectorXd u(2);
    u << x, theta;
    return exchange->exchange(u, 0.0);
  }
};

SetupGroup group_of(setups::Geometry geometry) {
  SetupGroup g;
  g.geometry = two_actuators(geometry);
  return g;
}

TEST(SetupExchange, LinearSendsTheHandComputedStrokesAndReturnsTransposedJacobianForces) {
  Exchange e(group_of(setups::Geometry::kLinear));
  e.link.force_n[0] = 300.0;
  e.link.force_n[1] = -120.0;
  ASSERT_EQ(e.to(0.004, 0.003), StepOutcome::kOk);
  EXPECT_NEAR(e.link.sent.back().displacement_m[0], 0.004, 1e-15);
  EXPECT_NEAR(e.link.sent.back().displacement_m[1], 0.004 - kH * 0.003, 1e-15);
  EXPECT_NEAR(e.exchange->specimen_forces()[0], 300.0 - 120.0, 1e-12);
  EXPECT_NEAR(e.exchange->specimen_forces()[1], -kH * -120.0, 1e-12);
  StepRecord r;
  e.exchange->fill_channels(r);
  EXPECT_NEAR(r.dof_measured_m[0], 0.004, 1e-15);
  EXPECT_NEAR(r.dof_measured_m[1], 0.003, 1e-15);
  EXPECT_NEAR(r.measured_m[1], 0.004 - kH * 0.003, 1e-15);  // the actuator's stroke
  EXPECT_NEAR(r.dof_force_n[1], kH * 120.0, 1e-12);
  EXPECT_EQ(r.measured_force_n[1], -120.0);  // the load cell's
}

TEST(SetupExchange, LargeDisplacementStrokesAndForcesAtTheMeasuredConfiguration) {
  Exchange e(group_of(setups::Geometry::kLargeDisplacement));
  e.link.force_n[0] = 1000.0;
  e.link.force_n[1] = 2000.0;
  const double x = 0.03, theta = 0.2;  // large: s2 departs from the linear x - h θ by ~3 mm
  ASSERT_EQ(e.to(x, theta), StepOutcome::kOk);
  const double px = x - kH * std::sin(theta) + kL2, py = kH * std::cos(theta) - kH, l2 = std::hypot(px, py);
  EXPECT_NEAR(e.link.sent.back().displacement_m[0], x, 1e-14);
  EXPECT_NEAR(e.link.sent.back().displacement_m[1], l2 - kL2, 1e-14);
  EXPECT_GT(std::abs(l2 - kL2 - (x - kH * theta)), 1e-3);
  // J row 2: the unit vector along actuator 2 dotted with the point's motion along x and θ.
  const double ux = px / l2, uy = py / l2;
  const double j21 = ux, j22 = ux * (-kH * std::cos(theta)) + uy * (-kH * std::sin(theta));
  EXPECT_NEAR(e.exchange->specimen_forces()[0], 1000.0 + j21 * 2000.0, 1e-8);
  EXPECT_NEAR(e.exchange->specimen_forces()[1], j22 * 2000.0, 1e-8);
  StepRecord r;
  e.exchange->fill_channels(r);
  EXPECT_NEAR(r.dof_measured_m[0], x, 1e-12);
  EXPECT_NEAR(r.dof_measured_m[1], theta, 1e-12);
}

// The loop writes the channels' part of its row in place (RecordLayout::Row): unpacked, the
// row carries what fill_channels writes into a record, a setup's strokes and DOF view alike.
TEST(SetupExchange, ARowWrittenInPlaceCarriesTheChannelsAsARecordDoes) {
  Exchange e(group_of(setups::Geometry::kLargeDisplacement));
  e.link.force_n[0] = 1000.0;
  e.link.force_n[1] = 2000.0;
  ASSERT_EQ(e.to(0.03, 0.2), StepOutcome::kOk);
  const StepRecord got = expect_row_carries_the_record(*e.exchange);
  EXPECT_EQ(got.channels, 2);
  EXPECT_NE(got.measured_m[1], got.dof_measured_m[1]);  // the stroke and the rotation, each in its place
}

TEST(SetupExchange, CalibrationOffsetsAreAddedToCommandsAndTakenOffMeasurements) {
  SetupGroup g = group_of(setups::Geometry::kLinear);
  g.calibration_offset_m = {0.003, -0.001};
  Exchange e(g);
  ASSERT_EQ(e.to(0.004, 0.003), StepOutcome::kOk);
  EXPECT_NEAR(e.link.sent.back().displacement_m[0], 0.004 + 0.003, 1e-15);
  EXPECT_NEAR(e.link.sent.back().displacement_m[1], 0.004 - kH * 0.003 - 0.001, 1e-15);
  StepRecord r;
  e.exchange->fill_channels(r);
  EXPECT_NEAR(r.dof_measured_m[0], 0.004, 1e-15);
  EXPECT_NEAR(r.dof_measured_m[1], 0.003, 1e-15);
}

TEST(SetupExchange, AGeometryThatFailsStopsWithItsOwnOutcomeNamingTheSetup) {
  Exchange e(group_of(setups::Geometry::kLargeDisplacement));
  // Actuator 1 reads a stroke no configuration has: shorter than its own length allows.
  e.link.reading_shift[0] = -2.0 * kL1;
  EXPECT_EQ(e.to(0.001, 0.0), StepOutcome::kGeometry);
  const LimitStop& l = e.exchange->limit_stop();
  EXPECT_EQ(l.kind, LimitStop::Kind::kGeometry);
  EXPECT_EQ(l.setup, 0);
  EXPECT_EQ(std::string(l.name.data()), "site 1 setup");
  EXPECT_NE(describe_limit_stop(l).find("did not converge"), std::string::npos) << describe_limit_stop(l);
  EXPECT_EQ(e.link.sent.size(), 1u);
}

TEST(SetupExchange, AnActuatorsStrokeLimitActsOnItsStrokeNotOnTheDofs) {
  SetupGroup g = group_of(setups::Geometry::kLinear);
  g.actuator_limits.resize(2);
  g.actuator_limits[1].max_stroke_m = 0.015;
  Exchange e(g);
  // Both DOFs are small (x = 0, θ = -0.01 rad) but actuator 2's stroke is -h θ = 0.008 m... then 0.016.
  ASSERT_EQ(e.to(0.0, -0.01), StepOutcome::kOk);
  EXPECT_EQ(e.to(0.0, -0.02), StepOutcome::kLimit);
  const LimitStop& l = e.exchange->limit_stop();
  EXPECT_EQ(l.kind, LimitStop::Kind::kStroke);
  EXPECT_EQ(l.actuator, 1);
  EXPECT_EQ(l.dof, -1);
  EXPECT_NEAR(l.value, 0.016, 1e-15);
  EXPECT_EQ(std::string(l.name.data()), "site 1 actuator east");
  EXPECT_NE(describe_limit_stop(l).find("site 1 actuator east (channel 1): its stroke 0.016 m"), std::string::npos)
      << describe_limit_stop(l);
  EXPECT_EQ(e.link.sent.size(), 1u);  // the command beyond was not sent
}

TEST(SetupExchange, ADofsStrokeLimitActsOnTheDofNotOnTheActuators) {
  std::vector<CoordinatorLimits> dof(2);
  dof[1].max_stroke_m = 0.005;  // rad: the rotation's
  Exchange e(group_of(setups::Geometry::kLinear), dof);
  // θ = 0.004 rad within its 0.005, though actuator 2's stroke 0.01 - h 0.004 = 0.0068 m is not.
  ASSERT_EQ(e.to(0.01, 0.004), StepOutcome::kOk);
  EXPECT_EQ(e.to(0.01, 0.006), StepOutcome::kLimit);
  const LimitStop& l = e.exchange->limit_stop();
  EXPECT_EQ(l.dof, 1);
  EXPECT_EQ(l.actuator, -1);
  EXPECT_EQ(std::string(l.name.data()), "site 1 DOF rotation");
  EXPECT_NE(describe_limit_stop(l).find("site 1 DOF rotation (channel 1): its target 0.006 rad"), std::string::npos)
      << describe_limit_stop(l);
}

TEST(SetupExchange, ForceLimitsActOnTheLoadCellAndOnTheDofsForceInItsUnits) {
  {
    SetupGroup g = group_of(setups::Geometry::kLinear);
    g.actuator_limits.resize(2);
    g.actuator_limits[0].max_force_n = 50.0;
    Exchange e(g);
    e.link.force_n[0] = 60.0;
    EXPECT_EQ(e.to(0.001, 0.0), StepOutcome::kLimit);
    EXPECT_EQ(e.exchange->limit_stop().actuator, 0);
    EXPECT_EQ(e.exchange->limit_stop().value, 60.0);
  }
  {
    std::vector<CoordinatorLimits> dof(2);
    dof[1].max_force_n = 100.0;  // N·m about the control point
    Exchange e(group_of(setups::Geometry::kLinear), dof);
    e.link.force_n[0] = 1000.0;  // no moment: on the rotation's axis
    e.link.force_n[1] = -100.0;  // moment -h f2 = 80 N·m: within
    EXPECT_EQ(e.to(0.001, 0.0), StepOutcome::kOk);
    e.link.force_n[1] = -150.0;  // 120 N·m: beyond
    EXPECT_EQ(e.to(0.001, 0.0), StepOutcome::kLimit);
    const LimitStop& l = e.exchange->limit_stop();
    EXPECT_EQ(l.dof, 1);
    EXPECT_NEAR(l.value, 120.0, 1e-12);
    EXPECT_STREQ(l.unit, "N·m");
  }
}

TEST(SetupExchange, StiffnessTimesDisplacementUsesTheDofsMeasuredDisplacement) {
  std::vector<RestoringForcePath> paths(2);
  paths[0] = {RestoringForceSource::kStiffnessTimesMeasuredDisplacement, 2.0e5};
  paths[1] = {RestoringForceSource::kStiffnessTimesMeasuredDisplacement, 3.0e4};
  Exchange e(group_of(setups::Geometry::kLinear), {}, paths);
  ASSERT_EQ(e.to(0.004, 0.003), StepOutcome::kOk);
  EXPECT_NEAR(e.exchange->specimen_forces()[0], 2.0e5 * 0.004, 1e-9);
  EXPECT_NEAR(e.exchange->specimen_forces()[1], 3.0e4 * 0.003, 1e-9);
}

// A linear compensator commutes with linear geometry: compensating the DOFs' targets and then
// taking J of them sends what compensating each actuator's stroke J u sends.
TEST(SetupExchange, CompensationOnTheDofsOrOnTheActuatorsIsTheSameThroughLinearGeometry) {
  const compensation::CompensatorConfig extrapolation = compensation::PolynomialExtrapolationParameters{3, 0.01};
  SetupGroup on_dofs = group_of(setups::Geometry::kLinear), on_actuators = on_dofs;
  on_dofs.compensate_dofs = true;
  Exchange a(on_dofs, {}, {}, extrapolation), b(on_actuators, {}, {}, extrapolation);
  double lead = 0.0;
  for (int n = 1; n <= 200; ++n) {
    const double t = n / 1024.0, x = 0.01 * std::sin(2.0 * M_PI * 1.5 * t), theta = 0.004 * std::sin(2.0 * M_PI * t);
    ASSERT_EQ(a.to(x, theta), StepOutcome::kOk);
    ASSERT_EQ(b.to(x, theta), StepOutcome::kOk);
    for (int c = 0; c < 2; ++c) {
      EXPECT_NEAR(a.link.sent.back().displacement_m[c], b.link.sent.back().displacement_m[c], 1e-12);
    }
    lead = std::max(lead, std::abs(a.link.sent.back().displacement_m[0] - x));  // the extrapolation acts
  }
  EXPECT_GT(lead, 1e-4);
}

}  // namespace
}  // namespace rpsd::coordinator
