// One node implementation: a site's node runs the same controller in this process (behind the
// in-process link) as `rpsd servo-node` runs over DDS, so its limits act identically in a
// rehearsal and on the rig. The same velocity limit, tripped by the paper's SDOF in free
// vibration, aborts the node and stops the test at the same step with the same flags and the
// same measurements before it, both ways.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <optional>
#include <string>
#include <thread>

#include "../coordinator/specimen_runs.h"
#include "claimed_dds_domain.h"
#include "rpsd/hybrid_test/actuator_links.h"
#include "rpsd/node/servo_node_loop.h"
#include "rpsd/servo/simulated_actuator.h"
#include "rpsd/transport/messages.h"

namespace rpsd::hybrid_test {
namespace {

constexpr std::uint32_t kTest = 71;

transport::DdsDomainConfig loopback() {
  return {::rpsd::testing::claimed_dds_domain(), std::string(RPSD_TEST_SOURCE_DIR) + "/transport/config/loopback.xml"};
}

// The paper's SDOF released from 10 mm: its velocity peaks near 0.1 m/s, and the node lets
// the command move at most 0.03 m/s (abort).
TestConfig clamped_sdof() {
  SpecimenSdof sdof;
  sdof.duration_s = 2.0;
  sdof.plant = servo::PureDelayParameters{0.004, sdof.stiffness_n_per_m, 8192.0, {}, {}};
  TestConfig config = specimen_sdof_test(sdof);
  config.transport.test_id = kTest;
  node::ServoNodeConfig node;
  node.limits[0].max_velocity_m_per_s = 0.03;
  node.actions.velocity = node::LimitAction::kAbort;
  config.site_nodes[1] = node;
  return config;
}

// `rpsd servo-node` in lock-step, in a thread of this process: the same node configuration
// and plant as the in-process site.
class DdsNode {
 public:
  // `rest_m`: where the node's actuator starts (nullopt: the test's initial displacement);
  // `read_at_rest`: the node reads its plant at rest after start, as `rpsd servo-node` does.
  explicit DdsNode(const TestConfig& config, std::optional<double> rest_m = std::nullopt, bool read_at_rest = true)
      : plant_(servo::make_plant(config.plant)),
        participant_(loopback()),
        endpoint_(participant_, endpoint_config(config)) {
    servo::Plant* plants[] = {plant_.get()};
    actuator_ = std::make_unique<servo::SimulatedActuator>(plants);
    node::ServoNodeConfig c = config.site_nodes.at(1);
    c.test_id = config.transport.test_id;
    c.site_id = 1;
    c.channels = 1;
    c.control_period_s = 1.0 / config.control_rate_hz;
    controller_ = std::make_unique<node::ServoNodeController>(c, *actuator_);
    const double x0[] = {rest_m.value_or(config.initial_displacement_m[0])};
    controller_->start(x0);
    if (read_at_rest) controller_->note_reading_at_rest(actuator_->measure());
    thread_ = std::thread([this] {
      node::ServoNodeLoopOptions options;
      options.real_time = false;
      options.realtime.lock_memory = false;
      options.realtime.fifo_priority = 0;
      options.realtime.keep_cpus_awake = false;
      node::run_servo_node_loop(*controller_, endpoint_, options, stop_);
    });
  }
  ~DdsNode() {
    stop_ = true;
    thread_.join();
  }
  const node::ServoNodeController& controller() const { return *controller_; }
  servo::ActuatorReading plant_reading() const { return actuator_->measure(); }

