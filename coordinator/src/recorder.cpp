#include "rpsd/coordinator/recorder.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstring>
#include <stdexcept>

#include "rpsd/output/csv_number.h"

namespace rpsd::coordinator {

Recorder::Recorder(const std::filesystem::path& csv, int channels, int dofs, RecorderOptions options)
    : layout_(channels, static_cast<int>(options.held_channels.size()), dofs),
      queue_(options.queue_capacity, layout_.row_bytes()),
      channels_(channels),
      dofs_(dofs),
      keep_records_(options.keep_records),
      dof_view_(std::move(options.dof_view)),
      held_channels_(std::move(options.held_channels)),
      csv_every_steps_(options.csv_every_steps),
      observers_(std::move(options.observers)),
      idle_poll_(options.idle_poll),
      row_(static_cast<std::size_t>(64 + (output::kG10MaxChars + 1) *
                                             (10 + 7 * channels + 4 * dofs + 3 * static_cast<int>(dof_view_.size()) +
                                              3 * static_cast<int>(held_channels_.size())))) {
  if (csv_every_steps_ < 1) throw std::invalid_argument("Recorder: csv_every_steps below 1");
  if (idle_poll_.count() <= 0) throw std::invalid_argument("Recorder: an idle poll of no time");
  for (const DofViewColumn& v : dof_view_) {
    if (v.channel < 0 || v.channel >= channels) throw std::invalid_argument("Recorder: a DOF view of no channel");
  }
  if (!csv.empty()) {
    csv_path_ = csv;
    csv_.open(csv);
    if (!csv_) throw std::runtime_error(csv.string() + ": cannot write: " + std::strerror(errno));
    write_header();
    check_stream();
  }
  writer_ = std::thread([this] { run(); });
}

std::chrono::microseconds paced_idle_poll(double control_period_s) {
  const double fifth_us = control_period_s * 1e6 / 5.0;
  if (!(fifth_us >= 50.0)) return std::chrono::microseconds(50);  // NaN too
  return std::chrono::microseconds(static_cast<std::int64_t>(std::min(fifth_us, 1000.0)));
}

Recorder::~Recorder() {
  if (!finished_) finish();
}

void Recorder::record(const StepRecord& r) {
  if (!queue_.try_push_with([&](std::byte* row) { layout_.pack(r, row); }))
    dropped_.fetch_add(1, std::memory_order_relaxed);
}

void Recorder::record_or_wait(const StepRecord& r) {
  while (!queue_.try_push_with([&](std::byte* row) { layout_.pack(r, row); })) std::this_thread::yield();
}

void Recorder::take(const std::byte* row) {
  // Entries beyond the rows' channels, held forces and DOFs are never written (every record
  // of one recorder has the same counts), so they keep a new record's zeros.
  layout_.unpack(row, unpacked_);
  const StepRecord& r = unpacked_;
  if (keep_records_) records_.push_back(r);
  if (csv_.is_open() && !write_failed_.load(std::memory_order_relaxed) && r.step % csv_every_steps_ == 0) {
    write_row(r);
    check_stream();
  }
  for (RecordObserver* o : observers_) {
    o->observe(r);
    if (o->failed() && !write_failed_.load(std::memory_order_relaxed)) {
      write_error_ = o->failure();
      write_failed_.store(true, std::memory_order_release);
    }
  }
}

void Recorder::check_stream() {
  if (csv_ || write_failed_.load(std::memory_order_relaxed)) return;
  write_error_ = csv_path_.string() + ": " + std::strerror(errno);
  write_failed_.store(true, std::memory_order_release);
}

void Recorder::run() {
  const auto take_one = [this](const std::byte* row) { take(row); };
  std::size_t since_flush = 0;
  for (;;) {
    bool any = false;
    while (queue_.try_pop_with(take_one)) {
      any = true;
      if (csv_.is_open() && ++since_flush >= 256) {
        csv_.flush();
        check_stream();
        since_flush = 0;
      }
    }
    if (!any) {
      if (stopping_.load(std::memory_order_acquire)) {
        // One last drain: the producer stopped before setting the flag.
        while (queue_.try_pop_with(take_one)) {
        }
        break;
      }
      if (csv_.is_open() && since_flush > 0) {
        csv_.flush();
        check_stream();
        since_flush = 0;
      }
      for (RecordObserver* o : observers_) o->idle();
      // Idle until the next poll, or until finish() asks for the last drain. The loop never
      // touches the lock: it only fills the queue.
      std::unique_lock lock(wake_mutex_);
      wake_.wait_for(lock, idle_poll_, [this] { return stopping_.load(std::memory_order_acquire); });
    }
  }
  if (csv_.is_open()) {
    csv_.close();
    check_stream();
  }
}

std::vector<StepRecord> Recorder::finish() {
  {
    const std::lock_guard lock(wake_mutex_);
    stopping_.store(true, std::memory_order_release);
  }
  wake_.notify_one();
  if (writer_.joinable()) writer_.join();
  finished_ = true;
  return std::move(records_);
}

void Recorder::write_header() {
  csv_ << "step,time_s,ground_acceleration_m_per_s2";
  for (int c = 0; c < channels_; ++c) {
    csv_ << ",target_m_ch" << c << ",command_m_ch" << c << ",measured_m_ch" << c << ",measured_force_n_ch" << c
         << ",specimen_restoring_force_n_ch" << c << ",tracking_indicator_m2_ch" << c;
  }
  for (int d = 0; d < dofs_; ++d) {
    csv_ << ",displacement_m_dof" << d << ",velocity_m_per_s_dof" << d << ",acceleration_m_per_s2_dof" << d
         << ",restoring_force_n_dof" << d;
  }
  csv_ << ",input_energy_j,kinetic_energy_j,damping_energy_j,restoring_energy_j,node_status,limit_flags";
  for (int c = 0; c < channels_; ++c) csv_ << ",round_trip_s_ch" << c;
  csv_ << ",cycle_lateness_s,feedback_age_periods";
  // A setup's channels: the columns above are its actuators' strokes and load-cell forces;
  // these its DOFs' targets, displacements and forces, in the DOF's own units.
  for (const DofViewColumn& v : dof_view_) {
    const char* displacement = v.rotation ? "rad" : "m";
    csv_ << ",dof_target_" << displacement << "_ch" << v.channel << ",dof_measured_" << displacement << "_ch"
         << v.channel << (v.rotation ? ",dof_moment_n_m_ch" : ",dof_force_n_ch") << v.channel;
  }
  // The channels in force control: the force commanded, the piston's stroke and its force.
  for (const int c : held_channels_) {
    csv_ << ",held_force_command_n_ch" << c << ",held_measured_m_ch" << c << ",held_measured_force_n_ch" << c;
  }
  csv_ << "\n";
}

void Recorder::write_row(const StepRecord& r) {
  // What printf's %.10g writes (format_g10), built in one buffer and handed to the stream once.
  char* const row = row_.data();
  char* const end = row + row_.size();
  char* out = row;
  const auto put = [&](double v) {
    *out++ = ',';
    out = output::format_g10(out, v);
  };
  out = std::to_chars(out, end, r.step).ptr;
  put(r.time_s);
  put(r.ground_acceleration_m_per_s2);
  for (int c = 0; c < channels_; ++c) {
    put(r.target_m[c]);
    put(r.command_m[c]);
    put(r.measured_m[c]);
    put(r.measured_force_n[c]);
    put(r.specimen_restoring_force_n[c]);
    put(r.tracking_indicator_m2[c]);
  }
  for (int d = 0; d < dofs_; ++d) {
    put(r.displacement_m[d]);
    put(r.velocity_m_per_s[d]);
    put(r.acceleration_m_per_s2[d]);
    put(r.restoring_force_n[d]);
  }
  put(r.input_energy_j);
  put(r.kinetic_energy_j);
  put(r.damping_energy_j);
  put(r.restoring_energy_j);
  *out++ = ',';
  out = std::to_chars(out, end, r.node_status).ptr;
  *out++ = ',';
  out = std::to_chars(out, end, r.limit_flags).ptr;
  for (int c = 0; c < channels_; ++c) put(r.round_trip_s[c]);
  put(r.cycle_lateness_s);
  *out++ = ',';
  out = std::to_chars(out, end, static_cast<int>(r.feedback_age_periods)).ptr;
  for (const DofViewColumn& v : dof_view_) {
    put(r.dof_target_m[v.channel]);
    put(r.dof_measured_m[v.channel]);
    put(r.dof_force_n[v.channel]);
  }
  for (std::size_t k = 0; k < held_channels_.size(); ++k) {
    put(r.held_force_command_n[k]);
    put(r.held_measured_m[k]);
    put(r.held_measured_force_n[k]);
  }
  *out++ = '\n';
  csv_.write(row, out - row);
}

}  // namespace rpsd::coordinator
