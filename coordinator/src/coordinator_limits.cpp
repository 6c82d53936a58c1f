#include "rpsd/coordinator/coordinator_limits.h"

#include <sstream>
#include <stdexcept>
#include <string>

namespace rpsd::coordinator {
namespace {

void tighten(double& limit, double rig, const char* key, const char* what) {
  if (limit == CoordinatorLimits::kNone) {
    limit = rig;
  } else if (limit > rig) {
    std::ostringstream message;
    message << key << ": " << limit << " is beyond the rig's " << what << " of " << rig
            << " (a limit may only tighten the rig's envelope)";
    throw std::invalid_argument(message.str());
  }
}

}  // namespace

CoordinatorLimits within_envelope(CoordinatorLimits limits, const servo::Envelope& envelope, double control_period_s) {
  tighten(limits.max_stroke_m, envelope.stroke_m, "max_stroke_m", "stroke");
  tighten(limits.max_force_n, envelope.force_n, "max_force_n", "force capacity");
  tighten(limits.max_increment_m, envelope.velocity_m_per_s * control_period_s, "max_increment_m",
          "velocity capacity over one control period");
  if (limits.max_tracking_error_m == CoordinatorLimits::kNone) limits.max_tracking_error_m = 0.5 * envelope.stroke_m;
  return limits;
}

}  // namespace rpsd::coordinator
