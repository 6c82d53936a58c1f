// The monitor's HTTP server on loopback, as a browser meets it: the page and its assets, a
// command refused without the token and sent once with it, the viewer's path guard, the live
// stream with the recent past, and the status saying when the data is stale or the link lost.
#include "rpsd/monitor/monitor_server.h"

#include <httplib.h>

#include <gtest/gtest.h>

#include <unistd.h>
#include <atomic>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

namespace rpsd::monitor {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using operator_commands::OperatorAction;

constexpr char kToken[] = "00112233445566778899aabbccddeeff";

class RecordingSink final : public CommandSink {
 public:
  std::optional<operator_commands::OperatorReply> send(OperatorAction action, const std::string& origin) override {
    const std::lock_guard lock(mutex);
    actions.push_back(action);
    origins.push_back(origin);
    operator_commands::OperatorReply r;
    r.status = operator_commands::ReplyStatus::kDone;
    std::snprintf(r.text.data(), r.text.size(), "stopping at step 12");
    return r;
  }
  std::mutex mutex;
  std::vector<OperatorAction> actions;
  std::vector<std::string> origins;
};

// One batch of a running run, then silence; its publisher alive until told otherwise.
class ScriptedSource final : public TelemetrySource {
 public:
  std::size_t take(std::vector<telemetry::TelemetryBatch>& batches, std::vector<telemetry::TelemetryEvent>&) override {
    if (sent_.exchange(true)) return 0;
    telemetry::TelemetryBatch b;
    b.status.run_id = 9;
    b.status.state = telemetry::RunState::kRunning;
    b.count = 2;
    for (int i = 0; i < 2; ++i) {
      b.samples[i].step = i + 1;
      b.samples[i].time_s = 0.5 * (i + 1);
      b.samples[i].channels = 1;
      b.samples[i].measured_m[0] = 0.001 * (i + 1);
    }
    batches.push_back(b);
    return 1;
  }
  bool wait(std::chrono::milliseconds timeout) override {
    std::this_thread::sleep_for(std::min(timeout, std::chrono::milliseconds(10)));
    return !sent_;
  }
  bool alive() const override { return alive_; }
  std::atomic<bool> alive_{true};

 private:
  std::atomic<bool> sent_{false};
};

// Batches of one run with the given sequence numbers, all at once, then silence.
class SequencedSource final : public TelemetrySource {
 public:
  explicit SequencedSource(std::vector<std::uint64_t> sequences) : sequences_(std::move(sequences)) {}
  std::size_t take(std::vector<telemetry::TelemetryBatch>& batches, std::vector<telemetry::TelemetryEvent>&) override {
    if (sent_.exchange(true)) return 0;
    for (const std::uint64_t sequence : sequences_) {
      telemetry::TelemetryBatch b;
      b.sequence = sequence;
      b.status.run_id = 9;
      b.status.state = telemetry::RunState::kRunning;
      b.count = 1;
      b.samples[0].step = static_cast<std::int64_t>(4 * (sequence + 1));
      b.samples[0].channels = 1;
      b.status.steps_done = b.samples[0].step;
      batches.push_back(b);
    }
    return sequences_.size();
  }
  bool wait(std::chrono::milliseconds timeout) override {
    std::this_thread::sleep_for(std::min(timeout, std::chrono::milliseconds(10)));
    return !sent_;
  }
  bool alive() const override { return true; }

 private:
  std::vector<std::uint64_t> sequences_;
  std::atomic<bool> sent_{false};
};

class MonitorServerTest : public ::testing::Test {
 protected:
  void start(TelemetrySource* source, double stale_after_s = 2.0) {
    results_ = fs::temp_directory_path() / ("rpsd-monitor-server-" + std::to_string(::getpid()));
    fs::remove_all(results_);
    fs::create_directories(results_ / "test-1");
    std::ofstream(results_ / "test-1" / "summary.json") << R"({"study":"rpsd_test","result":"completed"})";
    std::ofstream(results_ / "test-1" / "time_history.csv") << "step,time_s\n1,0.001\n";
    std::ofstream(results_.string() + "-secret.csv") << "secret";
    MonitorOptions o;
    o.port = 0;
    o.token = kToken;
    o.results_dir = results_;
    o.stale_after_s = stale_after_s;
    server_ = std::make_unique<MonitorServer>(o, source, &sink_, log_);
    server_->bind();
    thread_ = std::thread([this] { server_->serve(); });
    client_ = std::make_unique<httplib::Client>("127.0.0.1", server_->bound_port());
    client_->set_read_timeout(30, 0);
  }
  void TearDown() override {
    if (server_) server_->stop();
    if (thread_.joinable()) thread_.join();
    server_.reset();
    fs::remove_all(results_);
    fs::remove(results_.string() + "-secret.csv");
  }
  httplib::Result post(const std::string& body) { return client_->Post("/api/operator", body, "application/json"); }
  nlohmann::json status() { return nlohmann::json::parse(client_->Get("/api/status")->body); }

  fs::path results_;
  ScriptedSource scripted_;  // outlives the server, whose reader thread reads it until stopped
  RecordingSink sink_;
  std::ostringstream log_;
  std::unique_ptr<MonitorServer> server_;
  std::thread thread_;
  std::unique_ptr<httplib::Client> client_;
};

TEST_F(MonitorServerTest, ThePageAndItsAssetsAreServedFromTheBinary) {
  start(nullptr);
  const auto page = client_->Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("<title>rpsd monitor</title>"), std::string::npos);
  const auto uplot = client_->Get("/assets/vendor/uplot/uPlot.iife.min.js");
  ASSERT_TRUE(uplot);
  EXPECT_EQ(uplot->status, 200);
  EXPECT_GT(uplot->body.size(), 40000u);
  EXPECT_EQ(client_->Get("/assets/../monitor_server.cpp")->status, 404);
}

