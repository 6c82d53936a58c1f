// The sections of an rpsd_test scenario, each read from a config::Source: the scenario
// reader (test_scenario_file.cpp) composes them, and the scenario reference lists their keys
// by running each on a config::KeyTable. Each reads all its keys before it checks how they
// fit together, so that a listing stopped by such a check has listed every key.
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "rpsd/config/source.h"
#include "rpsd/hybrid_test/hybrid_test_config.h"
#include "rpsd/setups/planar_setup.h"
#include "rpsd/substructure/damping_models.h"
#include "rpsd/substructure/structure_kinds.h"
#include "rpsd/telemetry/telemetry_config.h"

namespace rpsd::scenarios::test_sections {

// The document's own keys; every section is a handle, read afterwards in order.
struct Document {
  std::unique_ptr<config::Source> structure;
  std::vector<std::unique_ptr<config::Source>> experimental;  // empty when only OpenSees sites take DOFs
  std::vector<std::unique_ptr<config::Source>> opensees_sites;
  std::vector<std::unique_ptr<config::Source>> experimental_setups;
  std::vector<std::unique_ptr<config::Source>> held_forces;
  std::optional<std::vector<double>> influence;
  std::unique_ptr<config::Source> servo;
  std::unique_ptr<config::Source> integrator;
  std::unique_ptr<config::Source> clock;
  std::unique_ptr<config::Source> transport;
  std::unique_ptr<config::Source> compensation;
  std::unique_ptr<config::Source> ground_motion;
  std::unique_ptr<config::Source> free_vibration;
  std::unique_ptr<config::Source> output;
  std::unique_ptr<config::Source> whole_structure_damping;
  std::unique_ptr<config::Source> operator_commands;
};
Document document(config::Source& root);

// `structure:` by its kind (substructure::StructureKinds), checked (a model is configured
// from it); files relative to the section's file (config::Source::relative_file).
using Structure = substructure::StructureConfig;
Structure structure(config::Source& st);
// `damping:` (substructure::DampingModels); `mass` is the structure's when it is known (a
// single ratio needs it).
substructure::DampingConfig damping(config::Source& d, const Eigen::MatrixXd* mass);

// experimental_setups[i], read before the DOFs it drives (a DOF's limits are stated in its
// motion's units). Its site's channels are filled in once the DOFs are read.
struct ExperimentalSetup {
  hybrid_test::ExperimentalSetupSite site;
  std::vector<Eigen::Index> dofs;                                // the structure's DOFs, in the setup's DOF order
  std::vector<setups::DofMotion> motions;                        // each DOF's motion, from the setup's kind
  std::vector<std::unique_ptr<config::Source>> actuator_limits;  // per actuator (null: none given)
  std::unique_ptr<config::Source> specimen;                      // for messages about the specimen's matrices
};
ExperimentalSetup experimental_setup(config::Source& s, Eigen::Index dofs);

// held_forces[i]: its own keys, each within its range, and its name's form; its `limits:`
// handle (null: none given) is left in `limits` for the checks against the rig, the sites and
// the other held forces, which read_test_config makes once the rig is known.
hybrid_test::HeldForce held_force(config::Source& h, std::unique_ptr<config::Source>& limits);

// experimental[i]; its `limits:` handle is left in `limits` for the envelope check. A DOF an
// experimental setup drives (`driven`: its motion) takes its specimen from the setup and its
// limits in its motion's units; its actuators take the rig's.
hybrid_test::ExperimentalChannel experimental(config::Source& e, Eigen::Index dofs, std::size_t index,
                                              std::unique_ptr<config::Source>& limits,
                                              std::optional<setups::DofMotion> driven = std::nullopt);
// An actuator's limits, or a translation DOF's (m, N).
coordinator::CoordinatorLimits limits(config::Source& l);
// A setup's rotation DOF's limits, in rad and N·m (kept in the same fields).
coordinator::CoordinatorLimits rotation_limits(config::Source& l);
// A specimen channel's own keys (channel, scales, stiffness, restoring force, site, limits),
// whatever says which DOF it takes; the caller finishes the section.
void specimen_channel(config::Source& e, std::size_t index, hybrid_test::ExperimentalChannel& channel,
                      std::unique_ptr<config::Source>& limits_section,
                      std::optional<setups::DofMotion> driven = std::nullopt);
// opensees_sites[i]: the site, and one channel per DOF it carries (channels from `first_channel`).
hybrid_test::OpenSeesSite opensees_site(config::Source& o, Eigen::Index dofs, int first_channel,
                                        std::vector<hybrid_test::ExperimentalChannel>& channels);

integrators::IntegratorConfig integrator(config::Source& r);
std::vector<std::string_view> integrator_names();
// An unknown scheme at `key` is refused with every name and a did-you-mean (a listing, whose
// has() says no, lists nothing here: the choice that follows lists the key).
void check_integrator_name(config::Source& r, std::string_view key);

void clock(config::Source& c, hybrid_test::TestConfig& t);
void transport(config::Source& r, hybrid_test::TestConfig& t);
// `operator_commands:`: whether the run acts on operator commands with DDS Security off, and
// an operator's stop returning the actuators to their start positions.
void operator_commands(config::Source& o, hybrid_test::TestConfig& t);
compensation::CompensatorConfig compensation(config::Source& r, double control_period_s);
void free_vibration(config::Source& f, Eigen::Index dofs, hybrid_test::TestConfig& t);
std::vector<Eigen::Index> record_dofs(config::Source& output, Eigen::Index dofs);
// output.format (before record_dofs, which finishes the section).
hybrid_test::ResultsFormat results_format(config::Source& output);
// output.histories and output.history_rate_hz, the latter checked against the control rate
// (before record_dofs, which finishes the section).
hybrid_test::HistoriesConfig histories(config::Source& output, double control_rate_hz);
// output.telemetry and output.telemetry_samples_per_s (before record_dofs, which finishes the section).
telemetry::TelemetryConfig telemetry(config::Source& output);

}  // namespace rpsd::scenarios::test_sections
