#include "rpsd/substructure/external_structure.h"

#include <cstdio>
#include <exception>
#include <limits>
#include <stdexcept>

namespace rpsd::substructure {

void ExternalStructureModel::configure(const ExternalStructureParameters& parameters) {
  matrices_.configure(parameters.matrices);
  name_ = parameters.name;
  failure_[0] = '\0';
  if (!parameters.source) {
    throw std::invalid_argument("structure.kind external `" + name_ +
                                "`: given only by a host program (rpsd.run(..., callables=...)); the command line "
                                "cannot run it");
  }
  try {
    host_ = parameters.source->make(dofs());
  } catch (const std::exception& e) {
    throw std::invalid_argument("structure external `" + name_ +
                                "`: the host could not make its structure: " + e.what());
  }
  if (!host_) throw std::invalid_argument("structure external `" + name_ + "`: the host made no structure");
  tangent_ = linalg::StructuralMatrix(matrices_.initial_stiffness().to_dense());
}

void ExternalStructureModel::fail(const char* call, const char* what) noexcept {
  if (failed()) return;  // the first failure is the one that stopped the run
  std::snprintf(failure_.data(), failure_.size(), "%s: %s", call, what);
}

const linalg::StructuralMatrix& ExternalStructureModel::tangent_stiffness() noexcept {
  if (failed()) return initial_stiffness();
  try {
    tangent_.dense_mut().setZero();
    if (host_->tangent_stiffness(tangent_.dense_mut())) return tangent_;
  } catch (const std::exception& e) {
    fail("tangent_stiffness()", e.what());
  } catch (...) {
    fail("tangent_stiffness()", "an exception that is no std::exception");
  }
  return initial_stiffness();
}

void ExternalStructureModel::restoring_force(const Eigen::Ref<const Eigen::VectorXd>& d_trial,
                                             Eigen::Ref<Eigen::VectorXd> r_out) noexcept {
  if (!failed()) {
    try {
      host_->restoring_force(d_trial, r_out);
      return;
    } catch (const std::exception& e) {
      fail("restoring_force()", e.what());
    } catch (...) {
      fail("restoring_force()", "an exception that is no std::exception");
    }
  }
  r_out.setConstant(std::numeric_limits<double>::quiet_NaN());
}

void ExternalStructureModel::commit() noexcept {
  if (failed()) return;
  try {
    host_->commit();
  } catch (const std::exception& e) {
    fail("commit()", e.what());
  } catch (...) {
    fail("commit()", "an exception that is no std::exception");
  }
}

}  // namespace rpsd::substructure
