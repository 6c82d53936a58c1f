#include "rpsd/servo/envelope.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "rpsd/config/key_error.h"

namespace rpsd::servo {

Envelope Envelope::read(config::Source& section) {
  Envelope e;
  // Bounds beyond any servo-hydraulic rig (10 m of stroke, 1 GN, 100 m/s), for typing errors.
  e.stroke_m = section.number("stroke_m", {"m", "the piston moves +/- this", 0.0, 10.0, true});
  e.force_n = section.number("force_n", {"N", "+/- the force the actuator can exert", 0.0, 1e9, true});
  e.velocity_m_per_s = section.number("velocity_m_per_s", {"m/s", "the fastest the piston can move", 0.0, 100.0, true});
  section.finish();
  return e;
}

void Envelope::validate() const {
  const auto check = [](double v, const char* key) {
    if (!(v > 0.0)) throw std::invalid_argument(std::string("rig.") + key + ": must be positive");
  };
  check(stroke_m, "stroke_m");
  check(force_n, "force_n");
  check(velocity_m_per_s, "velocity_m_per_s");
}

std::string describe(const Envelope& e) {
  char text[160];
  std::snprintf(text, sizeof text, "stroke +/-%.4g mm, force +/-%.4g kN, velocity %.3g m/s", 1e3 * e.stroke_m,
                1e-3 * e.force_n, e.velocity_m_per_s);
  return text;
}

void tighten_to_rig(double& limit, double rig, const std::string& key, const char* what) {
  if (limit == Envelope::kNone) {
    limit = rig;
  } else if (limit > rig) {
    std::ostringstream message;
    message << limit << " is beyond the rig's " << what << " of " << rig
            << " (a limit may only tighten the rig's envelope)";
    throw config::KeyError(key, message.str());
  }
}

}  // namespace rpsd::servo
