// The lowest mode of a test's numerical model, as the telemetry's identified damping needs it
// (telemetry/effective_damping_identifier.h): mass-normalised, with each record channel's
// weight phi_j^2 x force scale x displacement scale. Not real-time safe.
#pragma once

#include "rpsd/hybrid_test/hybrid_test_config.h"
#include "rpsd/telemetry/effective_damping_identifier.h"

namespace rpsd::studies {

// Unknown (LowestMode::known() false) for OpenSees sites, experimental setups (their record
// channels are actuator strokes, not the model's DOFs) and a model that does not build.
telemetry::LowestMode lowest_mode_for_identification(const hybrid_test::TestConfig& scenario);

}  // namespace rpsd::studies
