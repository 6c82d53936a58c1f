// The parts of the extension `_rpsd`, each registered on the module by its own file. The
// package rpsd (../rpsd/) wraps them; users call rpsd.run, rpsd.validate, ... not these.
#pragma once

#include <pybind11/pybind11.h>

#include <exception>
#include <string>
#include <tuple>
#include <vector>

#include "rpsd/hybrid_test/external_parts.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::python {

// C++ exceptions to the package's exception classes (rpsd.errors), as apps/rpsd/main.cpp maps
// the same types to exit codes.
void register_errors(pybind11::module_& m);
// The class in rpsd.errors ("KeyboardInterrupt" for a run interrupted in order) and the
// message a C++ exception is raised with in Python.
struct PythonError {
  std::string class_name;
  std::string message;
};
PythonError python_error_of(std::exception_ptr error);
// Overrides as the package passes them (rpsd._convert.override_texts): key, YAML value, origin.
using OverrideTexts = std::vector<std::tuple<std::string, std::string, std::string>>;
std::vector<scenarios::Override> to_overrides(const OverrideTexts& texts);
// The Python objects rpsd.run(..., callables={name: object}) gives, as the parts a scenario
// names with `kind: external` (a compensator, a structure's restoring force). Needs the GIL.
hybrid_test::ExternalParts external_parts(const pybind11::dict& callables);
// _rpsd.run_scenario: a scenario run into a folder on a worker thread, Ctrl-C honoured.
void register_run(pybind11::module_& m);
// _rpsd.validate_json, dry_run_json, analyze_servo_json, integrator_properties_json.
void register_checks(pybind11::module_& m);

}  // namespace rpsd::python
