#include "rpsd/monitor/recorded_telemetry_source.h"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>
#include <thread>

#include <nlohmann/json.hpp>

namespace rpsd::monitor {
namespace {

namespace fs = std::filesystem;

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(line.substr(start, comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return cells;
}

template <std::size_t N>
void copy_text(std::array<char, N>& to, const std::string& from) {
  const std::size_t n = std::min(from.size(), N - 1);
  std::memcpy(to.data(), from.data(), n);
  to[n] = '\0';
}

}  // namespace

std::size_t rows_due(const std::vector<telemetry::TelemetrySample>& rows, double steps_elapsed) {
  if (rows.empty()) return 0;
  const std::int64_t first = rows.front().step;
  const auto after = std::upper_bound(rows.begin(), rows.end(), steps_elapsed,
                                      [first](double elapsed, const telemetry::TelemetrySample& s) {
                                        return elapsed < static_cast<double>(s.step - first + 1);
                                      });
  return static_cast<std::size_t>(after - rows.begin());
}

std::vector<telemetry::TelemetrySample> read_time_history(const fs::path& csv) {
  std::ifstream in(csv);
  if (!in) throw std::runtime_error(csv.string() + ": cannot be read");
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(csv.string() + ":1: no header");
  std::map<std::string, std::size_t, std::less<>> column;
  std::vector<std::string> header;  // owned: `line` is read over
  for (const std::string_view name : split(line)) header.emplace_back(name);
  for (std::size_t i = 0; i < header.size(); ++i) column[header[i]] = i;
  const auto index = [&](const std::string& name) -> std::size_t {
    const auto it = column.find(name);
    if (it == column.end()) throw std::runtime_error(csv.string() + ":1: no column " + name);
    return it->second;
  };
  int channels = 0;
  while (channels < transport::kMaxChannels && column.count("target_m_ch" + std::to_string(channels)) != 0) ++channels;
  struct ChannelColumns {
    std::size_t target, command, measured, force, round_trip;
  };
  std::vector<ChannelColumns> ch;
  for (int c = 0; c < channels; ++c) {
    const std::string s = "_ch" + std::to_string(c);
    ch.push_back({index("target_m" + s), index("command_m" + s), index("measured_m" + s), index("measured_force_n" + s),
                  index("round_trip_s" + s)});
  }
  const std::size_t step = index("step"), time = index("time_s"), status = index("node_status"),
                    flags = index("limit_flags"), lateness = index("cycle_lateness_s"),
                    age = index("feedback_age_periods");
  std::vector<telemetry::TelemetrySample> samples;
  for (int line_number = 2; std::getline(in, line); ++line_number) {
    if (line.empty()) continue;
    const std::vector<std::string_view> cells = split(line);
    const auto cell = [&](std::size_t i) -> std::string_view {
      if (i >= cells.size()) {
        throw std::runtime_error(csv.string() + ":" + std::to_string(line_number) + ": no column " + header[i]);
      }
      return cells[i];
    };
    const auto fail = [&](std::size_t i) {
      return std::runtime_error(csv.string() + ":" + std::to_string(line_number) + ": " + header[i] +
                                " is not a number: " + std::string(cell(i)));
    };
    const auto real = [&](std::size_t i) {
      double v = 0.0;
      const std::string_view t = cell(i);
      const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
      if (r.ec != std::errc() || r.ptr != t.data() + t.size()) throw fail(i);
      return v;
    };
    const auto whole = [&](std::size_t i) {
      std::int64_t v = 0;
      const std::string_view t = cell(i);
      const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
      if (r.ec != std::errc() || r.ptr != t.data() + t.size()) throw fail(i);
      return v;
    };
    telemetry::TelemetrySample s;
    s.step = whole(step);
    s.time_s = real(time);
    s.channels = static_cast<std::uint8_t>(channels);
    for (int c = 0; c < channels; ++c) {
      s.target_m[c] = real(ch[c].target);
      s.command_m[c] = real(ch[c].command);
      s.measured_m[c] = real(ch[c].measured);
      s.measured_force_n[c] = real(ch[c].force);
      s.round_trip_s[c] = real(ch[c].round_trip);
    }
    s.node_status = static_cast<std::uint32_t>(whole(status));
    s.limit_flags = static_cast<std::uint32_t>(whole(flags));
    s.cycle_lateness_s = real(lateness);
    s.feedback_age_periods = static_cast<std::uint8_t>(whole(age));
    samples.push_back(s);
  }
  return samples;
}

RecordedTelemetrySource::RecordedTelemetrySource(const fs::path& folder, RecordedRunOptions options)
    : options_(options), samples_(read_time_history(folder / "time_history.csv")) {
  std::ifstream in(folder / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in, nullptr, false);
  stopped_by_ = "completed";
  if (summary.is_object()) {
    if (summary.contains("result") && summary["result"].is_string()) stopped_by_ = summary["result"].get<std::string>();
    const auto sb = summary.find("stopped_by");
    if (sb != summary.end() && sb->is_object() && sb->contains("reason") && (*sb)["reason"].is_string()) {
      stopped_by_ = (*sb)["reason"].get<std::string>();
    }
    if (summary.contains("scenario") && summary["scenario"].is_string())
      test_name_ = summary["scenario"].get<std::string>();
    // output.histories: decimated keeps every k-th row; the run's counts are in its timing.
    const auto h = summary.find("histories");
    const auto t = summary.find("timing");
    if (h != summary.end() && h->is_object() && h->value("kept", "") == "decimated" && t != summary.end() &&
        t->is_object()) {
      if (t->contains("overruns") && (*t)["overruns"].is_number_integer())
        run_overruns_ = (*t)["overruns"].get<std::int64_t>();
      if (t->contains("late_feedback") && (*t)["late_feedback"].is_number_integer())
        run_late_feedback_ = (*t)["late_feedback"].get<std::int64_t>();
    }
  }
  if (test_name_.empty()) test_name_ = folder.filename().string();
  started_ = std::chrono::steady_clock::now();
}

std::size_t RecordedTelemetrySource::due_samples() const {
  if (options_.steps_per_second <= 0.0) return samples_.size();
  const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  return rows_due(samples_, elapsed_s * options_.steps_per_second);
}

std::size_t RecordedTelemetrySource::take(std::vector<telemetry::TelemetryBatch>& batches,
                                          std::vector<telemetry::TelemetryEvent>& events) {
  const std::lock_guard lock(mutex_);
  std::size_t added = 0;
  const auto event = [&](telemetry::EventKind kind, const telemetry::TelemetrySample* at, const std::string& text) {
    telemetry::TelemetryEvent e;
    e.test_id = options_.test_id;
    e.run_id = options_.run_id;
    e.kind = kind;
    if (at != nullptr) {
      e.step = at->step;
      e.time_s = at->time_s;
    }
    e.wall_clock_unix_ns =
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
            .count();
    copy_text(e.text, text);
    events.push_back(e);
    ++added;
  };
  if (!start_sent_) {
    start_sent_ = true;
    event(telemetry::EventKind::kRunStarted, samples_.empty() ? nullptr : &samples_.front(), "replay of " + test_name_);
  }
  const std::size_t due = due_samples();
  while (sent_ < due) {
    telemetry::TelemetryBatch b;
    b.sequence = sequence_++;
    while (sent_ < due && b.count < telemetry::kSamplesPerBatch) {
      const telemetry::TelemetrySample& s = samples_[sent_++];
      if (s.limit_flags != last_limit_flags_ && s.limit_flags != 0) {
        event(telemetry::EventKind::kLimit, &s, "limit flags " + std::to_string(s.limit_flags));
      }
      if (s.node_status != last_node_status_) {
        event(telemetry::EventKind::kNodeStatus, &s, "node status " + std::to_string(s.node_status));
      }
      worst_age_ = std::max(worst_age_, s.feedback_age_periods);
      if (s.cycle_lateness_s > 0.0) ++overruns_;
      if (s.feedback_age_periods > 0) ++late_feedback_;
      last_limit_flags_ = s.limit_flags;
      last_node_status_ = s.node_status;
      b.samples[b.count++] = s;
    }
    telemetry::TelemetryStatus& st = b.status;
    st.test_id = options_.test_id;
    st.run_id = options_.run_id;
    copy_text(st.test_name, test_name_);
    st.state = sent_ == samples_.size() ? telemetry::RunState::kEnded : telemetry::RunState::kRunning;
    // In steps, not rows: a decimated history's rows are k steps apart.
    st.steps_done = samples_[sent_ - 1].step;
    st.steps_planned = samples_.back().step;
    if (samples_.size() > 1) {
      const double span_s = samples_.back().time_s - samples_.front().time_s;
      st.control_rate_hz =
          span_s > 0.0 ? static_cast<double>(samples_.back().step - samples_.front().step) / span_s : 0.0;
    }
    st.channels = samples_.front().channels;
    st.worst_feedback_age_periods = worst_age_;
    const bool ended = st.state == telemetry::RunState::kEnded;
    st.overruns = ended && run_overruns_ >= 0 ? run_overruns_ : overruns_;
    st.late_feedback = ended && run_late_feedback_ >= 0 ? run_late_feedback_ : late_feedback_;
    st.predicted_effective_damping = options_.predicted_effective_damping;
    if (st.state == telemetry::RunState::kEnded) copy_text(st.stopped_by, stopped_by_);
    batches.push_back(b);
    ++added;
  }
  if (sent_ == samples_.size() && !end_sent_) {
    end_sent_ = true;
    event(telemetry::EventKind::kRunEnded, samples_.empty() ? nullptr : &samples_.back(), stopped_by_);
  }
  return added;
}

bool RecordedTelemetrySource::wait(std::chrono::milliseconds timeout) {
  {
    const std::lock_guard lock(mutex_);
    if (!start_sent_ || sent_ < due_samples() || (sent_ == samples_.size() && !end_sent_)) return true;
  }
  std::this_thread::sleep_for(std::min(timeout, std::chrono::milliseconds(20)));
  const std::lock_guard lock(mutex_);
  return sent_ < due_samples();
}

bool RecordedTelemetrySource::alive() const {
  const std::lock_guard lock(mutex_);
  return !end_sent_;
}

}  // namespace rpsd::monitor
