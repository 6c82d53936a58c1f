// The Speedgoat adapter: against a scripted target, the handshake vector by vector (each
// vector twice, newTarget lowered only once switchPC rose, a late handshake resumed and not
// restarted); against the emulated target over TCP and UDP, whole runs, the offsets of
// relative signals, a target that goes silent, malformed and oversized vectors, strangers'
// datagrams and a second client.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "rpsd/node/servo_node_controller.h"
#include "rpsd/node/speedgoat_actuator.h"
#include "rpsd/node/speedgoat_emulator.h"
#include "rpsd/node/tcp_stream.h"
#include "rpsd/scenarios/servo_parameters_file.h"
#include "rpsd/servo/servo_hydraulic_plant.h"
#include "speedgoat_test_link.h"

namespace rpsd::node {
namespace {

using speedgoat::get_double;
using speedgoat::put_double;
using testing::IdealTarget;
using testing::node_config;
using testing::ServingTarget;
using testing::target_config;

constexpr double kDt = 1.0 / 1024.0;
// How long the tests of a silent target let a handshake take: long enough that no answered
// move misses it on a loaded machine (a 20 ms timeout once counted an answered move as a
// missed reply: 3 no-replies, not 2), so that only the silence gives no reply. Each missed
// reply costs this long.
constexpr double kSilentTargetTimeoutS = 1.0;

// ---- A scripted target: the test plays the model's side by hand, one vector at a time. ----

// The node's side on its thread: what it throws fails the test instead of ending the process.
template <typename Body>
void guarded(Body body) {
  try {
    body();
  } catch (const std::exception& e) {
    ADD_FAILURE() << e.what();
  }
}

struct Script {
  TcpListener listener{Ipv4Endpoint::parse("127.0.0.1", 0, "test")};
  std::optional<TcpStream> stream;
  std::vector<std::byte> buffer = std::vector<std::byte>(256 * 8);

