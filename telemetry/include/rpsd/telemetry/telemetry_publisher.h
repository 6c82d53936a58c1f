// The coordinator's side of a test's telemetry: fed with the step records by the recorder's
// writer thread (a coordinator::RecordObserver), never by the loop, it keeps every k-th step
// (at most max_samples_per_s of test time), sends them 32 to a batch with the run's status,
// and sends events (the run starting and ending, limits acting, nodes changing state,
// operators' commands) as they happen. Writes never wait on a reader (docs/telemetry.md).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>

#include "rpsd/coordinator/live_counters.h"
#include "rpsd/coordinator/record_observer.h"
#include "rpsd/telemetry/effective_damping_identifier.h"
#include "rpsd/telemetry/telemetry_frame.h"

namespace rpsd::telemetry {

// Where and how a test publishes: its DDS domain and Cyclone configuration (with DDS Security,
// the XML names the coordinator's identity), its test id (partition), name and sample rate.
struct TelemetryPublisherConfig {
  std::uint32_t domain_id = 0;
  std::string dds_config;  // Cyclone XML file; empty: CYCLONEDDS_URI or Cyclone's defaults
  std::uint32_t test_id = 1;
  std::string test_name;
  double max_samples_per_s = 256.0;  // of test time: every k-th step, k = ceil(rate / this)
};

// The run, once built (TelemetryPublisher::start).
struct TelemetryRunInfo {
  std::uint64_t run_id = 0;
  std::int64_t steps_planned = 0;
  double control_rate_hz = 0.0;
  bool real_time = false;
  int channels = 0;
  double predicted_effective_damping = kUnknown;
  // The lowest mode the identified damping is projected on (unknown: none identified).
  LowestMode lowest_mode;
  // The loop's own counts (overruns, late feedback), read relaxed; null: none.
  const coordinator::LiveCounters* live = nullptr;
};

// How the run ended, in its summary's words.
struct TelemetryRunEnd {
  std::string stopped_by = "completed";
  bool stopped_by_limit = false;  // a coordinator limit stopped it
  std::int64_t overruns = 0, late_feedback = 0;
};

class TelemetryPublisher final : public coordinator::RecordObserver {
 public:
  // Joins the domain and writes in the test's partition. Not real-time safe; throws
  // transport::DdsError or std::runtime_error (an unreadable configuration file).
  explicit TelemetryPublisher(const TelemetryPublisherConfig& config);
  ~TelemetryPublisher() override;
  TelemetryPublisher(const TelemetryPublisher&) = delete;
  TelemetryPublisher& operator=(const TelemetryPublisher&) = delete;

  // The run is built: publishes "run started". Before the first record is observed.
  void start(const TelemetryRunInfo& run);
  // The recorder's writer thread: each record in order.
  void observe(const coordinator::StepRecord& record) override;
  // The recorder's writer thread, its queue empty: a batch waiting longer than ~100 ms goes.
  void idle() override;
  // Any thread: an event (an operator's command...); test_id and run_id are filled in when 0,
  // and its step and time (both 0) with the last step recorded (-1: none yet).
  void publish_event(const TelemetryEvent& event);
  // Any thread: the run is held (an operator's hold) or running again.
  void set_held(bool held);
  // After the recorder finished: the last batch, the status "ended" with why, a limit event
  // first when a coordinator limit stopped it, then "run ended". The run's LiveCounters are no
  // longer read (the run may be gone): its final counts are given here.
  void end(const TelemetryRunEnd& end);

  // Steps kept out of every k: the decimation (1: every step).
  std::int64_t keep_every_steps() const;
  std::uint64_t batches_sent() const;
  std::int64_t dropped_samples() const;  // kept samples whose batch a write refused

 private:
  struct Parts;
  std::unique_ptr<Parts> parts_;
  mutable std::mutex mutex_;  // the writer thread, operators' threads and the building thread
};

// Copies `text` into a fixed text field, cut to fit, always terminated.
template <std::size_t N>
void set_text(std::array<char, N>& field, std::string_view text) {
  const std::size_t n = std::min(text.size(), N - 1);
  std::copy_n(text.data(), n, field.begin());
  field[n] = '\0';
}

}  // namespace rpsd::telemetry
