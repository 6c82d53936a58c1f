// The checks and analyses of the command line as JSON text, the very JSON its `--json` prints
// (rpsd/commands/): rpsd.validate, rpsd.dry_run, rpsd.analyze_servo and
// rpsd.integrator_properties parse it into Python objects. The GIL is released while they work.
#include <pybind11/stl.h>

#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "bindings.h"
#include "rpsd/commands/analysis_reports.h"
#include "rpsd/commands/dry_run_check.h"
#include "rpsd/commands/overrides.h"
#include "rpsd/commands/run_scenario.h"
#include "rpsd/commands/validate_report.h"

namespace py = pybind11;

namespace rpsd::python {
namespace {

std::string validate_json(const std::string& file, const OverrideTexts& set, const py::dict& callables) {
  const hybrid_test::ExternalParts parts = external_parts(callables);
  const py::gil_scoped_release nogil;
  std::ostringstream text;
  return commands::validate_file(file, to_overrides(set), text, parts).dump(2);
}

// The dry run takes its steps on this thread, the GIL released: a Python part takes it per call.
std::string dry_run_json(const std::string& file, const OverrideTexts& set, const std::vector<std::string>& nodes,
                         const py::dict& callables) {
  const hybrid_test::ExternalParts parts = external_parts(callables);
  const py::gil_scoped_release nogil;
  const auto study = commands::load_run_scenario(file, commands::run_overrides({}, to_overrides(set)), parts);
  std::ostringstream table;
  return commands::dry_run_check(study, nodes, table).report.dump(2);
}

std::string analyze_servo_json(const std::string& file) {
  const py::gil_scoped_release nogil;
  return commands::servo_analysis_json(file).dump(2);
}

std::string integrator_properties_json(const std::string& name, const std::vector<double>& omega_dt, double damping,
                                       const std::optional<std::string>& rho_inf,
                                       const std::optional<std::string>& alpha) {
  const py::gil_scoped_release nogil;
  const commands::IntegratorQueryOptions query{name, rho_inf, alpha, omega_dt, damping};
  return commands::integrator_properties_json(commands::integrator_properties(query)).dump(2);
}

}  // namespace

void register_checks(py::module_& m) {
  m.def("validate_json", &validate_json, py::arg("file"), py::arg("overrides"), py::arg("callables") = py::dict(),
        "`rpsd validate FILE --json`");
  m.def("dry_run_json", &dry_run_json, py::arg("file"), py::arg("overrides"), py::arg("nodes"),
        py::arg("callables") = py::dict(), "`rpsd run FILE --dry-run --json`");
  m.def("analyze_servo_json", &analyze_servo_json, py::arg("file"), "`rpsd analyze FILE --json`");
  m.def("integrator_properties_json", &integrator_properties_json, py::arg("name"), py::arg("omega_dt"),
        py::arg("damping"), py::arg("rho_inf"), py::arg("alpha"), "`rpsd analyze integrator NAME --json`");
}

}  // namespace rpsd::python
