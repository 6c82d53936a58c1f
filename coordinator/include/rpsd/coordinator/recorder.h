// Hands step records from the real-time loop to a writer thread, which appends them to a
// CSV file (flushed every few hundred rows, so a crash loses at most the unflushed tail)
// and, if asked, keeps them in memory for metrics after the run.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "rpsd/coordinator/step_record.h"
#include "rpsd/realtime/spsc_queue.h"

namespace rpsd::coordinator {

struct RecorderOptions {
  // Keep every record in memory for finish(). Off when the metrics are computed as the test
  // runs: memory then stays flat however long the test is.
  bool keep_records = true;
  // Records the queue to the writer thread holds (712 bytes each): 4096 is 1 s at 4096 Hz.
  std::size_t queue_capacity = 1 << 12;
};

class Recorder {
 public:
  // Opens the CSV (empty path: none) and starts the writer. Not real-time safe.
  Recorder(const std::filesystem::path& csv, int channels, int dofs, RecorderOptions options = {});
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  // Real-time safe: never blocks; a full queue drops the record and counts it.
  void record(const StepRecord& r);
  // Waits (yielding) while the queue is full, so nothing is lost: for runs paced as fast as
  // possible, where a slower writer must slow the test down instead. Not real-time safe.
  void record_or_wait(const StepRecord& r);
  // Stops the writer after it has drained the queue; returns all records (none unless
  // RecorderOptions::keep_records). Not real-time safe.
  std::vector<StepRecord> finish();
  std::uint64_t dropped() const { return dropped_.load(); }

 private:
  void write_header();
  void write_row(const StepRecord& r);
  void take(const StepRecord& r);  // writer thread: one record off the queue
  void run();

  realtime::SpscQueue<StepRecord> queue_;
  std::ofstream csv_;
  int channels_, dofs_;
  bool keep_records_;
  std::vector<char> row_;  // one CSV row, built by the writer thread
  std::vector<StepRecord> records_;
  std::atomic<bool> stopping_{false};
  std::atomic<std::uint64_t> dropped_{0};
  std::thread writer_;
  bool finished_ = false;
};

}  // namespace rpsd::coordinator
