// Hands step records from the real-time loop to a writer thread, which appends them to a
// CSV file (flushed every few hundred rows, so a crash loses at most the unflushed tail)
// and, if asked, keeps them in memory for metrics after the run. Every write is checked: a
// failed one (a full disk) is reported to the loop through write_failed(), never ignored.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "rpsd/coordinator/record_layout.h"
#include "rpsd/coordinator/record_observer.h"
#include "rpsd/coordinator/step_record.h"
#include "rpsd/realtime/spsc_row_queue.h"

namespace rpsd::coordinator {

// A channel whose DOF view the CSV carries (a setup drives it): its columns' units follow the
// DOF's motion (m and N, or rad and N·m).
struct DofViewColumn {
  int channel = 0;
  bool rotation = false;
};

struct RecorderOptions {
  // Keep every record in memory for finish(). Off when the metrics are computed as the test
  // runs: memory then stays flat however long the test is.
  bool keep_records = true;
  // Records the queue to the writer thread holds, each packed to the test's channels, held
  // forces and DOFs (record_layout.h: 192 bytes for one channel and one DOF): 4096 is 1 s at
  // 4096 Hz.
  std::size_t queue_capacity = 1 << 12;
  // The channels a setup drives, whose DOF view follows each row's other columns (empty:
  // none, and the file is as without setups).
  std::vector<DofViewColumn> dof_view = {};
  // The link channels in force control, in their order (held_force.h), whose columns follow
  // the DOF view: held_force_command_n_chC, held_measured_m_chC, held_measured_force_n_chC
  // (empty: none, and the file is as without them).
  std::vector<int> held_channels = {};
  // The CSV keeps the rows of the steps n with n % csv_every_steps == 0 only (output.histories:
  // decimated); the observers still see every record. 1: every row.
  std::int64_t csv_every_steps = 1;
  // Called by the writer thread with each record after its row, in order (the telemetry, the
  // terminal's progress); they must outlive the recorder's finish(). Empty: none.
  std::vector<RecordObserver*> observers = {};
  // How long the writer idles on an empty queue. Each wake-up may take a core from the loop
  // (on two cores, polls every 200 us preempted the as-fast-as-possible SDOF loop ~170 times
  // a run, every 1 ms ~47: docs/performance.md), so a run as fast as possible polls every
  // 1 ms; a paced run polls within a fifth of its period (paced_idle_poll), so that each row
  // reaches the file within about a period of its step and a kill -9 loses no more than the
  // step in flight (tests/system/kill_coordinator.sh).
  std::chrono::microseconds idle_poll{1000};
};

// The writer's idle poll for a run paced at control_period_s: a fifth of the period, at most
// 1 ms and at least 50 us.
std::chrono::microseconds paced_idle_poll(double control_period_s);

class Recorder {
 public:
  // Opens the CSV (empty path: none) and starts the writer. Not real-time safe.
  Recorder(const std::filesystem::path& csv, int channels, int dofs, RecorderOptions options = {});
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  // Real-time safe: never blocks; a full queue drops the record and counts it. The queue
  // carries the record's first channels, held forces and DOFs, as many as the recorder was
  // built for (its channels, RecorderOptions::held_channels, its DOFs); what the writer's
  // CSV and observers see of them is the record as the loop wrote it.
  void record(const StepRecord& r);
  // Waits (yielding) while the queue is full, so nothing is lost: for runs paced as fast as
  // possible, where a slower writer must slow the test down instead. Not real-time safe.
  void record_or_wait(const StepRecord& r);
  // The same without a StepRecord between: write(std::byte* row) writes a row of layout()
  // (RecordLayout::Row) in place, in the queue's next row. record_in_place drops and counts
  // the record when the queue is full (false, `write` not called); record_or_wait_in_place
  // waits, as record_or_wait. The row stays as written until the next record: the caller
  // may read it back until then. Real-time safe when write is (but for the wait).
  template <typename Write>
  bool record_in_place(Write&& write) {
    if (queue_.try_push_with(write)) return true;
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  template <typename Write>
  void record_or_wait_in_place(Write&& write) {
    while (!queue_.try_push_with(write)) std::this_thread::yield();
  }
  // How each row is laid out (the recorder's channels, held forces and DOFs).
  const RecordLayout& layout() const { return layout_; }
  // Stops the writer after it has drained the queue; returns all records (none unless
  // RecorderOptions::keep_records). Not real-time safe.
  std::vector<StepRecord> finish();
  std::uint64_t dropped() const { return dropped_.load(); }
  // A write to the CSV failed: the rows from then on are not on disk. Real-time safe.
  bool write_failed() const { return write_failed_.load(std::memory_order_acquire); }
  // What failed ("FILE: No space left on device"); empty while nothing has.
  std::string write_error() const { return write_failed() ? write_error_ : std::string(); }

 private:
  void write_header();
  void write_row(const StepRecord& r);
  void take(const std::byte* row);  // writer thread: one record off the queue
  void run();
  void check_stream();  // writer thread: a failed write becomes write_failed()

  RecordLayout layout_;
  realtime::SpscRowQueue queue_;
  StepRecord unpacked_;  // writer thread: each row unpacked, in turn
  std::filesystem::path csv_path_;
  std::ofstream csv_;
  int channels_, dofs_;
  bool keep_records_;
  std::vector<DofViewColumn> dof_view_;
  std::vector<int> held_channels_;  // the link channels of the held forces, in their order
  std::int64_t csv_every_steps_;
  std::vector<RecordObserver*> observers_;
  std::chrono::microseconds idle_poll_;
  std::vector<char> row_;  // one CSV row, built by the writer thread
  std::vector<StepRecord> records_;
  std::atomic<bool> stopping_{false};
  std::mutex wake_mutex_;  // the writer's idle wait and finish() only, never the loop
  std::condition_variable wake_;
  std::atomic<std::uint64_t> dropped_{0};
  std::string write_error_;  // set by the writer thread before write_failed_
  std::atomic<bool> write_failed_{false};
  std::thread writer_;
  bool finished_ = false;
};

}  // namespace rpsd::coordinator
