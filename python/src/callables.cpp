// Python objects as the parts a scenario names `kind: external` (rpsd.run(..., callables=...)):
// a compensator or controller (compensation::HostCompensator) and a numerical substructure's
// restoring force (substructure::HostRestoringForce). Each run and channel gets its own deep
// copy of the object given, so its state is kept between calls and never shared between runs.
// The test runs on a thread without the GIL: every call into Python, and every release of a
// Python object, takes it. Nothing here runs on a real-time path: the reader refuses an
// external part under a real-time clock.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>

#include <memory>
#include <string>
#include <utility>

#include "bindings.h"
#include "rpsd/compensation/external_compensator.h"
#include "rpsd/substructure/external_structure.h"

namespace py = pybind11;

namespace rpsd::python {
namespace {

// A Python object held from threads that may not hold the GIL: released under the GIL.
class HeldObject {
 public:
  explicit HeldObject(py::object object) : object_(std::move(object)) {}
  ~HeldObject() {
    const py::gil_scoped_acquire gil;
    object_ = py::object();
  }
  HeldObject(const HeldObject&) = delete;
  HeldObject& operator=(const HeldObject&) = delete;
  const py::object& get() const { return object_; }

 private:
  py::object object_;
};

// The object a run gets: a class is called with no arguments, anything else deep-copied (the
// state the user gave it is each run's start).
py::object fresh_copy(const py::object& given) {
  if (py::isinstance<py::type>(given)) return given();
  return py::module_::import("copy").attr("deepcopy")(given);
}

bool has(const py::object& o, const char* name) { return py::hasattr(o, name); }

class PythonCompensator final : public compensation::HostCompensator {
 public:
  explicit PythonCompensator(py::object object) : object_(std::move(object)) {}
  void configure(double dt_s) override { call_if("configure", dt_s); }
  void reset(double initial_displacement_m) override { call_if("reset", initial_displacement_m); }
  double command(double target_m) override {
    const py::gil_scoped_acquire gil;
    const py::object& o = object_.get();
    return (has(o, "command") ? o.attr("command")(target_m) : o(target_m)).cast<double>();
  }
  void observe(double target_m, double measured_m) override { call_if("observe", target_m, measured_m); }

 private:
  template <typename... Args>
  void call_if(const char* method, Args... args) {
    const py::gil_scoped_acquire gil;
    if (has(object_.get(), method)) object_.get().attr(method)(args...);
  }
  HeldObject object_;
};

class PythonCompensatorSource final : public compensation::ExternalCompensatorSource {
 public:
  PythonCompensatorSource(std::string name, py::object given) : name_(std::move(name)), given_(std::move(given)) {}
  std::unique_ptr<compensation::HostCompensator> make(int /*channel*/) const override {
    const py::gil_scoped_acquire gil;
    py::object o = fresh_copy(given_.get());
    if (!has(o, "command") && !PyCallable_Check(o.ptr())) {
      throw std::invalid_argument("callables['" + name_ +
                                  "']: a compensator is callable with the target (m) or has command(target_m)");
    }
    return std::make_unique<PythonCompensator>(std::move(o));
  }

 private:
  std::string name_;
  HeldObject given_;
};

class PythonRestoringForce final : public substructure::HostRestoringForce {
 public:
  PythonRestoringForce(py::object object, Eigen::Index dofs) : object_(std::move(object)), dofs_(dofs) {}
  void restoring_force(const Eigen::Ref<const Eigen::VectorXd>& d_trial, Eigen::Ref<Eigen::VectorXd> r_out) override {
    const py::gil_scoped_acquire gil;
    const Eigen::VectorXd d = d_trial;  // the callable may keep it: its own copy
    const auto r = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(
        object_.get().attr("restoring_force")(d));
    if (!r || r.ndim() != 1 || r.shape(0) != dofs_) {
      throw std::invalid_argument("restoring_force(d) must return " + std::to_string(dofs_) + " numbers");
    }
    for (Eigen::Index i = 0; i < dofs_; ++i) r_out[i] = r.at(i);
  }
  void commit() override {
    const py::gil_scoped_acquire gil;
    if (has(object_.get(), "commit")) object_.get().attr("commit")();
  }
  bool tangent_stiffness(Eigen::Ref<Eigen::MatrixXd> k_out) override {
    const py::gil_scoped_acquire gil;
    if (!has(object_.get(), "tangent_stiffness")) return false;
    const py::object k = object_.get().attr("tangent_stiffness")();
    if (k.is_none()) return false;
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(k);
    if (!a || a.ndim() != 2 || a.shape(0) != dofs_ || a.shape(1) != dofs_) {
      throw std::invalid_argument("tangent_stiffness() must return a " + std::to_string(dofs_) + "x" +
                                  std::to_string(dofs_) + " matrix or None");
    }
    for (Eigen::Index i = 0; i < dofs_; ++i)
      for (Eigen::Index j = 0; j < dofs_; ++j) k_out(i, j) = a.at(i, j);
    return true;
  }

 private:
  HeldObject object_;
  Eigen::Index dofs_;
};

class PythonStructureSource final : public substructure::ExternalStructureSource {
 public:
  PythonStructureSource(std::string name, py::object given) : name_(std::move(name)), given_(std::move(given)) {}
  std::unique_ptr<substructure::HostRestoringForce> make(Eigen::Index dofs) const override {
    const py::gil_scoped_acquire gil;
    py::object o = fresh_copy(given_.get());
    if (!has(o, "restoring_force")) {
      throw std::invalid_argument("callables['" + name_ + "']: a structure has restoring_force(d) (and commit())");
    }
    return std::make_unique<PythonRestoringForce>(std::move(o), dofs);
  }

 private:
  std::string name_;
  HeldObject given_;
};

}  // namespace

std::vector<scenarios::Override> to_overrides(const OverrideTexts& texts) {
  std::vector<scenarios::Override> overrides;
  for (const auto& [key, value, origin] : texts) overrides.push_back({key, value, origin});
  return overrides;
}

hybrid_test::ExternalParts external_parts(const py::dict& callables) {
  hybrid_test::ExternalParts parts;
  for (const auto& [key, value] : callables) {
    const std::string name = py::str(key);
    const py::object given = py::reinterpret_borrow<py::object>(value);
    // The scenario says which kind each name is; each name serves as either.
    parts.compensators.emplace(name, std::make_shared<PythonCompensatorSource>(name, given));
    parts.structures.emplace(name, std::make_shared<PythonStructureSource>(name, given));
  }
  return parts;
}

}  // namespace rpsd::python
