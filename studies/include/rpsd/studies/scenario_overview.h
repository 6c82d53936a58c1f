// What rpsd understood of a test scenario, before anything runs (`rpsd validate`): the
// structure's DOFs, modes and damping (whole, and its numerical part; a model beyond the dense
// solver's 2000 DOFs its lowest modes, by the sparse one), the steps, the record, each channel's
// rig envelope, converter rails and the limits the test will run with, and warnings: modes
// above the actuator's cut-off, limits beyond a converter's rail. Builds nothing that
// moves or connects. Not real-time safe.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "rpsd/coordinator/coordinator_limits.h"
#include "rpsd/hybrid_test/hybrid_test_config.h"
#include "rpsd/servo/envelope.h"
#include "rpsd/studies/converter_rails.h"

namespace rpsd::studies {

struct ModeOverview {
  double frequency_hz = 0.0;
  double damping_ratio = 0.0;  // phi' C phi / (2 w) of the mass-normalised mode
};

struct ChannelOverview {
  int channel = 0;
  Eigen::Index dof = 0;
  std::uint32_t site_id = 1;
  double specimen_stiffness_n_per_m = 0.0;
  servo::Envelope envelope;
  coordinator::CoordinatorLimits limits;  // the envelope unless the scenario tightens it
  std::string opensees;                   // an OpenSees site's address ("host:port, reference :port"); "" otherwise
  ConverterRails rails;                   // the plant's converters (infinite: none)
};

struct ScenarioOverview {
  Eigen::Index dofs = 0;
  std::vector<ModeOverview> structure_modes;  // numerical part with the specimens' stiffness
  std::vector<ModeOverview> numerical_modes;  // numerical part alone (empty: no stiffness of its own)
  double control_rate_hz = 0.0;
  std::string loop_timing;  // clock.loop_timing's name
  std::int64_t steps = 0;
  double duration_s = 0.0;
  bool has_record = false;
  std::string record;                              // its source
  double source_step_s = 0.0, source_pga_g = 0.0;  // the record as read
  std::vector<std::string> processing;             // what the scenario did to it, in order
  double record_dt_s = 0.0, record_pga_g = 0.0;    // as the test runs it
  std::vector<ChannelOverview> channels;
  // One line per held force (held_forces[]): "site 1 held force axial, channel 1: ..."; empty
  // without any.
  std::vector<std::string> held_forces;
  std::optional<double> actuator_cutoff_hz;  // the servo model's (linear analysis); none for other plants
  // What deserves a look before the test: a mode above the actuator's cut-off (naming the mass
  // key), a limit that a converter's rail would pre-empt.
  std::vector<std::string> warnings;
};

ScenarioOverview overview_of(const hybrid_test::TestConfig& test);

// A few lines for a person: one section per part, SI units, frequencies in Hz.
void print_overview(const ScenarioOverview& overview, std::ostream& out);

// The same as JSON (`rpsd validate --json`, rpsd.validate in Python): the fields above, SI
// units in the names, a limit or rail that is not stated as null.
nlohmann::json overview_json(const ScenarioOverview& overview);

}  // namespace rpsd::studies
