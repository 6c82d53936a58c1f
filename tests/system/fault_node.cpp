// rpsd_fault_node: stands in for the servo nodes of a test (one DDS endpoint per site, one
// channel each) and answers every command at once as a perfect actuator would (x = u,
// F = k u), but on chosen steps of one site it sends the coordinator bad feedback first:
//
//   --wrong-test S     a sample with another test id, before the answer to step S
//   --wrong-site S     a sample claiming another site (in this site's partition)
//   --wrong-channels S a sample with 2 channels instead of 1
//   --older S          a sample of step S - 10 (older than what the coordinator has)
//   --duplicate S      the answer to step S twice
//   --late S           the answer to step S only after --late-ms milliseconds
//   --nan S            a NaN displacement in the answer to step S and in every answer after it
//                      (a failed transducer stays failed)
//   --node-fault S     the node's fault flag in the answer to step S and in every answer after
//                      it (a node that has faulted stays faulted)
//
// Each fault comes with the first command at or after its step S: in real time commands are
// best effort and the one of step S may be lost.
// Every bad sample carries a displacement of 1 m, which the coordinator must never use.
// --real-time makes its reader and writer best effort, as a real-time node's are, and runs
// its threads at SCHED_FIFO 80 with memory locked (when allowed), as a node's loop.
//
// It writes what it sent (answers, and the command step each fault came with) as JSON to
// --summary when it stops
// (SIGTERM/SIGINT or --duration). Used by tests/system/bad_feedback.sh.
#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "rpsd/realtime/pacer.h"
#include "rpsd/realtime/realtime_setup.h"
#include "rpsd/transport/dds_node_endpoint.h"

namespace {

std::atomic<bool> g_stop{false};
void request_stop(int) { g_stop.store(true); }

struct Options {
  std::uint32_t domain_id = 0;
  std::string dds_config;
  std::uint32_t test_id = 7;
  std::vector<std::uint32_t> sites{1, 2};
  std::uint32_t faulty_site = 2;
  double stiffness_n_per_m = 700.8e3;
  std::map<std::string, std::int64_t> fault_step;  // fault name -> step (absent: never)
  double late_ms = 3.0;
  double duration_s = 0.0;
  bool real_time = false;
  std::string summary;
};

struct SiteCounts {
  std::int64_t answers = 0;
  std::map<std::string, std::int64_t> fault_sent_at_step;  // fault name -> the command step it came with
};

[[noreturn]] void usage(const std::string& problem) {
  std::cerr << "rpsd_fault_node: " << problem
            << "\nusage: rpsd_fault_node --domain N --dds-config FILE [--test ID] [--faulty-site ID] [--duration S]"
               " [--summary FILE] [--late-ms MS] [--wrong-test S] [--wrong-site S] [--wrong-channels S] [--older S]"
               " [--duplicate S] [--late S] [--nan S] [--node-fault S]\n";
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) usage(flag + " needs a value");
    const std::string value = argv[++i];
    if (flag == "--domain")
      o.domain_id = static_cast<std::uint32_t>(std::stoul(value));
    else if (flag == "--dds-config")
      o.dds_config = value;
    else if (flag == "--test")
      o.test_id = static_cast<std::uint32_t>(std::stoul(value));
    else if (flag == "--faulty-site")
      o.faulty_site = static_cast<std::uint32_t>(std::stoul(value));
    else if (flag == "--duration")
      o.duration_s = std::stod(value);
    else if (flag == "--summary")
      o.summary = value;
    else if (flag == "--real-time")
      o.real_time = value == "1";
    else if (flag == "--late-ms")
      o.late_ms = std::stod(value);
    else if (flag == "--wrong-test" || flag == "--wrong-site" || flag == "--wrong-channels" || flag == "--older" ||
             flag == "--duplicate" || flag == "--late" || flag == "--nan" || flag == "--node-fault") {
      o.fault_step[flag.substr(2)] = std::stoll(value);
    } else {
      usage("unknown option " + flag);
    }
  }
  if (o.dds_config.empty()) usage("--dds-config is required");
  return o;
}

