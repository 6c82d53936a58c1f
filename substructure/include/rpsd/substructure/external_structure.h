#pragma once
// A numerical substructure whose restoring force a host program gives (`structure: {kind:
// external, name: ..., mass_kg, stiffness_n_per_m, damping}`): a Python callable behind the
// `rpsd` module, or any C++ object, for rehearsals only (a real-time clock is refused where
// the scenario is read). The file gives what the integrator needs, M, C and the initial
// stiffness K0, read as the linear kind reads them; the host gives R(d) with trial/commit.
// The tangent stiffness is the host's when it gives one, K0 otherwise.
//
// ExternalStructureModel wraps the host's law for the loop: a host call that throws is caught
// and kept, the force turns non-finite so that the integrator refuses the step, and the test
// ends the run with the host's message (hybrid_test: StepOutcome::kHostCallFailed).

#include <array>
#include <memory>
#include <string>

#include "rpsd/substructure/linear_mdof_model.h"

namespace rpsd::substructure {

// The host's restoring-force law of one run's structure. Its calls may throw (any exception):
// the wrapper catches them. Called on the thread that runs the test, never concurrently.
class HostRestoringForce {
 public:
  virtual ~HostRestoringForce() = default;
  // r_out = R(d_trial) from the last committed state: any number of trials within a step
  // leave the history untouched. Both of size dofs.
  virtual void restoring_force(const Eigen::Ref<const Eigen::VectorXd>& d_trial, Eigen::Ref<Eigen::VectorXd> r_out) = 0;
  // Accepts the last trial as the state at the end of the step.
  virtual void commit() {}
  // The tangent stiffness at the last trial state into k_out (dofs x dofs, zeroed); false
  // when the host gives none (then K0 serves).
  virtual bool tangent_stiffness(Eigen::Ref<Eigen::MatrixXd> /*k_out*/) { return false; }
};

// What a host program gives for one name: a new law at rest (committed at d = 0) for each
// run (the test and its perfect-actuator reference, each case of a batch). make() may throw:
// the run is then refused with its message. Called on the thread that builds the run.
class ExternalStructureSource {
 public:
  virtual ~ExternalStructureSource() = default;
  virtual std::unique_ptr<HostRestoringForce> make(Eigen::Index dofs) const = 0;
};

struct ExternalStructureParameters {
  LinearMdofParameters matrices;  // M, C and K0, as the linear kind reads them
  std::string name;               // structure.name: which of the host's structures
  // The host's, filled in by the reader from what the host program gave it; a file cannot
  // set it. Shared by every copy of the configuration; never copied itself.
  std::shared_ptr<const ExternalStructureSource> source;
};

class ExternalStructureModel final : public NumericalModel {
 public:
  // Configures M, C and K0 as LinearMdofModel does, then asks the host for its law. Throws
  // std::invalid_argument: the matrices' checks, no source (a file run by the command line),
  // the host's make() failing. Not real-time safe.
  void configure(const ExternalStructureParameters& parameters);

  [[nodiscard]] Eigen::Index dofs() const noexcept override { return matrices_.dofs(); }
  [[nodiscard]] const linalg::StructuralMatrix& mass() const noexcept override { return matrices_.mass(); }
  [[nodiscard]] const linalg::StructuralMatrix& damping() const noexcept override { return matrices_.damping(); }
  [[nodiscard]] const linalg::StructuralMatrix& initial_stiffness() const noexcept override {
    return matrices_.initial_stiffness();
  }
  // The host's tangent at the last trial when it gives one, K0 otherwise (and after a failure).
  [[nodiscard]] const linalg::StructuralMatrix& tangent_stiffness() noexcept override;
  // The host's R(d_trial); NaN in every entry once a host call has failed.
  void restoring_force(const Eigen::Ref<const Eigen::VectorXd>& d_trial,
                       Eigen::Ref<Eigen::VectorXd> r_out) noexcept override;
  void commit() noexcept override;

  // Whether a host call threw, and its message ("restoring_force(): <what>"; truncated).
  bool failed() const noexcept { return failure_[0] != '\0'; }
  const char* failure() const noexcept { return failure_.data(); }
  const std::string& host_name() const noexcept { return name_; }

 private:
  void fail(const char* call, const char* what) noexcept;

  LinearMdofModel matrices_;
  linalg::StructuralMatrix tangent_;  // dense, dofs x dofs
  std::unique_ptr<HostRestoringForce> host_;
  std::string name_;
  std::array<char, 256> failure_{};
};

}  // namespace rpsd::substructure
