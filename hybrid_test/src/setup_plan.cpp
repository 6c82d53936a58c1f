#include "rpsd/hybrid_test/setup_plan.h"

#include <Eigen/LU>
#include <cmath>
#include <cstdio>

namespace rpsd::hybrid_test {

namespace {

std::string actuator_name(const setups::PlanarGeometry& g, int i) {
  const std::string& name = g.actuators[static_cast<std::size_t>(i)].name;
  return name.empty() ? "actuator " + std::to_string(i + 1) : name;
}

}  // namespace

SetupPlan plan_setups(const TestConfig& s, const Eigen::VectorXd& dof_hold_m, double control_period_s,
                      bool perfect_actuator) {
  const int channels = static_cast<int>(s.experimental.size());
  SetupPlan plan;
  plan.hold_m.assign(dof_hold_m.data(), dof_hold_m.data() + dof_hold_m.size());
  plan.stiffness_estimate_n_per_m.assign(static_cast<std::size_t>(channels), 0.0);
  plan.in_setup.assign(static_cast<std::size_t>(channels), false);
  std::vector<const ExperimentalChannel*> by_channel(static_cast<std::size_t>(channels));
  for (const auto& e : s.experimental) {
    by_channel[static_cast<std::size_t>(e.dof.actuator_channel)] = &e;
    plan.stiffness_estimate_n_per_m[static_cast<std::size_t>(e.dof.actuator_channel)] =
        e.dof.specimen_stiffness_estimate_n_per_m;
  }
  for (std::size_t k = 0; k < s.setups.size(); ++k) {
    const ExperimentalSetupSite& site = s.setups[k];
    const std::string where = "experimental_setups[" + std::to_string(k) + "]";
    coordinator::SetupGroup group;
    group.site_id = site.site_id;
    group.geometry = setups::planar_geometry(site.setup);
    const setups::PlanarSetup setup = [&] {
      try {
        return setups::PlanarSetup(group.geometry);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(where + ": " + e.what());
      }
    }();
    const int n = setup.dofs();
    if (static_cast<int>(site.channels.size()) != n) {
      throw std::invalid_argument(where + ": the setup drives " + std::to_string(n) + " DOF(s), one actuator each; " +
                                  std::to_string(site.channels.size()) + " channel(s) given");
    }
    for (const int c : site.channels) {
      if (c < 0 || c >= channels || by_channel[static_cast<std::size_t>(c)]->site_id != site.site_id ||
          plan.in_setup[static_cast<std::size_t>(c)]) {
        throw std::invalid_argument(where + ": channel " + std::to_string(c) + " is not a channel of site " +
                                    std::to_string(site.site_id) + " free for this setup");
      }
      plan.in_setup[static_cast<std::size_t>(c)] = true;
    }
    if (!site.actuator_limits.empty() && static_cast<int>(site.actuator_limits.size()) != n) {
      throw std::invalid_argument(where + ": give limits for every actuator or for none");
    }
    group.channels = site.channels;
    group.compensate_dofs = site.compensated == ExperimentalSetupSite::Compensated::kDofs;
    // The reference is numerical: no rig, no limits; otherwise each actuator's own, within
    // the rig's envelope (their default and ceiling).
    if (!perfect_actuator) {
      const servo::Envelope envelope = servo::envelope_of(s.plant);
      for (int i = 0; i < n; ++i) {
        const coordinator::CoordinatorLimits given = site.actuator_limits.empty()
                                                         ? coordinator::CoordinatorLimits{}
                                                         : site.actuator_limits[static_cast<std::size_t>(i)];
        try {
          group.actuator_limits.push_back(coordinator::within_envelope(given, envelope, control_period_s));
        } catch (const std::exception& e) {
          throw std::invalid_argument(where + ".actuator_limits[" + std::to_string(i) + "] (" +
                                      actuator_name(group.geometry, i) + "): " + e.what());
        }
      }
    }
    // The actuators rest at the strokes of the initial configuration; each force guard
    // predicts with its actuator's share of the DOFs' stiffness, diag(J⁻ᵀ K J⁻¹).
    setups::SetupVector u0(n), strokes(n);
    // The DOFs' stiffness: the setup's specimen, couplings included, or each DOF's estimate.
    Eigen::MatrixXd k_dof = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) {
      const auto c = static_cast<std::size_t>(site.channels[static_cast<std::size_t>(i)]);
      u0[i] = dof_hold_m[static_cast<Eigen::Index>(c)];
      k_dof(i, i) = by_channel[c]->dof.specimen_stiffness_estimate_n_per_m;
    }
    if (site.specimen_stiffness.rows() == n && site.specimen_stiffness.cols() == n) k_dof = site.specimen_stiffness;
    setup.strokes(u0, strokes);
    setups::SetupMatrix j(n, n);
    setup.jacobian(u0, j);
    const Eigen::MatrixXd j_inverse = Eigen::MatrixXd(j).inverse();
    const Eigen::MatrixXd k_actuator = j_inverse.transpose() * k_dof * j_inverse;
    for (int i = 0; i < n; ++i) {
      const auto c = static_cast<std::size_t>(site.channels[static_cast<std::size_t>(i)]);
      plan.hold_m[c] = strokes[i];
      plan.stiffness_estimate_n_per_m[c] = k_actuator(i, i);
    }
    plan.groups.push_back(std::move(group));
  }
  return plan;
}

std::vector<SetupCalibration> calibrate_setups(const TestConfig& s, SetupPlan& plan,
                                               const std::vector<std::optional<double>>& readings_m) {
  std::vector<SetupCalibration> calibrations;
  for (std::size_t k = 0; k < plan.groups.size(); ++k) {
    coordinator::SetupGroup& group = plan.groups[k];
    const setups::PlanarSetup setup(group.geometry);
    const double limit_m = s.setups[k].max_calibration_offset_m;
    SetupCalibration cal;
    cal.site_id = group.site_id;
    group.calibration_offset_m.assign(group.channels.size(), 0.0);
    for (std::size_t i = 0; i < group.channels.size(); ++i) {
      const auto c = static_cast<std::size_t>(group.channels[i]);
      const double predicted = plan.hold_m[c];
      const std::optional<double>& reading = readings_m[c];
      cal.measured = cal.measured && reading.has_value();
      const double offset = reading ? *reading - predicted : 0.0;
      const std::string name = actuator_name(group.geometry, static_cast<int>(i));
      if (!std::isfinite(offset) || std::abs(offset) > limit_m) {
        char text[640];
        std::snprintf(text, sizeof text,
                      "site %u, %.60s (channel %zu): its reading %.6g m at the start is %.6g m from the stroke %.6g m "
                      "the geometry predicts at the initial configuration, beyond "
                      "experimental_setups[%zu].max_calibration_offset_m %.6g m; the run does not start (measure "
                      "the rig's geometry again, or move the actuator to its reference length)",
                      static_cast<unsigned>(group.site_id), name.c_str(), c, reading.value_or(0.0), offset, predicted,
                      k, limit_m);
        throw CalibrationOutOfRange(text);
      }
      group.calibration_offset_m[i] = offset;
      cal.actuators.push_back(name);
      cal.channels.push_back(static_cast<int>(c));
      cal.reference_length_m.push_back(setup.reference_length_m(static_cast<int>(i)));
      cal.predicted_stroke_m.push_back(predicted);
      cal.reading_m.push_back(reading.value_or(predicted));
      cal.offset_m.push_back(offset);
    }
    calibrations.push_back(std::move(cal));
  }
  return calibrations;
}

}  // namespace rpsd::hybrid_test
