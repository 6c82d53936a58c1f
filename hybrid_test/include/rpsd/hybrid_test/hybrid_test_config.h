// Everything a test needs, typed (scenarios/ reads a `study: rpsd_test` file into it): the
// numerical substructure, the experimental channels, the plant, the integrator, the
// compensator, the excitation, the clock, the transport and the output. The parts are the
// lower modules' own configuration types; this file only names which is which.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "rpsd/compensation/compensator_factory.h"
#include "rpsd/coordinator/coordinator_limits.h"
#include "rpsd/coordinator/held_force.h"
#include "rpsd/coordinator/loop_timing.h"
#include "rpsd/coordinator/restoring_force.h"
#include "rpsd/hybrid_test/histories_config.h"
#include "rpsd/integrators/factory.h"
#include "rpsd/node/servo_node_config.h"
#include "rpsd/opensees/adapter_link.h"
#include "rpsd/operator_commands/operator_commands_config.h"
#include "rpsd/realtime/realtime_setup.h"
#include "rpsd/servo/plant_factory.h"
#include "rpsd/setups/setup_kinds.h"
#include "rpsd/substructure/linear_mdof_model.h"
#include "rpsd/substructure/partition.h"
#include "rpsd/substructure/shear_building.h"
#include "rpsd/substructure/structure_kinds.h"
#include "rpsd/telemetry/telemetry_config.h"

