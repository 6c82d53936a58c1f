// The extension module `_rpsd` inside the package rpsd (docs/python.md).
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "rpsd/build_info/build_info.h"

PYBIND11_MODULE(_rpsd, m) {
  m.doc() = "rpsd's C++ core for the package rpsd: use rpsd.run, rpsd.load, rpsd.validate, ... instead.";
  m.attr("version") = rpsd::build_info::version();
  m.attr("commit") = rpsd::build_info::commit();
  rpsd::python::register_errors(m);
  rpsd::python::register_run(m);
  rpsd::python::register_checks(m);
}
