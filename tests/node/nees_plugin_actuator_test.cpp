// The plugin adapter against the plugin site emulator over 127.0.0.1, and against a scripted
// site that answers canned lines: it follows the site step by step in the site's units; the
// lines it sends are OpenFresco's, written by hand here; a refused proposal, a site that stops
// answering, garbage, oversized and wrong-transaction answers and a missing channel each latch
// a fault that names the site's side and keeps its words; a second client and a stranger are
// turned away by the site while its session goes on.
#include <gtest/gtest.h>

#include <cmath>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "nees_plugin_test_site.h"
#include "rpsd/node/nees_plugin_actuator.h"
#include "rpsd/node/tcp_stream.h"

namespace rpsd::node {
namespace {

using nees_plugin::Axis;
using nees_plugin::Motion;
using servo::ActuatorStatus;
using testing::EmulatedSite;
using testing::mdl_x_in_mm_and_kn;
using testing::one_point_site;
using testing::plugin_adapter_config;
using testing::ServingSite;

// 11 significant digits on the wire (%.10E).
constexpr double kWireRelative = 1e-10;

// A site of one control point in mm and kN served on its own thread, and an adapter in session
// with it.
struct InSession {
  explicit InSession(const PluginSiteConfig& config, double reply_timeout_s = 10.0)
      : site(config), serving(site.emulator()), adapter(adapter_config(site, reply_timeout_s)) {
    const double x0[] = {0.0};
    adapter.start(x0);
  }
  static NeesPluginParameters adapter_config(EmulatedSite& site, double reply_timeout_s) {
    NeesPluginParameters p = plugin_adapter_config(site.emulator(), mdl_x_in_mm_and_kn());
    p.reply_timeout_s = reply_timeout_s;
    return p;
  }
  EmulatedSite site;
  ServingSite serving;
  NeesPluginActuator adapter;
};

TEST(NeesPluginActuator, FollowsTheSiteStepByStepInTheSitesUnits) {
  EmulatedSite site(one_point_site());
  const ServingSite serving(site.emulator());
  {
    NeesPluginActuator adapter(plugin_adapter_config(site.emulator(), mdl_x_in_mm_and_kn()));
    const double x0[] = {0.0};
    adapter.start(x0);
    servo::ActuatorReading r;
    for (int i = 1; i <= 200; ++i) {
      const double u[] = {0.02 * std::sin(2.0 * std::numbers::pi * i / 100.0)};
      ASSERT_EQ(adapter.exchange(u, 0.01, r), ActuatorStatus::kOk) << i;
      ASSERT_TRUE(r.fresh);
      // The site moved u[0] (in mm on the wire) and its spring pushes back 700.8 kN/m (in kN).
      ASSERT_NEAR(r.displacement_m[0], u[0], kWireRelative * 0.02) << i;
      ASSERT_NEAR(r.force_n[0], 700.8e3 * u[0], kWireRelative * 700.8e3 * 0.02) << i;
    }
    EXPECT_EQ(adapter.counters().proposals, 201u);  // the start's step and 200
    EXPECT_EQ(adapter.counters().executes, 201u);
    EXPECT_EQ(adapter.counters().readings, 201u);
    EXPECT_EQ(adapter.failed_side(), "none");
    const nlohmann::json summary = adapter.link_summary();
    EXPECT_EQ(summary["steps"], 201);
    EXPECT_EQ(summary["failure"], "none");
    EXPECT_EQ(adapter.summary_key(), "plugin_link");
  }
  // The adapter's end closed the session (close-session, answered).
  EXPECT_EQ(site.emulator().counters().executes, 201u);
  EXPECT_EQ(site.emulator().counters().sessions, 1u);
  EXPECT_EQ(site.emulator().counters().readings, 201u);
}

TEST(NeesPluginActuator, ChannelsSharingAControlPointAndARotationEachTakeTheirOwnValues) {
  PluginSiteConfig config;
  config.control_points = {{"LBCB1", {{"x", "translation", -1, 1, 1, 1}, {"y", "translation", -1, 1, 1, 1}}},
                           {"LBCB2", {{"z", "rotation", -1, 1, 1, 1}}}};
  // Three springs of their own, so that a channel reading another's force shows.
  EmulatedSite site(config, {1.0e5, 2.0e5, 3.0e5});
  const ServingSite serving(site.emulator());
  // The node's channels in another order than the site's dofs.
  NeesPluginActuator adapter(plugin_adapter_config(site.emulator(), {{"LBCB2", Axis::kZ, Motion::kRotation, 1, 1},
                                                                     {"LBCB1", Axis::kY, Motion::kTranslation, 1, 1},
                                                                     {"LBCB1", Axis::kX, Motion::kTranslation, 1, 1}}));
  const double x0[] = {0.0, 0.0, 0.0};
  adapter.start(x0);
  servo::ActuatorReading r;
  const double u[] = {0.003, -0.02, 0.01};
  ASSERT_EQ(adapter.exchange(u, 0.01, r), ActuatorStatus::kOk);
  EXPECT_NEAR(r.displacement_m[0], 0.003, 1e-12);
  EXPECT_NEAR(r.force_n[0], 3.0e5 * 0.003, 1e-6);  // LBCB2 z: the third dof's spring
  EXPECT_NEAR(r.displacement_m[1], -0.02, 1e-12);
  EXPECT_NEAR(r.force_n[1], 2.0e5 * -0.02, 1e-6);  // LBCB1 y
  EXPECT_NEAR(r.displacement_m[2], 0.01, 1e-12);
  EXPECT_NEAR(r.force_n[2], 1.0e5 * 0.01, 1e-6);  // LBCB1 x
  EXPECT_EQ(adapter.counters().readings, 4u);     // two control points a step
}

TEST(NeesPluginActuator, ARefusedProposalLatchesAFaultWithTheSitesOwnWords) {
  PluginSiteConfig config = one_point_site();
  config.control_points[0].dofs[0].lower_limit = -5.0;  // mm
  config.control_points[0].dofs[0].upper_limit = 5.0;
  InSession session(config);
  NeesPluginActuator& adapter = session.adapter;
  EmulatedSite& site = session.site;
  servo::ActuatorReading r;
  const double inside[] = {0.004};
  ASSERT_EQ(adapter.exchange(inside, 0.01, r), ActuatorStatus::kOk);
  const double beyond[] = {0.006};
  EXPECT_EQ(adapter.exchange(beyond, 0.01, r), ActuatorStatus::kFault);
  EXPECT_FALSE(r.fresh);
  EXPECT_EQ(r.displacement_m[0], 0.004);  // the last measurement stays
  EXPECT_EQ(adapter.failure(), NeesPluginFailure::kRefused);
  EXPECT_EQ(adapter.failed_side(), "site");
  const std::string words(adapter.site_message());
  EXPECT_EQ(words.rfind("ERROR\t", 0), 0u) << words;
  EXPECT_NE(words.find("MDL-00-01 x displacement 6.0000000000E+00 is beyond the site's limit 5.0000000000E+00"),
            std::string::npos)
      << words;
  EXPECT_EQ(words, site.emulator().last_refusal());  // verbatim
  // Latched: nothing more is sent, not even an in-limit step.
  EXPECT_EQ(adapter.exchange(inside, 0.01, r), ActuatorStatus::kFault);
  EXPECT_EQ(adapter.counters().proposals, 3u);
  EXPECT_EQ(adapter.counters().refusals, 1u);
  const nlohmann::json summary = adapter.link_summary();
  EXPECT_EQ(summary["failed_side"], "site");
  EXPECT_EQ(summary["failure"], "refused");
  EXPECT_EQ(summary["failed_stage"], "propose");
  EXPECT_EQ(summary["site_message"], words);
  EXPECT_EQ(site.emulator().counters().executes, 2u);  // the start's step and the one inside
}

TEST(NeesPluginActuator, ASiteThatStopsAnsweringFaultsAtTheDeadlineAndNothingMoves) {
  PluginSiteConfig config = one_point_site();
  config.fault = PluginSiteFault::kStopAnswering;
  config.fault_after_steps = 3;  // the start's step and two more
  InSession session(config, 0.3);
  NeesPluginActuator& adapter = session.adapter;
  servo::ActuatorReading r;
  const double u[] = {0.001};
  ASSERT_EQ(adapter.exchange(u, 0.01, r), ActuatorStatus::kOk);
  ASSERT_EQ(adapter.exchange(u, 0.01, r), ActuatorStatus::kOk);
  const double before_s = monotonic_seconds();
  const double next[] = {0.002};
  EXPECT_EQ(adapter.exchange(next, 0.01, r), ActuatorStatus::kFault);
  EXPECT_GE(monotonic_seconds() - before_s, 0.01 + 0.3);  // not before its deadline
  EXPECT_FALSE(r.fresh);
  EXPECT_EQ(r.displacement_m[0], 0.001);  // the known state: the last measurement
  EXPECT_EQ(adapter.failure(), NeesPluginFailure::kTimeout);
  EXPECT_EQ(adapter.failed_side(), "site");
  EXPECT_EQ(adapter.link_summary()["failed_stage"], "propose");
  EXPECT_EQ(adapter.counters().timeouts, 1u);
  EXPECT_EQ(adapter.exchange(next, 0.01, r), ActuatorStatus::kFault);  // latched, at once
  EXPECT_EQ(adapter.counters().timeouts, 1u);
  EXPECT_EQ(session.site.emulator().counters().executes, 3u);  // never executed
}

struct BadAnswer {
  PluginSiteFault fault;
  NeesPluginFailure failure;
  const char* words;  // in the kept site message
};

class NeesPluginBadAnswer : public ::testing::TestWithParam<BadAnswer> {};

TEST_P(NeesPluginBadAnswer, LatchesAFaultNamingTheSite) {
  PluginSiteConfig config = one_point_site();
  config.fault = GetParam().fault;
  config.fault_after_steps = 2;
  InSession session(config);
  NeesPluginActuator& adapter = session.adapter;
  servo::ActuatorReading r;
  const double u[] = {0.001}, v[] = {0.002};
  ASSERT_EQ(adapter.exchange(u, 0.01, r), ActuatorStatus::kOk);
  EXPECT_EQ(adapter.exchange(v, 0.01, r), ActuatorStatus::kFault);
  EXPECT_FALSE(r.fresh);
  EXPECT_EQ(r.displacement_m[0], 0.001);  // nothing of the bad answer taken
  EXPECT_EQ(adapter.failure(), GetParam().failure);
  EXPECT_EQ(adapter.failed_side(), "site");
  EXPECT_EQ(adapter.link_summary()["failed_stage"], "get-control-point");
  EXPECT_NE(std::string(adapter.site_message()).find(GetParam().words), std::string::npos) << adapter.site_message();
  EXPECT_EQ(adapter.exchange(u, 0.01, r), ActuatorStatus::kFault);
}

INSTANTIATE_TEST_SUITE_P(
    EveryKind, NeesPluginBadAnswer,
    ::testing::Values(BadAnswer{PluginSiteFault::kGarbage, NeesPluginFailure::kMalformed, "#garbage#"},
                      BadAnswer{PluginSiteFault::kOverlong, NeesPluginFailure::kOverlong, ""},
                      BadAnswer{PluginSiteFault::kWrongTransaction, NeesPluginFailure::kWrongTransaction,
                                "MDL-00-01\tx\tdisplacement\t2.0000000000E+00"}));

TEST(NeesPluginActuator, ASecondClientIsTurnedAwayWhileTheSessionGoesOn) {
  InSession session(one_point_site());
  EmulatedSite& site = session.site;
  const Ipv4Endpoint at = Ipv4Endpoint::parse("127.0.0.1", site.emulator().port(), "site");
  TcpStream second = TcpStream::connect(at, Ipv4Endpoint::parse("127.0.0.1", 0, "local"), 5.0);
  std::array<char, 512> line{};
  std::size_t size = 0;
  ASSERT_EQ(second.receive_line(line, size, monotonic_seconds() + 10.0), TcpStream::Io::kDone);
  const std::string words(line.data(), size);
  EXPECT_EQ(words.rfind("ERROR\t", 0), 0u) << words;
  EXPECT_NE(words.find("one session at a time"), std::string::npos) << words;
  EXPECT_EQ(second.receive_line(line, size, monotonic_seconds() + 10.0), TcpStream::Io::kClosed);
  servo::ActuatorReading r;
  const double u[] = {0.003};
  ASSERT_EQ(session.adapter.exchange(u, 0.01, r), ActuatorStatus::kOk);  // the session goes on
  EXPECT_NEAR(r.displacement_m[0], 0.003, 1e-12);
  EXPECT_EQ(site.emulator().counters().refused_clients, 1u);
  EXPECT_EQ(site.emulator().counters().sessions, 1u);
}

// Why the adapter's start against the site failed ("started" when it did not).
std::string start_failure(EmulatedSite& site) {
  const ServingSite serving(site.emulator());
  NeesPluginActuator adapter(plugin_adapter_config(site.emulator(), mdl_x_in_mm_and_kn()));
  const double x0[] = {0.0};
  try {
    adapter.start(x0);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "started";
}

TEST(NeesPluginActuator, AStartTheSiteRefusesThrowsWithTheSitesWords) {
  PluginSiteConfig config = one_point_site();
  config.node_host = "127.0.0.2";  // the site serves another node
  EmulatedSite site(config);
  const std::string why = start_failure(site);
  EXPECT_NE(why.find("open-session"), std::string::npos) << why;
  EXPECT_NE(why.find("this site serves its node only"), std::string::npos) << why;
  EXPECT_EQ(site.emulator().counters().foreign_clients, 1u);
  EXPECT_EQ(site.emulator().counters().sessions, 0u);
}

TEST(NeesPluginActuator, StartRefusesASiteThatDoesNotStandAtTheInitialDisplacement) {
  // The site's actuator lags 0.5 s behind a 0.01 s step: after the start's step it still
  // stands at 8 mm, where it began, not at the node's 0.
  EmulatedSite site(one_point_site(), {}, 0.5);
  const double at_8_mm[] = {0.008};
  site.emulator().start(at_8_mm);
  const std::string why = start_failure(site);
  EXPECT_NE(why.find("channel 0 (MDL-00-01 x) measures 0.008 m"), std::string::npos) << why;
  EXPECT_NE(why.find("start_tolerance_m 0.001"), std::string::npos) << why;
}

// The n-th tab-separated field of a line.
std::string field(const std::string& line, int n) {
  std::size_t begin = 0;
  for (int i = 0; i < n; ++i) begin = line.find('\t', begin) + 1;
  return line.substr(begin, line.find_first_of("\t\n", begin) - begin);
}

// A site that answers get-control-point with "OK\t0\t<transaction>" and `reading`,
// open-session with `open_answer` and OK to the rest, and keeps the lines it read.
class ScriptedSite {
 public:
  explicit ScriptedSite(std::string reading, std::string open_answer = "OK\t0\n")
      : listener_(Ipv4Endpoint::parse("127.0.0.1", 0, "site")),
        reading_(std::move(reading)),
        open_answer_(std::move(open_answer)),
        thread_([this] { run(); }) {}
  ~ScriptedSite() {
    stop_.store(true);
    thread_.join();
  }
  std::uint16_t port() const { return listener_.port(); }
  std::vector<std::string> lines() {
    const std::lock_guard lock(mutex_);
    return lines_;
  }

 private:
  void run() {
    std::optional<TcpStream> client;
    while (!stop_.load() && !client) client = listener_.accept(0.01);
    std::array<char, 2048> line{};
    while (!stop_.load()) {
      std::size_t size = 0;
      const TcpStream::Io io = client->receive_line(line, size, monotonic_seconds() + 0.01);
      if (io == TcpStream::Io::kTimeout) continue;
      if (io != TcpStream::Io::kDone) return;
      const std::string text(line.data(), size);
      {
        const std::lock_guard lock(mutex_);
        lines_.push_back(text);
      }
      const std::string reply = text.rfind("get-control-point", 0) == 0 ? "OK\t0\t" + field(text, 1) + reading_
                                : text.rfind("open-session", 0) == 0    ? open_answer_
                                                                        : std::string("OK\t0\n");
      (void)client->send_all(std::as_bytes(std::span<const char>(reply.data(), reply.size())),
                             monotonic_seconds() + 5.0);
    }
  }
  TcpListener listener_;
  std::string reading_, open_answer_;
  std::mutex mutex_;
  std::vector<std::string> lines_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

NeesPluginParameters scripted_config(const ScriptedSite& site, std::vector<NeesPluginChannel> map) {
  NeesPluginParameters config;
  config.channels = static_cast<int>(map.size());
  config.port = site.port();
  config.local_host = "127.0.0.1";
  config.channel_map = std::move(map);
  config.reply_timeout_s = 10.0;
  return config;
}

TEST(NeesPluginActuator, SendsOpenFrescosLinesFromOpenSessionToCloseSession) {
  // A site of OpenFresco's kind: OK to everything, the reading at 1.5 mm and 2 N.
  ScriptedSite site("\tMDL-00-01\tx\tdisplacement\t1.5000000000E+00\tx\tforce\t2.0E+00\r\n");
  std::string transaction;
  {
    NeesPluginActuator adapter(scripted_config(site, mdl_x_in_mm_and_kn()));
    const double x0[] = {0.0015};
    adapter.start(x0);
    EXPECT_NEAR(adapter.initial_reading().displacement_m[0], 0.0015, 1e-15);
    EXPECT_NEAR(adapter.initial_reading().force_n[0], 2000.0, 1e-9);  // 2 kN
    transaction = adapter.link_summary()["failed_transaction"];       // none failed: empty
    EXPECT_EQ(transaction, "");
  }
  const std::vector<std::string> lines = site.lines();
  ASSERT_EQ(lines.size(), 6u);
  EXPECT_EQ(lines[0], "open-session\tOpenFresco\n");
  EXPECT_EQ(lines[1], "set-parameter\tOPFTransaction\tnstep\t1\n");
  transaction = field(lines[2], 1);
  EXPECT_EQ(transaction.rfind("OPFTransaction", 0), 0u) << transaction;
  EXPECT_EQ(lines[2], "propose\t" + transaction + "\tMDL-00-01\tx\tdisplacement\t1.5000000000E+00\n");
  EXPECT_EQ(lines[3], "execute\t" + transaction + "\n");
  EXPECT_EQ(lines[4], "get-control-point\t" + transaction + "\tMDL-00-01\n");
  EXPECT_EQ(lines[5], "close-session\tOpenFresco\n");
}

// The failure the adapter's start latches against a site whose reading is `reading`, and the
// site's words it kept.
std::pair<NeesPluginFailure, std::string> start_against(const std::string& reading) {
  ScriptedSite site(reading);
  NeesPluginActuator adapter(scripted_config(site, mdl_x_in_mm_and_kn()));
  const double x0[] = {0.0};
  EXPECT_THROW(adapter.start(x0), std::runtime_error);
  EXPECT_EQ(adapter.failed_side(), "site");
  return {adapter.failure(), std::string(adapter.site_message())};
}

TEST(NeesPluginActuator, AnAnswerWithoutAChannelsForceFaults) {
  // The site reports the displacement only, and a y axis no channel follows.
  EXPECT_EQ(start_against("\tMDL-00-01\ty\tforce\t9\tx\tdisplacement\t0\n").first, NeesPluginFailure::kMissingChannel);
}

TEST(NeesPluginActuator, AnAnswerForAnotherControlPointFaults) {
  const auto [failure, words] = start_against("\tMDL-00-02\tx\tdisplacement\t0\tx\tforce\t0\n");
  EXPECT_EQ(failure, NeesPluginFailure::kWrongControlPoint);
  EXPECT_NE(words.find("MDL-00-02"), std::string::npos) << words;
}

TEST(NeesPluginActuator, ASiteMessageIsKeptBoundedAndPrintable) {
  ScriptedSite site("", "ERROR\t\x01\xff" + std::string(600, 'w') + "\n");
  NeesPluginActuator adapter(scripted_config(site, mdl_x_in_mm_and_kn()));
  const double x0[] = {0.0};
  EXPECT_THROW(adapter.start(x0), std::runtime_error);
  EXPECT_EQ(adapter.site_message().size(), 256u);
  const nlohmann::json summary = adapter.link_summary();
  EXPECT_EQ(summary["site_message_truncated"], true);
  EXPECT_EQ(std::string(summary["site_message"]).rfind("ERROR\t\\x01\\xffwww", 0), 0u) << summary["site_message"];
  EXPECT_NO_THROW((void)summary.dump());  // valid UTF-8 whatever the site sent
}

TEST(NeesPluginActuator, AConfigThatCannotWorkIsRefusedNamingTheField) {
  NeesPluginParameters config;
  config.port = 44000;
  config.channel_map = mdl_x_in_mm_and_kn();
  EXPECT_NO_THROW(config.validate());
  auto refused = [](NeesPluginParameters c, const std::string& field) {
    try {
      c.validate();
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind(field, 0), 0u) << e.what();
      return;
    }
    ADD_FAILURE() << field << " accepted";
  };
  NeesPluginParameters c = config;
  c.channel_map.push_back(c.channel_map[0]);
  c.channels = 2;
  refused(c, "channel_map[1].axis");  // the same control point and axis twice
  c = config;
  c.channel_map[0].control_point = "MDL 00";
  refused(c, "channel_map[0].control_point");
  c = config;
  c.session_name = "";
  refused(c, "session_name");
  c = config;
  c.port = 0;
  refused(c, "port");
}

}  // namespace
}  // namespace rpsd::node
