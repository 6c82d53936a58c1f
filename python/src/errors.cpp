// C++ exceptions raised as the package's exception classes (python/rpsd/errors.py), each
// carrying the command line's message: the same types apps/rpsd/main.cpp maps to exit codes.
#include <stdexcept>

#include "bindings.h"
#include "rpsd/commands/run_outcome.h"
#include "rpsd/ground_motion/record_error.h"
#include "rpsd/output/results_files.h"
#include "rpsd/scenarios/config_error.h"

namespace py = pybind11;

namespace rpsd::python {

PythonError python_error_of(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const scenarios::ConfigError& e) {
    return {"ConfigError", e.what()};
  } catch (const ground_motion::RecordError& e) {
    return {"ConfigError", e.what()};
  } catch (const commands::TestStopped& e) {
    return {"TestStopped", e.what()};
  } catch (const commands::DryRunNotReady& e) {
    return {"NotReady", e.what()};
  } catch (const commands::RunNotReady& e) {
    return {"NotReady", e.what()};
  } catch (const output::ResultsNotWritten& e) {
    return {"ResultsNotWritten", std::string("results not written: ") + e.what()};
  } catch (const commands::RunInterrupted& e) {
    return {"KeyboardInterrupt", e.what()};
  } catch (const std::invalid_argument& e) {
    // Inputs that do not fit together, an output folder in use: bad input (exit code 2).
    return {"ConfigError", e.what()};
  } catch (const std::exception& e) {
    return {"Error", e.what()};
  } catch (...) {
    return {"Error", "an unknown C++ exception"};
  }
}

namespace {

void translate(std::exception_ptr error) {
  if (!error) return;
  try {
    std::rethrow_exception(error);
  } catch (const py::error_already_set&) {
    throw;  // a Python error under way: pybind11 restores it
  } catch (const py::builtin_exception&) {
    throw;  // pybind11's own (TypeError, ...)
  } catch (...) {
    const PythonError e = python_error_of(std::current_exception());
    const py::object cls = e.class_name == "KeyboardInterrupt"
                               ? py::reinterpret_borrow<py::object>(PyExc_KeyboardInterrupt)
                               : py::module_::import("rpsd.errors").attr(e.class_name.c_str());
    PyErr_SetObject(cls.ptr(), py::str(e.message).ptr());
  }
}

}  // namespace

void register_errors(py::module_&) { py::register_exception_translator(&translate); }

}  // namespace rpsd::python
