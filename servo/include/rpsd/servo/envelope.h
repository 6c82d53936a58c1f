// What a rig can do, per actuator channel: its stroke, its force capacity and its velocity
// capacity. It is every node's and every coordinator's default limit; a user may only
// tighten it (docs/safety.md).
#pragma once

#include <limits>
#include <string>

#include "rpsd/config/source.h"

namespace rpsd::servo {

struct Envelope {
  static constexpr double kNone = std::numeric_limits<double>::infinity();
  double stroke_m = kNone;          // the piston moves +/- this
  double force_n = kNone;           // +/- the force the actuator can exert
  double velocity_m_per_s = kNone;  // the fastest the piston can move

  bool stated() const { return stroke_m < kNone && force_n < kNone && velocity_m_per_s < kNone; }

  // A `rig:` section: all three keys, positive. Not real-time safe.
  static Envelope read(config::Source& section);
  // Throws std::invalid_argument naming the key unless all three are positive (infinity: not
  // stated). Not real-time safe.
  void validate() const;
};

// "stroke +/-127 mm, force +/-156 kN, velocity 1.31 m/s"
std::string describe(const Envelope& envelope);

// A user's limit against the rig's: none given (infinity) becomes the rig's; one beyond it
// throws config::KeyError (an std::invalid_argument) at `key` and the rig's `what` ("stroke"); a tighter one
// stands. The one rule for nodes and coordinators alike. Not real-time safe.
void tighten_to_rig(double& limit, double rig, const std::string& key, const char* what);

}  // namespace rpsd::servo
