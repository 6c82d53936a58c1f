// The host program's restoring force behind NumericalModel: M, C and K0 as the linear kind's,
// R(d), commit and the tangent forwarded, a failing call caught and kept, no source refused.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "rpsd/substructure/external_structure.h"

namespace rpsd::substructure {
namespace {

// A one-storey elastic-perfectly-plastic spring: R = k (d - plastic), |R| <= yield; its plastic
// displacement is history, moved only by commit(). Throws on its `throw_at`-th trial.
class PlasticHost final : public HostRestoringForce {
 public:
  PlasticHost(bool gives_tangent, long throw_at) : gives_tangent_(gives_tangent), throw_at_(throw_at) {}
  void restoring_force(const Eigen::Ref<const Eigen::VectorXd>& d, Eigen::Ref<Eigen::VectorXd> r) override {
    if (++trials_ == throw_at_) throw std::runtime_error("diverged");
    const double elastic = kK * (d[0] - committed_plastic_);
    trial_plastic_ = committed_plastic_;
    yielding_ = std::abs(elastic) > kYield;
    if (yielding_) trial_plastic_ = d[0] - std::copysign(kYield, elastic) / kK;
    r[0] = kK * (d[0] - trial_plastic_);
  }
  void commit() override { committed_plastic_ = trial_plastic_; }
  bool tangent_stiffness(Eigen::Ref<Eigen::MatrixXd> k) override {
    k(0, 0) = yielding_ ? 0.0 : kK;
    return gives_tangent_;
  }
  static constexpr double kK = 1000.0, kYield = 10.0;

 private:
  bool gives_tangent_;
  long throw_at_, trials_ = 0;
  double committed_plastic_ = 0.0, trial_plastic_ = 0.0;
  bool yielding_ = false;
};

struct PlasticSource final : ExternalStructureSource {
  std::unique_ptr<HostRestoringForce> make(Eigen::Index dofs) const override {
    asked_dofs = dofs;
    return std::make_unique<PlasticHost>(gives_tangent, throw_at);
  }
  bool gives_tangent = true;
  long throw_at = 0;
  mutable Eigen::Index asked_dofs = 0;
};

ExternalStructureParameters one_storey(std::shared_ptr<const ExternalStructureSource> source) {
  LinearMdofParameters m;
  m.mass_kg = linalg::StructuralMatrix(Eigen::MatrixXd::Constant(1, 1, 2.0));
  m.stiffness_n_per_m = linalg::StructuralMatrix(Eigen::MatrixXd::Constant(1, 1, PlasticHost::kK));
  return {m, "storey", std::move(source)};
}

Eigen::VectorXd at(double d) { return Eigen::VectorXd::Constant(1, d); }

TEST(ExternalStructure, TrialsStartFromTheCommittedStateAndTheTangentIsTheHostsOrK0) {
  auto source = std::make_shared<PlasticSource>();
  ExternalStructureModel model;
  model.configure(one_storey(source));
  EXPECT_EQ(source->asked_dofs, 1);
  EXPECT_EQ(model.mass().coeff(0, 0), 2.0);
  EXPECT_EQ(model.initial_stiffness().coeff(0, 0), PlasticHost::kK);
  Eigen::VectorXd r(1);
  model.restoring_force(at(0.05), r);  // yields: 10 N
  EXPECT_NEAR(r[0], 10.0, 1e-12);
  EXPECT_EQ(model.tangent_stiffness().coeff(0, 0), 0.0);  // the host's tangent
  model.restoring_force(at(0.005), r);                    // another trial, from the committed state
  EXPECT_NEAR(r[0], 5.0, 1e-12);
  model.restoring_force(at(0.05), r);
  model.commit();  // plastic 0.04
  model.restoring_force(at(0.04), r);
  EXPECT_NEAR(r[0], 0.0, 1e-12);

  source->gives_tangent = false;
  ExternalStructureModel without;
  without.configure(one_storey(source));
  without.restoring_force(at(0.05), r);
  EXPECT_EQ(without.tangent_stiffness().coeff(0, 0), PlasticHost::kK);  // none given: K0
}

TEST(ExternalStructure, AHostCallThatThrowsIsKeptAndEveryLaterForceIsNaN) {
  auto source = std::make_shared<PlasticSource>();
  source->throw_at = 2;
  ExternalStructureModel model;
  model.configure(one_storey(source));
  Eigen::VectorXd r(1);
  model.restoring_force(at(0.001), r);
  EXPECT_NEAR(r[0], 1.0, 1e-12);
  EXPECT_FALSE(model.failed());
  model.restoring_force(at(0.001), r);  // throws: caught, the integrator refuses the NaN
  EXPECT_TRUE(std::isnan(r[0]));
  EXPECT_TRUE(model.failed());
  EXPECT_STREQ(model.failure(), "restoring_force(): diverged");
  model.restoring_force(at(0.001), r);
  EXPECT_TRUE(std::isnan(r[0]));
  EXPECT_EQ(model.tangent_stiffness().coeff(0, 0), PlasticHost::kK);
}

TEST(ExternalStructure, WithoutASourceItIsRefusedNamingTheKindAndTheHost) {
  ExternalStructureModel model;
  try {
    model.configure(one_storey(nullptr));
    FAIL() << "configured";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "structure.kind external `storey`: given only by a host program (rpsd.run(..., callables=...)); "
                 "the command line cannot run it");
  }
}

}  // namespace
}  // namespace rpsd::substructure
