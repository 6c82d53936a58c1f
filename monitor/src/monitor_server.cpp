#include "rpsd/monitor/monitor_server.h"

#include <httplib.h>

#include <atomic>
#include <cmath>
#include <ctime>
#include <deque>
#include <fstream>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <nlohmann/json.hpp>

#include "rpsd/monitor/access_token.h"
#include "rpsd/monitor/results_catalog.h"
#include "rpsd/monitor/results_path.h"
#include "rpsd/monitor/telemetry_json.h"
#include "rpsd/monitor/web_assets.h"

namespace rpsd::monitor {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

constexpr std::uintmax_t kLargestServedFileBytes = 512u << 20;
constexpr int kServerThreads = 40;  // each open stream holds one (StreamHubOptions::max_clients)

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

void send_json(httplib::Response& res, int code, const json& body) {
  res.status = code;
  res.set_header("Cache-Control", "no-store");
  res.set_content(body.dump(), "application/json");
}

}  // namespace

struct MonitorServer::Impl {
  Impl(MonitorOptions o, TelemetrySource* s, CommandSink* c, std::ostream& l)
      : options(std::move(o)), source(s), sink(c), log(l), hub(options.stream) {}

  MonitorOptions options;
  TelemetrySource* source;
  CommandSink* sink;
  std::ostream& log;
  std::mutex log_mutex;
  StreamHub hub;
  httplib::Server http;
  int port = -1;
  std::atomic<bool> stopping{false};
  std::thread pump;

  // What the pump saw last, for /api/status.
  mutable std::mutex state_mutex;
  json last_status = nullptr;
  std::string last_state;
  std::optional<Clock::time_point> last_batch_at;
  std::uint64_t expected_sequence = 0;  // the next batch of the run, by its sequence
  std::uint64_t last_run_id = 0;
  std::uint64_t batches_lost = 0;
  std::deque<json> recent_events;
  bool alive = false;

  json status() const {
    const std::lock_guard lock(state_mutex);
    json s{{"test_id", options.test_id},
           {"telemetry", source != nullptr},
           {"commands", sink != nullptr},
           {"viewer", !options.results_dir.empty()},
           {"alive", alive},
           {"run", last_status},
           {"batches_lost", batches_lost},
           {"browsers", hub.clients()},
           {"dropped_to_browsers", hub.dropped_total()},
           {"events", json(recent_events)}};
    double age_s = NAN;
    if (last_batch_at) age_s = std::chrono::duration<double>(Clock::now() - *last_batch_at).count();
    s["last_batch_age_s"] = std::isfinite(age_s) ? json(age_s) : json(nullptr);
    // Stale: a run under way whose batches stopped coming; lost: its publisher is gone.
    const bool under_way = last_state == "running" || last_state == "starting";
    s["stale"] = under_way && (!std::isfinite(age_s) || age_s > options.stale_after_s);
    s["link_lost"] = source != nullptr && under_way && !alive;
    return s;
  }

  void pump_loop() {
    std::vector<telemetry::TelemetryBatch> batches;
    std::vector<telemetry::TelemetryEvent> events;
    auto next_notice = Clock::now();
    while (!stopping.load()) {
      source->wait(std::chrono::milliseconds(100));
      batches.clear();
      events.clear();
      source->take(batches, events);
      const bool now_alive = source->alive();
      for (const telemetry::TelemetryEvent& e : events) {
        json j = event_json(e);
        {
          const std::lock_guard lock(state_mutex);
          recent_events.push_back(j);
          while (recent_events.size() > 50) recent_events.pop_front();
        }
        hub.publish_event(j.dump());
      }
      for (const telemetry::TelemetryBatch& b : batches) {
        json j = batch_json(b);
        {
          const std::lock_guard lock(state_mutex);
          // A run's batches count from 0: those sent before the first one received (the monitor
          // matched the publisher after its history had moved on) are lost as surely as a gap.
          if (b.status.run_id != last_run_id) expected_sequence = 0;
          if (b.sequence > expected_sequence) batches_lost += b.sequence - expected_sequence;
          expected_sequence = b.sequence + 1;
          last_run_id = b.status.run_id;
          last_status = j["status"];
          last_state = run_state_name(b.status.state);
          last_batch_at = Clock::now();
        }
        const double time_s = b.count > 0 ? b.samples[b.count - 1].time_s : 0.0;
        hub.publish_batch(j.dump(), b.status.run_id, time_s);
      }
      {
        const std::lock_guard lock(state_mutex);
        alive = now_alive;
      }
      if (Clock::now() >= next_notice) {  // the link's state, twice a second, to every browser
        next_notice = Clock::now() + std::chrono::milliseconds(500);
        json s = status();
        json notice{{"type", "link"},
                    {"test_id", options.test_id},
                    {"alive", s["alive"]},
                    {"stale", s["stale"]},
                    {"link_lost", s["link_lost"]},
                    {"last_batch_age_s", s["last_batch_age_s"]},
                    {"batches_lost", s["batches_lost"]}};
        hub.publish_transient(notice.dump());
      }
    }
  }

