// _rpsd.run_scenario: `rpsd run` in this process. The study runs on a worker thread with the
// GIL released; the calling thread wakes every 100 ms, takes the GIL and lets Python handle its
// signals, so Ctrl-C (KeyboardInterrupt) asks the run to stop in order, as SIGINT does on the
// command line, waits for its end and is raised then. Nothing here is on the real-time path:
// the loop runs inside the study as it does under the command line.
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "bindings.h"
#include "rpsd/commands/overrides.h"
#include "rpsd/commands/run_outcome.h"
#include "rpsd/commands/run_scenario.h"
#include "rpsd/output/results_files.h"

namespace py = pybind11;

namespace rpsd::python {
namespace {

// The scenario as `rpsd run` reads it; a single test writes results.h5 and the CSV tables
// (format "both") unless the caller names a format (the argument, or output.format in `set`).
studies::StudyDocument load_for_python(const std::string& scenario, const std::vector<scenarios::Override>& set,
                                       commands::RunOverrideOptions extra, const hybrid_test::ExternalParts& parts) {
  studies::StudyDocument file = commands::load_run_scenario(scenario, commands::run_overrides(extra, set), parts);
  if (!extra.format.empty() || !commands::is_single_test(file)) return file;
  extra.format = "both";
  return commands::load_run_scenario(scenario, commands::run_overrides(extra, set), parts);
}

// Runs the study on a worker thread; returns when it ended. A Python signal handler's
// exception (KeyboardInterrupt) raised meanwhile sets the stop request and is returned.
std::optional<py::error_already_set> run_watching_signals(const studies::StudyDocument& file,
                                                          commands::ScenarioRunOptions& options, studies::StudyRun& run,
                                                          std::exception_ptr& failure) {
  std::atomic<bool> stop{false};
  options.stop_request = &stop;
  std::mutex mutex;
  std::condition_variable ended;
  bool done = false;
  std::optional<py::error_already_set> pending;
  py::gil_scoped_release nogil;
  std::thread worker([&] {
    try {
      run = commands::run_scenario(file, options);
    } catch (...) {
      failure = std::current_exception();
    }
    const std::lock_guard lock(mutex);
    done = true;
    ended.notify_all();
  });
  std::unique_lock lock(mutex);
  while (!ended.wait_for(lock, std::chrono::milliseconds(100), [&] { return done; })) {
    if (pending) continue;  // asked to stop: wait for the run's end
    lock.unlock();
    {
      const py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) {
        pending.emplace();  // fetches the exception the handler raised
        stop.store(true, std::memory_order_relaxed);
      }
    }
    lock.lock();
  }
  lock.unlock();
  worker.join();
  return pending;
}

py::dict run_scenario(const std::string& scenario, const std::string& out, const OverrideTexts& set,
                      const std::string& record, const std::string& format, bool prepare, const py::dict& callables) {
  const std::vector<scenarios::Override> overrides = to_overrides(set);
  const hybrid_test::ExternalParts parts = external_parts(callables);
  std::optional<studies::StudyDocument> file;
  {
    const py::gil_scoped_release nogil;
    commands::RunOverrideOptions given;
    given.record = record;
    given.format = format;
    file.emplace(load_for_python(scenario, overrides, given, parts));
  }
  commands::ScenarioRunOptions options;
  options.out = out;
  options.prepare = prepare;
  studies::StudyRun run;
  std::exception_ptr failure;
  std::optional<py::error_already_set> interrupted = run_watching_signals(*file, options, run, failure);
  if (interrupted) throw std::move(*interrupted);
  if (failure) std::rethrow_exception(failure);
  py::dict done;
  done["single_test"] = commands::is_single_test(*file);
  done["result"] = hybrid_test::result_name(run.result);
  // The exception a run that did not complete ends with (rpsd.TestStopped, ...): its class and
  // message, raised by the package once it has loaded what the run recorded.
  try {
    commands::throw_unless_completed(run, (std::filesystem::path(out) / "summary.json").string());
  } catch (...) {
    const PythonError e = python_error_of(std::current_exception());
    done["error_class"] = e.class_name;
    done["error"] = e.message;
  }
  return done;
}

// Prepares an output folder as `rpsd run --out` does (created, refused if it holds anything).
void prepare_folder(const std::string& out, bool replace) { output::prepare_results_folder(out, replace); }

}  // namespace

void register_run(py::module_& m) {
  m.def("run_scenario", &run_scenario, py::arg("scenario"), py::arg("out"), py::arg("overrides"), py::arg("record"),
        py::arg("format"), py::arg("prepare"), py::arg("callables") = py::dict(),
        "Runs a scenario file into `out` as `rpsd run` does; returns {single_test, result[, error_class, error]}.");
  m.def("prepare_folder", &prepare_folder, py::arg("out"), py::arg("replace") = false,
        "Makes `out` ready for one run as `rpsd run --out` does.");
}

}  // namespace rpsd::python
