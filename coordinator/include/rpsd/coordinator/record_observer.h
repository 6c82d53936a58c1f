// Whoever watches a run's records as they are written (the telemetry publisher, the terminal's
// progress): called by the recorder's writer thread, never by the loop, so a watcher may
// allocate, lock and do I/O without touching the real-time path. A slow watcher slows the
// writer only: the loop drops and counts records in real time, waits as fast as possible.
#pragma once

#include <string>

#include "rpsd/coordinator/step_record.h"

namespace rpsd::coordinator {

class RecordObserver {
 public:
  virtual ~RecordObserver() = default;
  // Each record the writer takes, in order, after its CSV row.
  virtual void observe(const StepRecord& record) = 0;
  // The queue is empty (about every millisecond while the loop is slower than the writer).
  virtual void idle() {}
  // A watcher that writes the results (results.h5) and failed: the recorder then reports it as
  // its own failed write (Recorder::write_failed), which stops the test as a failed CSV does.
  virtual bool failed() const { return false; }
  virtual std::string failure() const { return {}; }
};

}  // namespace rpsd::coordinator
