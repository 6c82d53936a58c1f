// Every compensator rpsd knows, registered in one place (the list below): a new one is its
// own header and source (its parameters naming themselves with kName, reading their keys with
// read(), and naming the CommandCompensator they configure) plus one entry here
// (CONTRIBUTING.md).
#pragma once

#include <memory>
#include <string_view>

#include "rpsd/compensation/adaptive_inverse_compensator.h"
#include "rpsd/compensation/adaptive_time_series_compensator.h"
#include "rpsd/compensation/command_compensator.h"
#include "rpsd/compensation/discrete_phase_lead.h"
#include "rpsd/compensation/external_compensator.h"
#include "rpsd/compensation/inverse_compensator.h"
#include "rpsd/compensation/lti_filter_compensator.h"
#include "rpsd/compensation/pass_through_compensator.h"
#include "rpsd/compensation/polynomial_extrapolation.h"
#include "rpsd/config/kind_list.h"

namespace rpsd::compensation {

using CompensatorKinds =
    config::KindList<PassThroughParameters, DiscretePhaseLeadParameters, PolynomialExtrapolationParameters,
                     InverseCompensationParameters, AdaptiveInverseCompensationParameters, AdaptiveTimeSeriesParameters,
                     LtiFilterParameters, ExternalCompensatorParameters>;
using CompensatorConfig = CompensatorKinds::Variant;

// The compensator for config, configured for control step dt_s and at rest at zero
// displacement (call reset() for another start). Throws std::invalid_argument with the
// scheme's precise message. `channel` tells an external (host) compensator which channel it
// serves. Not real-time safe.
std::unique_ptr<CommandCompensator> make_compensator(const CompensatorConfig& config, double dt_s, int channel = 0);

// Whether the host program gives this compensator (kind external): never on a real-time path.
inline bool is_external(const CompensatorConfig& config) noexcept {
  return std::holds_alternative<ExternalCompensatorParameters>(config);
}

// The name() the compensator made from config will report. Real-time safe.
inline std::string_view compensator_name(const CompensatorConfig& config) noexcept { return config::kind_name(config); }

}  // namespace rpsd::compensation