 private:
  static transport::DdsNodeEndpointConfig endpoint_config(const TestConfig& config) {
    transport::DdsNodeEndpointConfig c;
    c.test_id = config.transport.test_id;
    c.site_id = 1;
    c.qos.control_period_s = 1.0 / config.control_rate_hz;
    return c;
  }
  std::unique_ptr<servo::Plant> plant_;
  std::unique_ptr<servo::SimulatedActuator> actuator_;
  transport::DdsParticipant participant_;
  transport::DdsNodeEndpoint endpoint_;
  std::unique_ptr<node::ServoNodeController> controller_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

TEST(SiteNode, AVelocityLimitTripsIdenticallyInProcessAndOverDds) {
  const TestConfig in_process = clamped_sdof();
  const coordinator::testing::SdofRun here = coordinator::testing::run_steps(in_process);
  // The node aborted on a command too fast: the test stopped on its fault.
  ASSERT_EQ(here.outcome, coordinator::StepOutcome::kNodeFault);
  EXPECT_GT(here.records.size(), 0u);

  TestConfig over_dds = in_process;
  over_dds.transport.kind = TransportConfig::Kind::kDds;
  over_dds.transport.domain_id = loopback().domain_id;
  over_dds.transport.dds_config = loopback().config_file;
  over_dds.clock.realtime.keep_cpus_awake = false;
  coordinator::testing::SdofRun there;
  std::uint64_t velocity_activations = 0;
  {
    DdsNode node(over_dds);
    there = coordinator::testing::run_steps(over_dds);
    velocity_activations = node.controller().counters().activations(node::LimitKind::kVelocity);
  }
  EXPECT_EQ(there.outcome, coordinator::StepOutcome::kNodeFault);
  EXPECT_EQ(velocity_activations, 1u);
  ASSERT_EQ(here.records.size(), there.records.size());
  for (std::size_t n = 0; n < here.records.size(); ++n) {
    ASSERT_EQ(here.records[n].measured_m[0], there.records[n].measured_m[0]) << n;
    ASSERT_EQ(here.records[n].limit_flags, there.records[n].limit_flags) << n;
  }

  // Without the node's limit the same test runs to its end.
  TestConfig free = in_process;
  free.site_nodes.clear();
  EXPECT_EQ(coordinator::testing::run_steps(free).outcome, coordinator::StepOutcome::kOk);
}

// Issue 30: over DDS a site's reading and force at rest are its node's measurements, from the
// heartbeat after the node is found: a node whose actuator rests 2 mm off the coordinator's
// hold gives its own reading and load cell, not the hold and the stiffness estimate. A node
// that has read nothing yet gives no reading (calibration not measured) and the estimate.
TEST(SiteNode, OverDdsTheReadingAndForceAtRestAreTheNodesMeasurements) {
  TestConfig config = clamped_sdof();
  config.transport.test_id = kTest + 2;  // not the other tests': ctest may run them at once
  config.site_nodes[1] = node::ServoNodeConfig{};
  config.transport.kind = TransportConfig::Kind::kDds;
  config.transport.domain_id = loopback().domain_id;
  config.transport.dds_config = loopback().config_file;
  config.clock.realtime.keep_cpus_awake = false;
  const double hold_m[] = {config.initial_displacement_m[0]};
  const double period_s = 1.0 / config.control_rate_hz;
  const double estimate_n = config.experimental[0].dof.specimen_stiffness_estimate_n_per_m * hold_m[0];
  {
    DdsNode node(config, hold_m[0] + 0.002);
    const servo::ActuatorReading at_rest = node.plant_reading();
    ASSERT_NE(at_rest.force_n[0], estimate_n);
    ActuatorLinks links(config, period_s, false, hold_m, transport::draw_run_id());
    ASSERT_TRUE(links.initial_reading_m(0).has_value());
    EXPECT_EQ(*links.initial_reading_m(0), at_rest.displacement_m[0]);
    EXPECT_NEAR(*links.initial_reading_m(0), hold_m[0] + 0.002, 1e-12);
    EXPECT_EQ(links.initial_force_n(0), at_rest.force_n[0]);
    EXPECT_TRUE(links.initial_force_measured(0));
  }
  {
    DdsNode node(config, hold_m[0] + 0.002, /*read_at_rest=*/false);
    ActuatorLinks links(config, period_s, false, hold_m, transport::draw_run_id());
    EXPECT_FALSE(links.initial_reading_m(0).has_value());
    EXPECT_EQ(links.initial_force_n(0), estimate_n);
    EXPECT_FALSE(links.initial_force_measured(0));
  }
}

// A site's node in this process knows its plant's converters: the SDOF released from 10 mm
// reads 8 mm on a displacement A/D whose rail is 8 mm (no limit file would pass the reader; this
// configuration is built by hand), and the node faults on that first reading, whatever the
// limits say. With a 20 mm rail the same test runs to its end.
TEST(SiteNode, AReadingOnItsConvertersRailFaultsTheNodeInThisProcess) {
  const auto run_with_rail = [](double rail_v) {
    SpecimenSdof sdof;
    sdof.duration_s = 0.5;
    servo::ChannelConverters converters;
    converters.displacement.units_per_volt = 1e-3;  // 1 mm/V
    converters.displacement.saturation_v = rail_v;
    sdof.plant = servo::PureDelayParameters{0.004, sdof.stiffness_n_per_m, 8192.0, {}, converters};
    return coordinator::testing::run_sdof(sdof);
  };
  const coordinator::testing::SdofRun railed = run_with_rail(8.0);
  EXPECT_EQ(railed.outcome, coordinator::StepOutcome::kNodeFault);
  EXPECT_TRUE(railed.records.empty());  // on the first exchange: no step was taken with it
  EXPECT_EQ(run_with_rail(20.0).outcome, coordinator::StepOutcome::kOk);
}

// One node, two runs of one test id (two coordinators): the node serves the run whose first
// command it took and says so in its heartbeat; a second run is refused before its first step
// with its own reason, never taking the first run's measurements for its own; the first goes
// on to its end, and once it has ended (its end of run) the node serves the next run.
TEST(SiteNode, ASecondRunOfOneTestIsRefusedWhileTheFirstRunsAndServedAfterIt) {
  TestConfig config = clamped_sdof();
  config.transport.test_id = kTest + 1;            // not the other test's: ctest may run both at once
  config.site_nodes[1] = node::ServoNodeConfig{};  // no limit acts: the run goes to its end
  config.transport.kind = TransportConfig::Kind::kDds;
  config.transport.domain_id = loopback().domain_id;
  config.transport.dds_config = loopback().config_file;
  config.clock.realtime.keep_cpus_awake = false;
  DdsNode node(config);
  TestAssembly first(config, {});
  ASSERT_EQ(first.step(), coordinator::StepOutcome::kOk);
  {
    TestAssembly second(config, {});
    EXPECT_NE(second.run_id(), first.run_id());
    EXPECT_EQ(second.step(), coordinator::StepOutcome::kRefused);
    const TestRun refused = second.finish(coordinator::StepOutcome::kRefused);
    EXPECT_EQ(refused.steps, 0);
    EXPECT_EQ(refused.refusal, "site 1 is serving another run (run " + transport::run_id_text(first.run_id()) +
                                   "; this run is " + transport::run_id_text(second.run_id()) +
                                   "): a node serves one run at a time");
  }
  for (std::int64_t n = 1; n < first.steps_planned(); ++n) ASSERT_EQ(first.step(), coordinator::StepOutcome::kOk) << n;
  const TestRun done = first.finish(coordinator::StepOutcome::kOk);
  EXPECT_EQ(done.steps, first.steps_planned());
  EXPECT_EQ(done.run_id, first.run_id());
  TestAssembly third(config, {});
  EXPECT_EQ(third.step(), coordinator::StepOutcome::kOk);
  third.finish(coordinator::StepOutcome::kOk);
  EXPECT_EQ(node.controller().counters().runs, 2u);
}

}  // namespace
}  // namespace rpsd::hybrid_test