  void log_line(const std::string& line) {
    const std::lock_guard lock(log_mutex);
    log << utc_now() << " " << line << std::endl;
  }

  void operator_command(const httplib::Request& req, httplib::Response& res) {
    const std::string origin = req.remote_addr + ":" + std::to_string(req.remote_port);
    const json body = json::parse(req.body, nullptr, false);
    if (!body.is_object() || !body.contains("action") || !body["action"].is_string()) {
      send_json(res, 400, {{"error", "a JSON object with \"action\" and \"token\" is expected"}});
      return;
    }
    const std::string action_text = body["action"].get<std::string>();
    const std::string token =
        body.contains("token") && body["token"].is_string() ? body["token"].get<std::string>() : "";
    if (!token_matches(options.token, token)) {
      log_line("operator " + action_text + " from " + origin + ": refused, wrong or missing token");
      send_json(res, 403,
                {{"error", "refused: the token is wrong or missing (it is printed where rpsd monitor started)"}});
      return;
    }
    const std::optional<operator_commands::OperatorAction> action = parse_action(action_text);
    if (!action) {
      send_json(res, 400, {{"error", "unknown action \"" + action_text + "\" (stop, abort, hold, resume)"}});
      return;
    }
    if (sink == nullptr) {
      send_json(res, 503,
                {{"error", options.no_commands_why.empty() ? "this monitor has no link to send operator commands"
                                                           : options.no_commands_why}});
      return;
    }
    const std::optional<operator_commands::OperatorReply> reply = sink->send(*action, origin);
    if (!reply) {
      log_line("operator " + action_text + " from " + origin + ": no reply from the coordinator");
      send_json(res, 504,
                {{"error", "no reply from the coordinator: no run of test " + std::to_string(options.test_id) +
                               ", or it does not accept operator commands from this monitor"}});
      return;
    }
    const json r = reply_json(*reply);
    log_line("operator " + action_text + " from " + origin + ": " + r["status"].get<std::string>() + " " +
             r["text"].get<std::string>());
    send_json(res, reply->status == operator_commands::ReplyStatus::kDone ? 200 : 409, r);
  }

