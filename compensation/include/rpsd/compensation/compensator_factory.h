// A compensator from its typed configuration: the variant alternative selects the scheme.
#pragma once

#include <memory>
#include <string_view>
#include <variant>

#include "rpsd/compensation/adaptive_inverse_compensator.h"
#include "rpsd/compensation/adaptive_time_series_compensator.h"
#include "rpsd/compensation/command_compensator.h"
#include "rpsd/compensation/discrete_phase_lead.h"
#include "rpsd/compensation/inverse_compensator.h"
#include "rpsd/compensation/pass_through_compensator.h"
#include "rpsd/compensation/polynomial_extrapolation.h"

namespace rpsd::compensation {

using CompensatorConfig =
    std::variant<PassThroughParameters, DiscretePhaseLeadParameters, PolynomialExtrapolationParameters,
                 InverseCompensationParameters, AdaptiveInverseCompensationParameters, AdaptiveTimeSeriesParameters>;

/// The compensator for config, configured for control step dt_s and at rest at zero
/// displacement (call reset() for another start). Throws std::invalid_argument with the
/// scheme's precise message. Not real-time safe.
std::unique_ptr<CommandCompensator> make_compensator(const CompensatorConfig& config, double dt_s);

/// The name() the compensator made from config will report. Real-time safe.
std::string_view compensator_name(const CompensatorConfig& config) noexcept;

}  // namespace rpsd::compensation