  // The next vector the node sent: {newTarget, first control signal}.
  std::array<double, 2> next() {
    EXPECT_EQ(stream->receive_exact(buffer, monotonic_seconds() + 10.0), TcpStream::Io::kDone);
    return {get_double(buffer, 0), get_double(buffer, 1)};
  }
  // Nothing more from the node for a moment (it waits for the target).
  bool quiet() {
    const double until = monotonic_seconds() + 0.05;
    while (monotonic_seconds() < until) {
      if (stream->readable_now()) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return true;
  }
  void send(double switch_pc, double at_target, double displacement_signal, double force_signal) {
    std::vector<std::byte> out(256 * 8);
    put_double(out, 0, switch_pc);
    put_double(out, 1, at_target);
    put_double(out, 2, displacement_signal);
    put_double(out, 3, force_signal);
    ASSERT_EQ(stream->send_all(out, monotonic_seconds() + 10.0), TcpStream::Io::kDone);
  }
};

TEST(SpeedgoatActuator, SpeaksTheHandshakeVectorByVector) {
  Script script;
  SpeedgoatActuator adapter(node_config(script.listener.port(), false));
  std::thread node([&] {
    guarded([&] {
      const double x0[] = {0.0};
      adapter.start(x0);
      const double command[] = {0.004};
      servo::ActuatorReading reading;
      EXPECT_EQ(adapter.exchange(command, kDt, reading), servo::ActuatorStatus::kOk);
      EXPECT_NEAR(reading.displacement_m[0], 0.004, 1e-15);
      EXPECT_NEAR(reading.force_n[0], 4e5, 1e-6);  // 400 signal units at 1e-3 per N
    });
  });
  script.stream = script.listener.accept(10.0);
  ASSERT_TRUE(script.stream);
  script.send(0, 1, 0.0, 0.0);  // at rest: the node's first acquire()
  // The offsets (none relative here: the initial command) go out twice with newTarget = 0.
  EXPECT_EQ(script.next(), (std::array<double, 2>{0.0, 0.0}));
  EXPECT_EQ(script.next(), (std::array<double, 2>{0.0, 0.0}));
  // Each handshake: newTarget = 1 twice, then nothing until switchPC rises; newTarget = 0
  // twice, then nothing until switchPC falls and atTarget is read from a later vector.
  for (const double signal : {0.0, 4.0}) {  // the first move (to the initial 0 m), then 4 mm
    EXPECT_EQ(script.next(), (std::array<double, 2>{1.0, signal}));
    EXPECT_EQ(script.next(), (std::array<double, 2>{1.0, signal}));
    EXPECT_TRUE(script.quiet()) << "newTarget lowered before switchPC rose";
    script.send(0, 1, 0.0, 0.0);  // a stale vector of the previous state: drained
    EXPECT_TRUE(script.quiet());
    script.send(1, 0, 0.0, 0.0);
    EXPECT_EQ(script.next(), (std::array<double, 2>{0.0, signal}));
    EXPECT_EQ(script.next(), (std::array<double, 2>{0.0, signal}));
    script.send(0, 1, signal, signal * 100.0);  // switchPC fell: this one's atTarget is not taken
    EXPECT_TRUE(script.quiet());
    script.send(0, 0, 9.0, 9.0);  // still moving: drained
    script.send(0, 1, signal, signal * 100.0);
  }
  node.join();
  EXPECT_EQ(adapter.counters().handshakes, 1u);
  EXPECT_EQ(adapter.counters().drained_vectors, 2u * 2u);  // two per handshake, the first move's included
  EXPECT_EQ(adapter.link_counters().vectors_sent, 2u + 4u * 2u);
}

TEST(SpeedgoatActuator, ResumesALateHandshakeInsteadOfStartingAnother) {
  Script script;
  auto config = node_config(script.listener.port(), false);
  // The first exchange waits this long for its late target; the second must get its answer
  // within it, from a script thread a loaded machine may hold back (50 ms once was too short).
  config.reply_timeout_s = 1.0;
  SpeedgoatActuator adapter(config);
  std::atomic<int> stage{0};
  std::vector<servo::ActuatorStatus> statuses;
  servo::ActuatorReading reading;
  std::thread node([&] {
    guarded([&] {
      const double x0[] = {0.0};
      adapter.start(x0);
      const double first[] = {0.002}, second[] = {0.003};
      statuses.push_back(adapter.exchange(first, kDt, reading));  // the target is late
      stage.store(1);
      while (stage.load() != 2) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      statuses.push_back(adapter.exchange(second, kDt, reading));  // finishes the first
    });
    stage.store(1);
  });
  script.stream = script.listener.accept(10.0);
  ASSERT_TRUE(script.stream);
  script.send(0, 1, 0.0, 0.0);
  script.next(), script.next();
  script.next(), script.next();
  script.send(1, 0, 0.0, 0.0);
  script.next(), script.next();
  script.send(0, 1, 0.0, 0.0);
  script.send(0, 1, 0.0, 0.0);  // start() done
  EXPECT_EQ(script.next(), (std::array<double, 2>{1.0, 2.0}));
  EXPECT_EQ(script.next(), (std::array<double, 2>{1.0, 2.0}));
  while (stage.load() != 1) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  script.send(1, 0, 0.0, 0.0);  // late: the node gave up on this period
  stage.store(2);
  // The next exchange lowers newTarget for the first command; it sends no new target.
  EXPECT_EQ(script.next(), (std::array<double, 2>{0.0, 2.0}));
  EXPECT_EQ(script.next(), (std::array<double, 2>{0.0, 2.0}));
  script.send(0, 0, 0.0, 0.0);
  script.send(0, 1, 2.0, 200.0);
  node.join();
  ASSERT_EQ(statuses.size(), 2u);
  EXPECT_EQ(statuses[0], servo::ActuatorStatus::kNoReply);
  EXPECT_EQ(statuses[1], servo::ActuatorStatus::kOk);
  EXPECT_NEAR(reading.displacement_m[0], 0.002, 1e-15);
  EXPECT_EQ(adapter.counters().resumed_handshakes, 1u);
  EXPECT_EQ(adapter.counters().missed_deadlines, 1u);
  EXPECT_TRUE(script.quiet());  // the second command was never sent
}

// ---- Against the emulated target. ----

void expect_whole_run(bool udp) {
  auto tc = target_config(udp, 2);
  IdealTarget target(tc);
  SpeedgoatActuator adapter(node_config(target.emulator->port(), udp, 2));
  const ServingTarget serving(*target.emulator);
  const double x0[] = {0.0, 0.0};
  adapter.start(x0);
  servo::ActuatorReading reading;
  const int steps = 300;
  for (int i = 1; i <= steps; ++i) {
    const double u[] = {0.02 * std::sin(2.0 * std::numbers::pi * 2.0 * i * kDt), -0.001 * i / steps};
    ASSERT_EQ(adapter.exchange(u, kDt, reading), servo::ActuatorStatus::kOk) << i;
    ASSERT_TRUE(reading.fresh);
    for (int c = 0; c < 2; ++c) {
      ASSERT_NEAR(reading.displacement_m[c], u[c], 1e-15) << i;
      ASSERT_NEAR(reading.force_n[c], 1e5 * u[c], 1e-9) << i;
    }
  }
  EXPECT_EQ(adapter.counters().handshakes, static_cast<std::uint64_t>(steps));
  EXPECT_EQ(adapter.counters().missed_deadlines, 0u);
  EXPECT_GT(adapter.counters().drained_vectors, 0u);  // the answers to the repeated vectors
  EXPECT_EQ(std::string(adapter.failed_side()), "none");
  const auto summary = adapter.link_summary();
  EXPECT_EQ(summary["transport"], udp ? "udp" : "tcp");
  EXPECT_EQ(summary["handshakes"], steps);
}

// Mixed control (issue 30): channel 1 in force control. Its force command reaches the target in
// the force slot the map declares, in the lab's scale, with its mode in the control_mode slot;
// the target's servo model holds the force on the paper's specimen.
TEST(SpeedgoatActuator, AForceChannelsCommandReachesTheTargetInItsForceSlot) {
  auto tc = target_config(false, 2);
  tc.control.push_back({1, "force", 1e-3});  // kN
  tc.control.push_back({1, "control_mode", 1.0});
  const char* env = std::getenv("RPSD_SOURCE_DIR");
  const std::filesystem::path dir = env != nullptr && *env != '\0' ? env : RPSD_TEST_SOURCE_DIR;
  auto rig = scenarios::load_servo_parameters(dir / "examples/servo/paper-mts-244.yaml");
  rig.controller.force_gain_v_per_n = 1e-5;
  servo::PureDelayPlant plant0({0.0, 1e5, 8192.0, {}});
  servo::ServoHydraulicPlant plant1(rig);
  servo::Plant* plants[] = {&plant0, &plant1};
  SpeedgoatEmulator target(plants, tc);
  const double zero[] = {0.0, 0.0};
  target.start(zero);

  auto config = node_config(target.port(), false, 2);
  config.rig = {0.25, 2e5, 1.0};
  config.signals.control.push_back({1, speedgoat::ControlQuantity::kForce, 1e-3, speedgoat::Reference::kAbsolute});
  config.signals.control.push_back({1, speedgoat::ControlQuantity::kControlMode, 1.0, speedgoat::Reference::kAbsolute});
  EXPECT_EQ(config.control_mode_refusal(1, servo::ControlMode::kForce), "");
  EXPECT_NE(config.control_mode_refusal(0, servo::ControlMode::kForce), "");
  EXPECT_NE(config.control_mode_refusal(1, servo::ControlMode::kDisplacement), "");
  SpeedgoatActuator adapter(config);
  EXPECT_TRUE(adapter.controls_force(1));
  EXPECT_FALSE(adapter.controls_force(0));
  const ServingTarget serving(target);
  adapter.start(zero);
  servo::ActuatorReading reading;
  const servo::ControlMode modes[] = {servo::ControlMode::kDisplacement, servo::ControlMode::kForce};
  for (int i = 1; i <= 2048; ++i) {
    const double x[] = {0.001, 0.0}, f[] = {0.0, 5000.0};
    ASSERT_EQ(adapter.exchange_mixed(x, f, modes, kDt, reading), servo::ActuatorStatus::kOk) << i;
  }
  EXPECT_EQ(target.force_target_n()[1], 5000.0);
  EXPECT_EQ(target.control_mode()[1], servo::ControlMode::kForce);
  EXPECT_EQ(target.control_mode()[0], servo::ControlMode::kDisplacement);
  EXPECT_NEAR(reading.displacement_m[0], 0.001, 1e-15);
  // Two seconds of the force loop (a time constant of ~0.7 s; tests/servo): on its way to 5 kN.
  EXPECT_GT(reading.force_n[1], 3000.0);
  EXPECT_LT(reading.force_n[1], 5000.0);
}

TEST(SpeedgoatActuator, FollowsCommandsOverTcp) { expect_whole_run(false); }
TEST(SpeedgoatActuator, FollowsCommandsOverUdp) { expect_whole_run(true); }

TEST(SpeedgoatActuator, EndsTheSessionTwiceWhenDestroyed) {
  IdealTarget target(target_config(false));
  {
    SpeedgoatActuator adapter(node_config(target.emulator->port(), false));
    const ServingTarget serving(*target.emulator);
    const double x0[] = {0.0};
    adapter.start(x0);
  }
  for (int i = 0; i < 20 && target.emulator->counters().vectors_received < 8; ++i) target.emulator->serve(0.05);
  EXPECT_EQ(target.emulator->counters().sessions_ended, 1u);
  EXPECT_EQ(target.emulator->counters().vectors_received, 2u + 4u + 2u);  // offsets, first move, -1 twice
}

// The transducers read 5 mm and 0.3 kN at rest (signal units); relative signals take that as zero.
void expect_offsets(bool udp) {
  auto tc = target_config(udp);
  tc.daq_offsets = {5.0, 0.3};
  IdealTarget target(tc);
  auto config = node_config(target.emulator->port(), udp);
  config.signals.control[0].reference = speedgoat::Reference::kRelative;
  config.signals.control[0].signal_per_si = 2000.0;  // another scale than the DAQ's: the offset converts
  config.signals.daq[0].reference = speedgoat::Reference::kRelative;
  config.signals.daq[1].reference = speedgoat::Reference::kRelative;
  tc.control[0].signal_per_si = 2000.0;
  IdealTarget scaled(tc);
  config.port = scaled.emulator->port();
  SpeedgoatActuator adapter(config);
  const ServingTarget serving(*scaled.emulator);
  const double x0[] = {0.0};
  adapter.start(x0);
  EXPECT_EQ(adapter.initial_daq(), (std::vector<double>{5.0, 0.3}));
  EXPECT_EQ(adapter.daq_offsets(), (std::vector<double>{-5.0, -0.3}));
  EXPECT_EQ(adapter.control_offsets(), (std::vector<double>{10.0}));  // 5 mm in the control's 2000/m
  servo::ActuatorReading reading;
  const double u[] = {0.01};
  ASSERT_EQ(adapter.exchange(u, kDt, reading), servo::ActuatorStatus::kOk);
  EXPECT_NEAR(reading.displacement_m[0], 0.01, 1e-15);
  EXPECT_NEAR(reading.force_n[0], 1e3, 1e-9);
  EXPECT_NEAR(scaled.emulator->reading().displacement_m[0], 0.01, 1e-15);  // the piston moved 10 mm, not 15
  const auto offsets = adapter.link_summary()["offsets"];
  EXPECT_EQ(offsets["control"], nlohmann::json::array({10.0}));
  EXPECT_EQ(offsets["daq"], nlohmann::json::array({-5.0, -0.3}));
  EXPECT_EQ(offsets["initial_daq"], nlohmann::json::array({5.0, 0.3}));
  EXPECT_NE(adapter.describe_link().find("DAQ at start [5, 0.3]"), std::string::npos) << adapter.describe_link();
}

TEST(SpeedgoatActuator, MeasuresAndRecordsTheOffsetsOfRelativeSignalsOverTcp) { expect_offsets(false); }
TEST(SpeedgoatActuator, MeasuresAndRecordsTheOffsetsOfRelativeSignalsOverUdp) { expect_offsets(true); }

TEST(SpeedgoatActuator, RefusesToStartWhereAnAbsoluteDaqSaysThePistonIsElsewhere) {
  auto tc = target_config(false);
  tc.daq_offsets = {5.0, 0.0};  // 5 mm read at rest, and the node's DAQ is absolute
  IdealTarget target(tc);
  SpeedgoatActuator adapter(node_config(target.emulator->port(), false));
  const ServingTarget serving(*target.emulator);
  const double x0[] = {0.0};
  try {
    adapter.start(x0);
    FAIL() << "started 5 mm away";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("measures 0.005 m (after offsets)"), std::string::npos) << e.what();
  }
  servo::ActuatorReading reading;
  EXPECT_EQ(adapter.exchange(x0, kDt, reading), servo::ActuatorStatus::kFault);  // not started: nothing sent
}

void expect_silent_target_faults(bool udp) {
  auto tc = target_config(udp);
  tc.silent_after_moves = 4;  // the first move at start, then three answered commands
  IdealTarget target(tc);
  auto config = node_config(target.emulator->port(), udp);
  config.reply_timeout_s = kSilentTargetTimeoutS;
  config.max_missed_replies = 3;
  SpeedgoatActuator adapter(config);
  const ServingTarget serving(*target.emulator);
  const double x0[] = {0.0};
  adapter.start(x0);
  std::vector<servo::ActuatorStatus> statuses;
  servo::ActuatorReading reading;
  const double hang_guard_s = monotonic_seconds() + 30.0;
  for (int i = 1; i <= 10 && monotonic_seconds() < hang_guard_s; ++i) {
    const double u[] = {0.001 * i};
    statuses.push_back(adapter.exchange(u, kDt, reading));
  }
  using S = servo::ActuatorStatus;
  const std::vector<S> expected{S::kOk,      S::kOk,    S::kOk,    S::kNoReply, S::kNoReply,
                                S::kNoReply, S::kFault, S::kFault, S::kFault,   S::kFault};
  EXPECT_EQ(statuses, expected);
  EXPECT_NEAR(reading.displacement_m[0], 0.003, 1e-15);  // the last measurement stands
  EXPECT_EQ(std::string(adapter.failed_side()), "target");
  EXPECT_EQ(adapter.link_summary()["failed_side"], "target");
  EXPECT_EQ(adapter.counters().missed_deadlines, 4u);
  EXPECT_EQ(adapter.counters().resumed_handshakes, 3u);
}

TEST(SpeedgoatActuator, ATargetThatGoesSilentGivesNoReplyThenALatchedFaultOverTcp) {
  expect_silent_target_faults(false);
}
TEST(SpeedgoatActuator, ATargetThatGoesSilentGivesNoReplyThenALatchedFaultOverUdp) {
  expect_silent_target_faults(true);
}

// The node behind the adapter: commands stop being applied and the node is latched in fault.
TEST(SpeedgoatActuator, TheNodeLatchesItsFaultWhenTheTargetGoesSilent) {
  auto tc = target_config(false);
  tc.silent_after_moves = 3;
  IdealTarget target(tc);
  auto config = node_config(target.emulator->port(), false);
  config.reply_timeout_s = kSilentTargetTimeoutS;
  config.max_missed_replies = 2;
  SpeedgoatActuator adapter(config);
  ServoNodeConfig nc;
  nc.test_id = 1;
  nc.site_id = 1;
  nc.channels = 1;
  nc.control_period_s = kDt;
  nc.command_timeout_periods = 1000;
  ServoNodeController node(nc, adapter);
  const ServingTarget serving(*target.emulator);
  const double x0[] = {0.0};
  node.start(x0);
  transport::CommandSample command{.test_id = 1, .site_id = 1, .run_id = 7, .channels = 1};
  transport::FeedbackSample feedback;
  for (int i = 1; i <= 8; ++i) {
    command.step = i;
    command.time_s = i * kDt;
    command.displacement_m[0] = 1e-4 * i;
    node.accept(command);
    node.tick(feedback);
  }
  EXPECT_TRUE(node.faulted());
  EXPECT_EQ(node.counters().actuator_no_replies, 2u);
  EXPECT_GE(node.counters().actuator_faults, 1u);
  EXPECT_EQ(std::string(adapter.failed_side()), "target");
  // A hang guard, not a measured time: until newTarget = -1 has reached the target.
  const double hang_guard_s = monotonic_seconds() + 30.0;
  while (target.emulator->counters().sessions_ended == 0 && monotonic_seconds() < hang_guard_s)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(target.emulator->counters().sessions_ended, 1u);  // newTarget = -1 reached the target
}

// The lab's model measures in tenths of a millimetre where the node file says millimetres: the
// node reads ten times the piston's displacement, and the first reading beyond the rig's
// stroke faults the node, whatever commanded it.
TEST(SpeedgoatActuator, AMeasurementBeyondTheRigFaultsTheNode) {
  auto tc = target_config(false);
  tc.daq[0].signal_per_si = 10000.0;
  IdealTarget target(tc);
  SpeedgoatActuator adapter(node_config(target.emulator->port(), false));
  ServoNodeConfig nc;
  nc.test_id = 1;
  nc.site_id = 1;
  nc.channels = 1;
  nc.control_period_s = kDt;
  nc.rig[0] = {0.01, 1e6, 1.0};  // a 10 mm stroke
  ServoNodeController node(nc, adapter);
  const ServingTarget serving(*target.emulator);
  const double x0[] = {0.0};
  node.start(x0);
  transport::CommandSample command{.test_id = 1, .site_id = 1, .run_id = 9, .channels = 1};
  transport::FeedbackSample feedback;
  int faulted_at = 0;
  for (int i = 1; i <= 20 && faulted_at == 0; ++i) {
    command.step = i;
    command.time_s = i * kDt;
    command.displacement_m[0] = 2e-4 * i;  // reaches 1 mm at step 5: the node reads 10 mm
    node.accept(command);
    node.tick(feedback);
    if (node.faulted()) faulted_at = i;
  }
  EXPECT_EQ(faulted_at, 5);  // 1 mm commanded, 10 mm read: at the stroke
  EXPECT_NE(feedback.status & transport::kNodeFault, 0u);
  EXPECT_EQ(std::string(adapter.failed_side()), "none");  // the link is fine; the measurement is not
}

TEST(SpeedgoatActuator, AMalformedVectorFaultsTheLink) {
  for (const bool udp : {false, true}) {
    auto tc = target_config(udp);
    tc.malformed_at_move = 3;  // a NaN displacement in the second command's at-target vector
    IdealTarget target(tc);
    SpeedgoatActuator adapter(node_config(target.emulator->port(), udp));
    const ServingTarget serving(*target.emulator);
    const double x0[] = {0.0}, u[] = {0.001};
    adapter.start(x0);
    servo::ActuatorReading reading;
    EXPECT_EQ(adapter.exchange(u, kDt, reading), servo::ActuatorStatus::kOk) << udp;
    EXPECT_EQ(adapter.exchange(u, kDt, reading), servo::ActuatorStatus::kFault) << udp;
    EXPECT_FALSE(reading.fresh);
    EXPECT_EQ(adapter.counters().malformed_vectors, 1u);
    EXPECT_EQ(std::string(adapter.failed_side()), "target");
    EXPECT_EQ(adapter.exchange(u, kDt, reading), servo::ActuatorStatus::kFault) << "latched";
  }
}

TEST(SpeedgoatActuator, AnOversizedDatagramIsDroppedAndAnOversizedTcpVectorFaults) {
  for (const bool udp : {true, false}) {
    auto tc = target_config(udp);
    tc.oversized_at_move = 2;  // the first command's at-target vector is one double longer
    IdealTarget target(tc);
    SpeedgoatActuator adapter(node_config(target.emulator->port(), udp));
    const ServingTarget serving(*target.emulator);
    const double x0[] = {0.0};
    adapter.start(x0);
    servo::ActuatorReading reading;
    servo::ActuatorStatus status = servo::ActuatorStatus::kOk;
    for (int i = 1; i <= 5 && status == servo::ActuatorStatus::kOk; ++i) {
      const double u[] = {0.001 * i};
      status = adapter.exchange(u, kDt, reading);
      if (status == servo::ActuatorStatus::kOk) {
        EXPECT_NEAR(reading.displacement_m[0], u[0], 1e-15);
      }
    }
    if (udp) {  // a datagram of the wrong size is counted and dropped; the next vector carries on
      EXPECT_EQ(status, servo::ActuatorStatus::kOk);
      EXPECT_EQ(adapter.link_counters().bad_packets, 1u);
    } else {  // on a stream the extra double shifts every later vector: their flags are garbage
      EXPECT_EQ(status, servo::ActuatorStatus::kFault);
      EXPECT_EQ(adapter.counters().malformed_vectors, 1u);
      EXPECT_EQ(std::string(adapter.failed_side()), "target");
    }
  }
}

TEST(SpeedgoatActuator, StrangersDatagramsAreDroppedByBothSides) {
  IdealTarget target(target_config(true));
  SpeedgoatActuator adapter(node_config(target.emulator->port(), true));
  const ServingTarget serving(*target.emulator);
  const double x0[] = {0.0};
  adapter.start(x0);
  UdpSocket stranger(Ipv4Endpoint::parse("127.0.0.1", 0, "test"));
  std::vector<std::byte> forged(256 * 8);
  put_double(forged, 0, 1.0);  // to the target: newTarget = 1 toward 0.2 m
  put_double(forged, 1, 200.0);
  const std::byte hello[1] = {std::byte{'a'}};
  std::vector<std::byte> reply(256 * 8);  // to the node: at target, at 0.1 m
  put_double(reply, 1, 1.0);
  put_double(reply, 2, 100.0);
  servo::ActuatorReading reading;
  for (int i = 1; i <= 50; ++i) {
    if (i % 10 == 0) {
      stranger.send_to(hello, Ipv4Endpoint::parse("127.0.0.1", target.emulator->port(), "t"));
      stranger.send_to(forged, Ipv4Endpoint::parse("127.0.0.1", target.emulator->port(), "t"));
      stranger.send_to(reply, Ipv4Endpoint::parse("127.0.0.1", adapter.local_port(), "n"));
    }
    const double u[] = {0.0001 * i};
    ASSERT_EQ(adapter.exchange(u, kDt, reading), servo::ActuatorStatus::kOk) << i;
    ASSERT_NEAR(reading.displacement_m[0], u[0], 1e-15) << i;
  }
  EXPECT_EQ(adapter.link_counters().foreign_datagrams, 5u);
  for (int i = 0; i < 40 && target.emulator->counters().foreign_datagrams < 10; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(target.emulator->counters().foreign_datagrams, 10u);
  EXPECT_NEAR(target.emulator->reading().displacement_m[0], 0.005, 1e-15);
}

TEST(SpeedgoatActuator, TheTargetRefusesASecondClientAndOneFromAnotherAddress) {
  IdealTarget target(target_config(false));
  SpeedgoatActuator adapter(node_config(target.emulator->port(), false));
  const ServingTarget serving(*target.emulator);
  const double x0[] = {0.0};
  adapter.start(x0);
  const Ipv4Endpoint emulator = Ipv4Endpoint::parse("127.0.0.1", target.emulator->port(), "t");
  TcpStream second = TcpStream::connect(emulator, Ipv4Endpoint::parse("127.0.0.1", 0, "t"), 5.0);
  TcpStream elsewhere = TcpStream::connect(emulator, Ipv4Endpoint::parse("127.0.0.2", 0, "t"), 5.0);
  servo::ActuatorReading reading;
  for (int i = 1; i <= 50; ++i) {
    const double u[] = {0.0001 * i};
    ASSERT_EQ(adapter.exchange(u, kDt, reading), servo::ActuatorStatus::kOk) << i;
  }
  std::array<std::byte, 8> nothing{};
  EXPECT_EQ(second.receive_exact(nothing, monotonic_seconds() + 5.0), TcpStream::Io::kClosed);
  EXPECT_EQ(elsewhere.receive_exact(nothing, monotonic_seconds() + 5.0), TcpStream::Io::kClosed);
  EXPECT_EQ(target.emulator->counters().refused_clients, 2u);
  EXPECT_EQ(target.emulator->counters().sessions, 1u);
}

// The node may start before the target's model listens: it asks again until start_timeout_s.
TEST(SpeedgoatActuator, StartWaitsForATargetThatIsNotListeningYet) {
  std::uint16_t port = 0;
  {
    const TcpListener probe(Ipv4Endpoint::parse("127.0.0.1", 0, "test"));
    port = probe.port();  // free once the probe is gone
  }
  SpeedgoatActuator adapter(node_config(port, false));
  std::atomic<bool> started{false};
  std::thread node([&] {
    guarded([&] {
      const double x0[] = {0.0};
      adapter.start(x0);
      started.store(true);
    });
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // refused meanwhile
  auto tc = target_config(false);
  tc.port = port;
  IdealTarget target(tc);
  {
    const ServingTarget serving(*target.emulator);
    node.join();
  }
  EXPECT_TRUE(started.load());
  EXPECT_EQ(target.emulator->counters().sessions, 1u);
}

TEST(SpeedgoatActuator, StartFailsClearlyWhenNoTargetListens) {
  auto config = node_config(1, false);  // nothing listens on port 1
  config.start_timeout_s = 0.5;
  SpeedgoatActuator adapter(config);
  const double x0[] = {0.0};
  EXPECT_THROW(adapter.start(x0), std::runtime_error);
}

TEST(SpeedgoatParameters, RefusesAMapWithoutAForceSignalOrWithARelativeVelocity) {
  auto config = node_config(5000, false);
  config.signals.daq.pop_back();
  EXPECT_THROW(config.validate(), std::invalid_argument);
  config = node_config(5000, false);
  config.signals.control.push_back({0, speedgoat::ControlQuantity::kVelocity, 1.0, speedgoat::Reference::kRelative});
  EXPECT_THROW(config.validate(), std::invalid_argument);
  config = node_config(5000, false);
  config.signals.vector_doubles = 3;  // no room for two DAQ signals and the flags
  EXPECT_THROW(config.validate(), std::invalid_argument);
}

TEST(SpeedgoatSignals, VelocityAccelerationAndTimeAreTheCommandsFiniteDifferences) {
  Script script;
  auto config = node_config(script.listener.port(), false);
  config.signals.control.push_back({0, speedgoat::ControlQuantity::kVelocity, 1.0, speedgoat::Reference::kAbsolute});
  config.signals.control.push_back(
      {0, speedgoat::ControlQuantity::kAcceleration, 1.0, speedgoat::Reference::kAbsolute});
  config.signals.control.push_back({0, speedgoat::ControlQuantity::kTime, 1.0, speedgoat::Reference::kAbsolute});
  SpeedgoatActuator adapter(config);
  std::thread node([&] {
    guarded([&] {
      const double x0[] = {0.0};
      adapter.start(x0);
      servo::ActuatorReading reading;
      const double a[] = {0.001}, b[] = {0.003};
      adapter.exchange(a, 0.5, reading);
      adapter.exchange(b, 0.5, reading);
    });
  });
  script.stream = script.listener.accept(10.0);
  ASSERT_TRUE(script.stream);
  auto handshake = [&](std::array<double, 4> expected) {
    for (int copy = 0; copy < 2; ++copy) {
      script.next();
      for (int k = 0; k < 4; ++k) EXPECT_NEAR(get_double(script.buffer, 1 + k), expected[k], 1e-15) << k;
    }
    script.send(1, 0, 0.0, 0.0);
    script.next(), script.next();
    script.send(0, 0, 0.0, 0.0);
    script.send(0, 1, expected[0], 0.0);
  };
  script.send(0, 1, 0.0, 0.0);
  script.next(), script.next();
  handshake({0.0, 0.0, 0.0, 0.0});
  handshake({1.0, 0.002, 0.004, 0.5});  // (1 mm - 0) / 0.5 s; (0.002 - 0) / 0.5 s; t = 0.5 s
  handshake({3.0, 0.004, 0.004, 1.0});
  node.join();
}

}  // namespace
}  // namespace rpsd::node