  void results_file(const httplib::Request& req, httplib::Response& res) {
    const std::string folder = req.has_param("folder") ? req.get_param_value("folder") : "";
    const std::string name = req.has_param("name") ? req.get_param_value("name") : "";
    if (!servable_file_name(name)) {
      send_json(res, 400, {{"error", "not a result file name: " + name}});
      return;
    }
    // One name (no separator, no leading dot) inside a folder the guard accepts as a whole.
    const std::optional<std::filesystem::path> file =
        resolve_under(options.results_dir, folder.empty() ? name : folder + "/" + name);
    std::error_code ec;
    if (!file || !std::filesystem::is_regular_file(*file, ec)) {
      send_json(res, 404, {{"error", "no such file under the results folder"}});
      return;
    }
    if (std::filesystem::file_size(*file, ec) > kLargestServedFileBytes) {
      send_json(res, 413, {{"error", "the file is larger than the viewer serves"}});
      return;
    }
    std::ifstream in(*file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    const bool json_file = name.size() > 5 && name.substr(name.size() - 5) == ".json";
    res.set_header("Cache-Control", "no-store");
    res.set_content(text.str(), json_file ? "application/json" : "text/plain; charset=utf-8");
  }

  void routes() {
    http.set_payload_max_length(64 * 1024);
    http.new_task_queue = [] { return new httplib::ThreadPool(kServerThreads); };
    http.set_default_headers({{"X-Content-Type-Options", "nosniff"}, {"X-Frame-Options", "DENY"}});
    const auto page = [](const std::string& path, httplib::Response& res) {
      const std::optional<WebAsset> asset = find_web_asset(path);
      if (!asset) {
        res.status = 404;
        res.set_content("not found", "text/plain");
        return;
      }
      res.set_content(asset->bytes.data(), asset->bytes.size(), std::string(asset->content_type).c_str());
    };
    http.Get("/", [page](const httplib::Request&, httplib::Response& res) { page("index.html", res); });
    http.Get(R"(/assets/(.+))",
             [page](const httplib::Request& req, httplib::Response& res) { page(req.matches[1], res); });
    http.Get("/api/status", [this](const httplib::Request&, httplib::Response& res) { send_json(res, 200, status()); });
    http.Get("/api/stream", [this](const httplib::Request&, httplib::Response& res) { stream(res); });
    http.Post("/api/operator",
              [this](const httplib::Request& req, httplib::Response& res) { operator_command(req, res); });
    http.Get("/api/results", [this](const httplib::Request&, httplib::Response& res) {
      if (options.results_dir.empty()) {
        send_json(res, 404, {{"error", "no --results folder given"}});
        return;
      }
      send_json(res, 200, catalog_json(list_results_folders(options.results_dir)));
    });
    http.Get("/api/results/file", [this](const httplib::Request& req, httplib::Response& res) {
      if (options.results_dir.empty()) {
        send_json(res, 404, {{"error", "no --results folder given"}});
        return;
      }
      results_file(req, res);
    });
  }

  void stream(httplib::Response& res) {
    const std::optional<StreamHub::ClientId> id = hub.join();
    if (!id) {
      send_json(res, 503, {{"error", "too many browsers stream at once"}});
      return;
    }
    res.set_header("Cache-Control", "no-store");
    const StreamHub::ClientId client = *id;
    auto dropped_seen = std::make_shared<std::uint64_t>(0);
    res.set_chunked_content_provider(
        "text/event-stream",
        [this, client, dropped_seen](std::size_t, httplib::DataSink& sink) {
          std::vector<StreamHub::Message> messages;
          std::uint64_t dropped = 0;
          if (!hub.next(client, messages, std::chrono::milliseconds(1000), dropped)) return false;
          std::string out;
          if (dropped != *dropped_seen) {
            *dropped_seen = dropped;
            out += "data: {\"type\":\"dropped\",\"count\":" + std::to_string(dropped) + "}\n\n";
          }
          for (const StreamHub::Message& m : messages) {
            out += "data: ";
            out += *m;
            out += "\n\n";
          }
          if (out.empty()) out = ": keep-alive\n\n";  // finds a browser that went away
          return sink.write(out.data(), out.size());
        },
        [this, client](bool) { hub.leave(client); });
  }
};

MonitorServer::MonitorServer(MonitorOptions options, TelemetrySource* source, CommandSink* sink, std::ostream& log)
    : impl_(std::make_unique<Impl>(std::move(options), source, sink, log)) {
  impl_->routes();
}

MonitorServer::~MonitorServer() {
  stop();
  if (impl_->pump.joinable()) impl_->pump.join();
}

void MonitorServer::bind() {
  const MonitorOptions& o = impl_->options;
  if (o.port == 0) {
    impl_->port = impl_->http.bind_to_any_port(o.host);
  } else {
    impl_->port = impl_->http.bind_to_port(o.host, o.port) ? o.port : -1;
  }
  if (impl_->port <= 0) {
    throw std::invalid_argument("monitor: cannot listen on " + o.host + ":" + std::to_string(o.port) +
                                " (an address of this host, and a port no other program holds)");
  }
}

int MonitorServer::bound_port() const { return impl_->port; }

void MonitorServer::serve() {
  if (impl_->source != nullptr && !impl_->pump.joinable()) impl_->pump = std::thread([this] { impl_->pump_loop(); });
  impl_->http.listen_after_bind();
}

void MonitorServer::stop() {
  impl_->stopping.store(true);
  impl_->hub.close();
  impl_->http.stop();
}

}  // namespace rpsd::monitor