namespace rpsd::hybrid_test {

struct ExperimentalChannel {
  substructure::ExperimentalDof dof;  // DOF, channel, scales, specimen stiffness estimate
  coordinator::RestoringForceSource restoring_force = coordinator::RestoringForceSource::kMeasuredForce;
  std::uint32_t site_id = 1;              // the servo node (site) that owns the actuator
  coordinator::CoordinatorLimits limits;  // experimental[i].limits
  // The specimen's own damping (specimen scale), part of the whole structure's: what the
  // numerical part's damping leaves out when the damping is the whole structure's.
  double specimen_damping_n_s_per_m = 0.0;
  // The specimen's own mass (specimen scale), part of the structure's: the numerical part
  // leaves it to the measured force (m_e d2x_m/dt2), and the ground motion still loads it.
  double specimen_mass_kg = 0.0;
  // The structure's stiffness includes this specimen's (experimental[].specimen: the structure
  // is the whole reference building), so the numerical part's is K_N = K - K_E: a drawn k_e
  // changes the partition too, and K_N + K_E stays the reference building's.
  bool stiffness_in_structure = false;
};

// A site whose DOFs an experimental setup drives (experimental_setups[]): its actuators push
// on the specimen's control point, and the setup turns the DOFs' targets into the actuators'
// strokes and their measured strokes and forces back into the DOFs' displacements and forces.
// The setup is square: its actuator i answers on the link on the test channel of its DOF i,
// so a site keeps one channel per DOF. Without one, each DOF is its own actuator's stroke.
struct ExperimentalSetupSite {
  std::uint32_t site_id = 1;
  // The test's channels of the setup's DOFs, in the setup's DOF order (experimental[] entries
  // of this site); the setup's actuator i is commanded on channels[i].
  std::vector<int> channels;
  setups::SetupConfig setup;
  // Each actuator's own limits (stroke, velocity or increment, force, tracking), the rig's
  // envelope their default and ceiling; the DOFs' limits are their experimental[] entries'.
  std::vector<coordinator::CoordinatorLimits> actuator_limits;
  // Where the compensators act: on each actuator's stroke (the lag is the actuator's), or on
  // the DOFs' targets before the geometry.
  enum class Compensated { kActuators, kDofs };
  Compensated compensated = Compensated::kActuators;
  // Calibration: each actuator's reading at the start, where the specimen sits at its
  // initial configuration, is recorded as its offset from the stroke the geometry predicts;
  // beyond this the run does not start.
  double max_calibration_offset_m = 0.002;
  // The specimen's coupled stiffness and damping over the setup's DOFs (specimen scale, N/m,
  // N·m/rad, ...), simulated for a rehearsal; empty: each actuator's plant keeps its own
  // specimen, as without a setup.
  Eigen::MatrixXd specimen_stiffness, specimen_damping;
};

// An actuator of an experimental site that holds a force in force control (mixed control,
// held_forces[]; docs/held-forces.md), as a column's axial load: not a DOF of the structure,
// its force is neither commanded by the integrator nor fed back to it. Held force k is on the
// link channel experimental.size() + k, after its site's structure channels on its node.
struct HeldForce {
  std::uint32_t site_id = 1;
  std::string name;                         // [a-z0-9_], unique: "axial"
  double force_n = 0.0;                     // held once ramped (negative: compression)
  double max_force_rate_n_per_s = 0.0;      // the ramp's rate from the force at rest (> 0)
  double specimen_stiffness_n_per_m = 0.0;  // what the jack pushes on: the rehearsal's specimen, the node's guard
  // As read: infinite means the rig's (held_forces.h, held_force_limits fills them in).
  coordinator::HeldForceLimits limits;
};

// How the loop is paced.
struct ClockConfig {
  enum class Mode { kAsFastAsPossible, kRealTime };
  Mode mode = Mode::kAsFastAsPossible;
  // Real time: late feedback is replaced by the newest measurement (counted and flagged)
  // while that answers a command at most this many control periods old; beyond, the node
  // is taken for silent and the test stops (a dead node: on the 5th period with 4).
  int max_feedback_age_periods = 4;
  // Which target a step commands and which force it feeds back: rpsd's end of step, or the
  // RTHS benchmark's target now with the force a sample late (coordinator/loop_timing.h).
  // The perfect-actuator reference is the structure integrated whole, in rpsd's timing.
  coordinator::LoopTiming loop_timing = coordinator::LoopTiming::kEndOfStep;
  realtime::RealTimeRequest realtime;
};

// Where the actuators are: simulated in this process, or servo nodes reached over DDS.
struct TransportConfig {
  enum class Kind { kInProcess, kDds };
  Kind kind = Kind::kInProcess;
  std::uint32_t test_id = 1;  // DDS partition: two tests on one network never cross
  std::uint32_t domain_id = 0;
  std::filesystem::path dds_config;  // Cyclone XML; empty: CYCLONEDDS_URI or defaults
  double feedback_timeout_s = 1.0;   // lock-step: longest wait for one step's feedback
  // Lock-step: poll for the feedback this long before sleeping until it comes (0: never).
  double busy_wait_s = 0.0;
  double discovery_timeout_s = 10.0;  // longest wait for every site's node at start
};

// When a test has run away, beyond the limits of each channel (coordinator_limits.h), a
// node's stroke or force limit acting and a piston on its end stop: a servovalve fully open
// for longer than this. A node's rate limits (velocity, increment, acceleration) shape the
// commands it applies, also after a command that came late or was lost in real time; they
// are recorded per step (limit_flags), and a command faster than the rig is the coordinator's
// increment limit's to stop.
struct RunAwayConfig {
  double max_valve_saturation_s = 0.25;
};

// A ground-acceleration record already read and processed to the integration step.
struct GroundMotion {
  std::string name;  // file or generator, for titles
  double dt_s = 0.0;
  std::vector<double> acceleration_m_per_s2;
  double record_step_s = 0.0;           // the record's own step, before resampling
  double record_pga_m_per_s2 = 0.0;     // the record's own peak, before any processing
  std::vector<std::string> processing;  // what was done to it, in order ("scaled by 0.15", ...)
};

// A numerical site carried by a remote OpenSees model through its `adapter` element: its
// basic DOFs are the structure's `dofs`, each an experimental channel of this site whose
// restoring force is the substructure's (no rig, no compensation). An adapter serves one run,
// so the perfect-actuator reference that runs beside the test needs a second OpenSees process
// on reference_port.
struct OpenSeesSite {
  opensees::AdapterSiteConfig adapter;  // site id, host, port, DOF count, timeouts
  std::uint16_t reference_port = 0;
  // The substructure's initial stiffness between its DOFs (row i, column j: the adapter's
  // -dof order), for K0; its diagonal is the channels' estimates. Empty: diagonal only.
  Eigen::MatrixXd stiffness_n_per_m;
};

// What a test's histories are written as (output.format, docs/results-format.md): the CSV
// tables, results.h5, or both.
enum class ResultsFormat { kCsv, kHdf5, kBoth };

struct TestConfig {
  std::string name;
  std::string description;
  substructure::StructureConfig structure;
  std::vector<ExperimentalChannel> experimental;
  // The sites whose DOFs a setup drives (the others: one actuator per DOF).
  std::vector<ExperimentalSetupSite> setups;
  // The actuators that hold a force (mixed control): link channels experimental.size() + k.
  std::vector<HeldForce> held_forces;
  Eigen::VectorXd influence;  // ground-motion influence vector (default: all ones)
  servo::PlantConfig plant;   // every channel's actuator (each channel gets its own)
  integrators::IntegratorConfig integrator = integrators::CentralDifferenceParameters{};
  compensation::CompensatorConfig compensation = compensation::PassThroughParameters{};
  double control_rate_hz = 1024.0;  // integration step = control period x iterations
  ClockConfig clock;
  RunAwayConfig run_away;
  TransportConfig transport;
  operator_commands::OperatorCommandsConfig operator_commands;  // stop, abort, hold, resume (docs/operator-commands.md)
  // Either a ground motion or an initial displacement (free vibration) drives the test.
  std::optional<GroundMotion> ground_motion;
  Eigen::VectorXd initial_displacement_m;
  double duration_s = 0.0;  // free vibration length, or the record's length
  std::vector<Eigen::Index> record_dofs;
  telemetry::TelemetryConfig telemetry;  // published for `rpsd monitor` when enabled
  ResultsFormat results_format = ResultsFormat::kCsv;
  HistoriesConfig histories;  // output.histories: every step, the criteria only, or decimated
  // In process: the servo node of a site, by site id (its limits, limit actions and
  // watchdog; identity, channels and period come from the test). A site without one runs
  // a node with ServoNodeConfig's defaults.
  std::map<std::uint32_t, node::ServoNodeConfig> site_nodes;
  // The damping of the whole structure (numerical part with the specimens' stiffness), when
  // given: the numerical part's C is it less the specimens' own damping (the structure's own
  // damping is then none). The RTHS benchmark's 5 % in every mode of the reference building.
  std::optional<substructure::DampingConfig> whole_structure_damping;
  // Numerical sites in remote OpenSees processes (their channels are in `experimental`).
  std::vector<OpenSeesSite> opensees_sites;
  // The OpenSees site of a site id, or nullptr for a site with an actuator.
  const OpenSeesSite* opensees_site(std::uint32_t site_id) const {
    for (const auto& site : opensees_sites)
      if (site.adapter.site_id == site_id) return &site;
    return nullptr;
  }
};

// The partition of the scenario's structure: its experimental channels, their estimated
// stiffness (an OpenSees site's whole matrix) and the influence vector.
substructure::PartitionConfig partition_config(const TestConfig& config, Eigen::Index dofs);

// DOFs of the scenario's structure.
Eigen::Index structure_dofs(const TestConfig& config);

// Whether the numerical part leaves the specimens' own damping and mass to their measured
// force (a test), or keeps them (the perfect-actuator reference, whose specimen is k x only:
// the whole structure).
enum class SpecimenShare { kLeftToSpecimens, kKeptInNumericalPart };

// The numerical part of the scenario's structure, configured (without the specimens' stiffness).
// An external structure asks its host for a new law (substructure/external_structure.h).
// Throws what configuring it throws. Not real-time safe.
std::unique_ptr<substructure::NumericalModel> make_numerical_model(
    const TestConfig& config, SpecimenShare share = SpecimenShare::kLeftToSpecimens);

// The same numerical part's M, C and K0, an external structure's with K0 d for its restoring
// force: for the checks and overviews that need no step, so they ask nothing of a host
// program. Not real-time safe.
std::unique_ptr<substructure::NumericalModel> numerical_matrices(const TestConfig& config,
                                                                 SpecimenShare share = SpecimenShare::kLeftToSpecimens);

// Whether a host program gives a part of the test (compensation or structure kind external):
// lock-step only, never on a real-time path.
bool uses_external_parts(const TestConfig& config);

// The whole structure's mass, specimens' included (the structure's as given): what the ground
// motion loads. Not real-time safe.
linalg::StructuralMatrix whole_structure_mass(const TestConfig& config);

}  // namespace rpsd::hybrid_test
