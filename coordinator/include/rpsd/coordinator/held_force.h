// A channel in force control (mixed control): an actuator that holds a force on the specimen,
// as a column's axial load, while the structure's channels follow displacements. It is not a
// DOF of the structure: the integrator neither commands it nor takes its force. The
// coordinator ramps its force command from the force measured at rest to the held force at a
// stated rate, sends it in force mode (CommandSample::control_mode), and checks what comes
// back: the load cell against its force limit, the piston's measured stroke against its
// stroke limit (a softening specimen lets a force-controlled piston run), and the force's
// tracking error. Its link channels come after the structure's.
#pragma once

#include <array>
#include <cstdint>
#include <limits>

namespace rpsd::coordinator {

struct HeldForceLimits {
  static constexpr double kNone = std::numeric_limits<double>::infinity();
  double max_force_n = kNone;        // |measured force|: beyond it the test stops (kLimit)
  double max_stroke_m = kNone;       // |measured stroke|: beyond it the piston has run (kRunAway)
  double max_force_error_n = kNone;  // |force command - measured force|: beyond it, run away
};

struct HeldForceChannel {
  std::uint32_t site_id = 1;
  std::array<char, 64> name{};          // for people: "site 1 held force axial"
  int channel = 0;                      // its link channel, after the structure's channels
  double force_n = 0.0;                 // the force held once ramped
  double max_force_rate_n_per_s = 0.0;  // the ramp's rate (> 0)
  double force_at_rest_n = 0.0;         // measured before the first command: the ramp starts here
  HeldForceLimits limits;
};

}  // namespace rpsd::coordinator
