// rpsd_forge_command: an intruder on the command topic of one site (security off). It waits
// until the site's node says it serves a run (its heartbeat) and has answered it (feedback),
// then writes, from a DDS writer of its own in the site's partition:
//
//   foreign-run       a command of a made-up run with step 9 x 10^18 (what took a node over)
//   copied-run-huge   the served run's id (copied from the heartbeat) with step 9 x 10^18
//   copied-run-next   the served run's id with the next step and a displacement of 20 mm
//   copied-run-end    the served run's end of run
//
// and exits. None may move the actuator or free the node: the node must refuse the first
// three (another run, unknown writer) and ignore the end. What it sent goes to --summary as
// JSON (the run ids as 16 hex digits, the steps). Used by tests/system/forged_command.sh.
#include <dds/dds.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "rpsd/realtime/pacer.h"
#include "rpsd/transport/dds_participant.h"
#include "rpsd/transport/dds_qos_profile.h"
#include "rpsd/transport/dds_site_ports.h"
#include "rpsd/transport/messages.h"
#include "rpsd_messages.h"

namespace {

struct Options {
  std::uint32_t domain_id = 0;
  std::string dds_config;
  std::uint32_t test_id = 7, site_id = 1;
  double timeout_s = 60.0;
  std::string summary;
};

[[noreturn]] void usage(const std::string& problem) {
  std::cerr << "rpsd_forge_command: " << problem
            << "\nusage: rpsd_forge_command --domain N --dds-config FILE [--test ID] [--site ID] [--timeout S]"
               " [--summary FILE]\n";
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
    else if (flag == "--site")
      o.site_id = static_cast<std::uint32_t>(std::stoul(value));
    else if (flag == "--timeout")
      o.timeout_s = std::stod(value);
    else if (flag == "--summary")
      o.summary = value;
    else
      usage("unknown option " + flag);
  }
  if (o.dds_config.empty()) usage("--dds-config is required");
  return o;
}

struct Forged {
  std::string kind;
  std::uint64_t run_id;
  std::int64_t step;
  bool end_of_run;
};

}  // namespace

int main(int argc, char** argv) {
  using namespace rpsd::transport;
  const Options o = parse(argc, argv);
  DdsParticipant participant({o.domain_id, o.dds_config});
  // A coordinator's ports (command writer, feedback reader) as a lock-step coordinator has
  // them, and a heartbeat reader, all in the site's partition.
  DdsSitePorts ports(participant, o.test_id, o.site_id, participant.command_topic(), stream_writer_qos({}),
                     participant.feedback_topic(), stream_reader_qos({}));
  const DdsQos partition = site_partition_qos(o.test_id, o.site_id);
  const DdsEntity subscriber(dds_create_subscriber(participant.get(), partition.get(), nullptr),
                             "dds_create_subscriber");
  const DdsEntity heartbeats(
      dds_create_reader(subscriber.get(), participant.heartbeat_topic(), heartbeat_qos({}).get(), nullptr),
      "dds_create_reader(heartbeat)");

  // Wait for the run: a heartbeat naming it, this writer matched by the node's reader, and an
  // answer of that run to know its step.
  const std::int64_t until = rpsd::realtime::monotonic_now_ns() + static_cast<std::int64_t>(o.timeout_s * 1e9);
  std::uint64_t served = 0;
  std::int64_t newest_step = -1;
  rpsd_dds_NodeHeartbeat heartbeat{};
  rpsd_dds_Feedback feedback{};
  dds_sample_info_t info[1];
  while (served == 0 || newest_step < 0 || !ports.peer_matched()) {
    if (rpsd::realtime::monotonic_now_ns() > until) {
      std::cerr << "rpsd_forge_command: no run on site " << o.site_id << " within " << o.timeout_s << " s\n";
      return 1;
    }
    void* h[1] = {&heartbeat};
    while (dds_take(heartbeats.get(), h, info, 1, 1) > 0) {
      if (info[0].valid_data) served = heartbeat.serving_run_id;
    }
    void* f[1] = {&feedback};
    while (dds_take(ports.reader(), f, info, 1, 1) > 0) {
      if (info[0].valid_data && served != 0 && feedback.run_id == served) newest_step = feedback.step;
    }
    dds_sleepfor(DDS_MSECS(5));
  }

  const std::uint64_t foreign = draw_run_id();
  const std::vector<Forged> forged = {{"foreign-run", foreign, 9'000'000'000'000'000'000, false},
                                      {"copied-run-huge", served, 9'000'000'000'000'000'000, false},
                                      {"copied-run-next", served, newest_step + 1, false},
                                      {"copied-run-end", served, newest_step + 2, true}};
  for (const Forged& f : forged) {
    rpsd_dds_Command wire{};
    wire.test_id = o.test_id;
    wire.site_id = o.site_id;
    wire.run_id = f.run_id;
    wire.step = f.step;
    wire.time_s = 1.0;
    wire.control_period_s = 1.0 / 1024.0;
    wire.end_of_run = f.end_of_run;
    wire.channels = 1;
    wire.displacement_m[0] = 0.02;
    if (dds_write(ports.writer(), &wire) < 0) {
      std::cerr << "rpsd_forge_command: dds_write failed\n";
      return 1;
    }
  }
  // Reliable: give the samples time to reach the node before the writer goes.
  dds_sleepfor(DDS_MSECS(500));
  std::cout << "rpsd_forge_command: sent " << forged.size() << " forged commands to site " << o.site_id
            << " serving run " << run_id_text(served) << " at step " << newest_step << std::endl;
  if (!o.summary.empty()) {
    std::ofstream out(o.summary);
    out << "{\"served_run_id\": \"" << run_id_text(served) << "\", \"served_step\": " << newest_step
        << ", \"forged\": [";
    for (std::size_t i = 0; i < forged.size(); ++i) {
      out << (i ? ", " : "") << "{\"kind\": \"" << forged[i].kind << "\", \"run_id\": \""
          << run_id_text(forged[i].run_id) << "\", \"step\": " << forged[i].step << "}";
    }
    out << "]}\n";
  }
  return 0;
}