TEST_F(MonitorServerTest, ACommandWithoutTheRightTokenIsRefusedAndNeverSent) {
  start(nullptr);
  EXPECT_EQ(post(R"({"action":"stop"})")->status, 403);
  EXPECT_EQ(post(R"({"action":"stop","token":""})")->status, 403);
  EXPECT_EQ(post(R"({"action":"stop","token":"00112233445566778899aabbccddeefe"})")->status, 403);
  EXPECT_EQ(post("action=stop")->status, 400);
  EXPECT_TRUE(sink_.actions.empty());
  EXPECT_NE(log_.str().find("operator stop from 127.0.0.1"), std::string::npos);
  EXPECT_NE(log_.str().find("refused, wrong or missing token"), std::string::npos);
}

TEST_F(MonitorServerTest, ACommandWithTheTokenIsSentOnceAndLogged) {
  start(nullptr);
  const auto res = post(std::string(R"({"action":"stop","token":")") + kToken + "\"}");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
  EXPECT_EQ(nlohmann::json::parse(res->body)["text"], "stopping at step 12");
  ASSERT_EQ(sink_.actions.size(), 1u);
  EXPECT_EQ(sink_.actions[0], OperatorAction::kStop);
  EXPECT_EQ(sink_.origins[0].rfind("127.0.0.1:", 0), 0u);
  EXPECT_EQ(post(std::string(R"({"action":"halt","token":")") + kToken + "\"}")->status, 400);
  EXPECT_EQ(sink_.actions.size(), 1u);
  EXPECT_NE(log_.str().find("operator stop from 127.0.0.1"), std::string::npos);
  EXPECT_NE(log_.str().find(": done stopping at step 12"), std::string::npos);
}

TEST_F(MonitorServerTest, TheViewerServesOnlyResultFilesUnderItsFolder) {
  start(nullptr);
  const auto list = client_->Get("/api/results");
  ASSERT_TRUE(list);
  const auto folders = nlohmann::json::parse(list->body)["folders"];
  ASSERT_EQ(folders.size(), 1u);
  EXPECT_EQ(folders[0]["path"], "test-1");
  const auto csv = client_->Get("/api/results/file?folder=test-1&name=time_history.csv");
  ASSERT_TRUE(csv);
  EXPECT_EQ(csv->status, 200);
  EXPECT_EQ(csv->body, "step,time_s\n1,0.001\n");
  const std::string secret = results_.filename().string() + "-secret.csv";
  EXPECT_EQ(client_->Get("/api/results/file?folder=..&name=" + secret)->status, 404);
  EXPECT_EQ(client_->Get("/api/results/file?folder=test-1/../..&name=" + secret)->status, 404);
  EXPECT_EQ(client_->Get("/api/results/file?folder=/etc&name=passwd.txt")->status, 404);
  EXPECT_EQ(client_->Get("/api/results/file?folder=test-1&name=../summary.json")->status, 400);
  EXPECT_EQ(client_->Get("/api/results/file?folder=test-1&name=missing.csv")->status, 404);
}

TEST_F(MonitorServerTest, TheStreamCarriesTheRecentPastAndTheStatusSaysStaleThenLost) {
  ScriptedSource& source = scripted_;
  start(&source, 0.2);
  // Wait until the batch has come through (a hang guard, not a measured time).
  for (int i = 0; i < 3000 && status()["run"].is_null(); ++i) std::this_thread::sleep_for(10ms);
  std::string received;
  const auto give_up = std::chrono::steady_clock::now() + 30s;  // a hang guard: the stream never ends by itself
  client_->Get("/api/stream", [&](const char* data, std::size_t n) {
    received.append(data, n);
    // Stop reading once the batch came.
    return received.find("\"type\":\"batch\"") == std::string::npos && std::chrono::steady_clock::now() < give_up;
  });
  EXPECT_NE(received.find("data: {"), std::string::npos);
  EXPECT_NE(received.find("\"measured_m\":[[0.001,0.002]]"), std::string::npos) << received;
  nlohmann::json s;
  for (int i = 0; i < 3000 && !(s = status())["stale"].get<bool>(); ++i) std::this_thread::sleep_for(10ms);
  EXPECT_TRUE(s["stale"]);
  EXPECT_FALSE(s["link_lost"]);
  EXPECT_EQ(s["run"]["state"], "running");
  source.alive_ = false;
  for (int i = 0; i < 3000 && !(s = status())["link_lost"].get<bool>(); ++i) std::this_thread::sleep_for(10ms);
  EXPECT_TRUE(s["link_lost"]);
}

// A monitor that matched a run's publisher late never receives its first batches (a run as
// fast as possible sends 80, the writer's history, in a few milliseconds): they count as lost,
// as a gap between two batches does, so that the page says its plots miss them.
TEST_F(MonitorServerTest, TheBatchesOfARunBeforeTheFirstReceivedCountAsLost) {
  SequencedSource source({3, 4, 6});
  start(&source);
  nlohmann::json s;
  // A hang guard, not a measured time: until the last batch (step 28) has come through.
  for (int i = 0; i < 3000 && ((s = status())["run"].is_null() || s["run"]["steps_done"] != 28); ++i)
    std::this_thread::sleep_for(10ms);
  EXPECT_EQ(s["run"]["steps_done"], 28) << s;
  EXPECT_EQ(s["batches_lost"], 4) << s;  // 0, 1, 2 before the first received, 5 between
}

}  // namespace
}  // namespace rpsd::monitor