void serve(rpsd::transport::DdsNodeEndpoint& node, std::uint32_t site, const Options& o, SiteCounts& counts) {
  using rpsd::transport::CommandSample;
  using rpsd::transport::FeedbackSample;
  const bool faulty = site == o.faulty_site;
  // Once, with the first command at or after the fault's step.
  const auto at = [&](const char* fault, std::int64_t step) {
    const auto it = o.fault_step.find(fault);
    const bool hit =
        faulty && it != o.fault_step.end() && step >= it->second && !counts.fault_sent_at_step.contains(fault);
    if (hit) counts.fault_sent_at_step[fault] = step;
    return hit;
  };
  bool transducer_failed = false;
  bool node_faulted = false;
  if (o.real_time) rpsd::realtime::apply_realtime({});
  CommandSample c;
  // Heartbeats as a servo node sends them: the coordinator starts once one says the node
  // has found it.
  rpsd::transport::NodeHeartbeat heartbeat;
  heartbeat.test_id = o.test_id;
  heartbeat.site_id = site;
  heartbeat.control_period_s = 1.0 / 1024.0;  // the bridge scenario's
  std::int64_t next_heartbeat_ns = 0;
  while (!g_stop.load()) {
    if (const std::int64_t now = rpsd::realtime::monotonic_now_ns(); now >= next_heartbeat_ns) {
      node.publish_heartbeat(heartbeat);
      next_heartbeat_ns = now + 100'000'000;
    }
    if (!node.wait_for_command_until(rpsd::realtime::monotonic_now_ns() + 50'000'000)) continue;
    while (node.take_command(c)) {
      if (c.end_of_run) continue;
      heartbeat.serving_run_id = c.run_id;  // the run it answers, as a node serves one
      FeedbackSample f;
      f.test_id = c.test_id;
      f.site_id = site;
      f.run_id = c.run_id;
      f.step = c.step;
      f.time_s = c.time_s;
      f.channels = c.channels;
      for (int k = 0; k < c.channels; ++k) {
        f.displacement_m[k] = c.displacement_m[k];
        f.force_n[k] = o.stiffness_n_per_m * c.displacement_m[k];
      }
      FeedbackSample bad = f;
      bad.displacement_m[0] = 1.0;
      if (at("wrong-test", c.step)) {
        bad.test_id = o.test_id + 1;
        node.publish(bad);
        bad.test_id = f.test_id;
      }
      if (at("wrong-site", c.step)) {
        bad.site_id = site + 100;
        node.publish(bad);
        bad.site_id = f.site_id;
      }
      if (at("wrong-channels", c.step)) {
        bad.channels = static_cast<std::uint8_t>(f.channels + 1);
        node.publish(bad);
        bad.channels = f.channels;
      }
      if (at("older", c.step)) {
        bad.step = c.step - 10;
        node.publish(bad);
      }
      if (at("late", c.step)) {
        std::this_thread::sleep_for(std::chrono::microseconds(static_cast<std::int64_t>(o.late_ms * 1e3)));
      }
      if (at("nan", c.step)) transducer_failed = true;
      if (transducer_failed) f.displacement_m[0] = std::numeric_limits<double>::quiet_NaN();
      if (at("node-fault", c.step) && !node_faulted) {
        // As a servo node does: the fault and its words in a heartbeat at once.
        node_faulted = true;
        heartbeat.state = rpsd::transport::NodeHeartbeat::kFaulted;
        const std::string_view words = "the lab controller says: proposal refused (rpsd_fault_node)";
        std::copy(words.begin(), words.end(), heartbeat.fault_text.begin());
        node.publish_heartbeat(heartbeat);
      }
      if (node_faulted) f.status |= rpsd::transport::kNodeFault;
      node.publish(f);
      ++counts.answers;
      if (at("duplicate", c.step)) node.publish(f);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  struct sigaction action {};
  action.sa_handler = request_stop;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);

  rpsd::transport::DdsParticipant participant({o.domain_id, o.dds_config});
  std::vector<std::unique_ptr<rpsd::transport::DdsNodeEndpoint>> endpoints;
  std::vector<SiteCounts> counts(o.sites.size());
  for (std::uint32_t site : o.sites) {
    rpsd::transport::DdsNodeEndpointConfig config;
    config.test_id = o.test_id;
    config.site_id = site;
    config.qos.newest_only = o.real_time;
    endpoints.push_back(std::make_unique<rpsd::transport::DdsNodeEndpoint>(participant, config));
  }
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < o.sites.size(); ++i) {
    threads.emplace_back([&, i] { serve(*endpoints[i], o.sites[i], o, counts[i]); });
  }
  std::cout << "rpsd_fault_node: test " << o.test_id << ", faults on site " << o.faulty_site << std::endl;
  const std::int64_t end_ns = rpsd::realtime::monotonic_now_ns() + static_cast<std::int64_t>(o.duration_s * 1e9);
  while (!g_stop.load() && (o.duration_s <= 0.0 || rpsd::realtime::monotonic_now_ns() < end_ns)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  g_stop.store(true);
  for (auto& t : threads) t.join();

  if (!o.summary.empty()) {
    std::ofstream out(o.summary);
    out << "{\"sites\": {";
    for (std::size_t i = 0; i < o.sites.size(); ++i) {
      out << (i ? ", " : "") << '"' << o.sites[i] << "\": {\"answers\": " << counts[i].answers
          << ", \"fault_sent_at_step\": {";
      bool first = true;
      for (const auto& [name, n] : counts[i].fault_sent_at_step) {
        out << (first ? "" : ", ") << '"' << name << "\": " << n;
        first = false;
      }
      out << "}}";
    }
    out << "}}\n";
  }
  return 0;
}
