// One test's results as an HDF5 file, results.h5 (docs/results-format.md): the inputs, and for
// each run (the test, its reference) the coordinator's, the experimental channels' and the
// recorded DOFs' histories, one dataset per CSV column with its unit. Every group and dataset
// is made before SWMR writing starts; then each run's observer, called by its recorder's
// writer thread (never the loop's), buffers records and appends them in blocks, flushing the
// file at least once a second. Not real-time safe (it never runs on the loop's thread).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rpsd/coordinator/recorder.h"

namespace rpsd::hdf5_output {

// What the file says of the inputs (/global_model).
struct Hdf5Inputs {
  std::string scenario_name;
  std::string effective_yaml;                      // the scenario as read, with overrides
  std::vector<std::filesystem::path> input_files;  // embedded whole, each with its SHA-256
};

// The columns of one run, as its recorder writes them (RecorderOptions).
struct Hdf5RunLayout {
  std::string name;  // the run's group: "test" or "reference"
  double control_rate_hz = 0.0;
  int channels = 0;
  std::vector<std::int64_t> dof_numbers;  // the recorded model DOFs, in the records' order
  std::vector<coordinator::DofViewColumn> dof_view;
  std::vector<int> held_channels;  // link channels, in the records' held order
  // Only the steps n with n % every_steps == 0 are written (output.histories: decimated).
  std::int64_t every_steps = 1;
};

// A quantity's unit from its name's suffix, as rpsd names them ("_m": "m", "_percent": "%"; "1"
// for none): the criteria's and the study tables' `units`.
std::string unit_of_name(const std::string& name);

class Hdf5Results {
 public:
  // Creates `path` (replacing it), writes the inputs and every run's empty datasets, and starts
  // SWMR writing. With a `group`: opens the existing `path` (a sweep's or batch's file,
  // hdf5_batch.h) and writes all that under a new group of that name instead, beside the
  // cases before it. Throws std::runtime_error naming the file on any failure.
  Hdf5Results(const std::filesystem::path& path, const Hdf5Inputs& inputs, const std::vector<Hdf5RunLayout>& runs,
              const std::string& group = {});
  // Closes the file if close() was not called (errors then go unreported).
  ~Hdf5Results();
  Hdf5Results(const Hdf5Results&) = delete;
  Hdf5Results& operator=(const Hdf5Results&) = delete;

  // Run `run`'s observer (in the order of the layouts), for its RecorderOptions::observers.
  coordinator::RecordObserver& observer(std::size_t run);
  // Writes what every run holds, flushes and closes the file; call after every recorder has
  // finished. Returns the first error (empty: none).
  std::string close();
  // The first write that failed ("FILE: what"); empty while none has. Any thread.
  std::string error() const;

  // After close(): adds /analysis, the criteria of summary.json (its "channels", "dofs",
  // "benchmark_criteria", "energy_error_j") and summary.json whole; under `group` when the
  // test is a case of a sweep's or batch's file. Throws std::runtime_error.
  static void write_analysis(const std::filesystem::path& path, const nlohmann::json& summary,
                             const std::string& group = {});

  // How long records may wait in memory before they are written and the file flushed.
  static constexpr std::chrono::milliseconds kFlushEvery{500};
  // Records a run buffers before it writes them (and the chunk length of every dataset).
  static constexpr std::size_t kBlockSteps = 4096;

  class RunWriter;

 private:
  void fail(const std::string& what);

  std::filesystem::path path_;
  std::int64_t file_ = -1;  // hid_t
  std::mutex hdf5_mutex_;   // every HDF5 call after construction: two writer threads share the file
  std::vector<std::unique_ptr<RunWriter>> runs_;
  mutable std::mutex error_mutex_;
  std::string error_;
  std::atomic<bool> failed_{false};
  bool closed_ = false;
  friend class RunWriter;
};

}  // namespace rpsd::hdf5_output
