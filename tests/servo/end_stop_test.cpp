// The simulated actuators end where their stroke ends: a command far beyond it drives the
// piston onto the end stop, which the measurement reports, and never past it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "paper_rig.h"
#include "rpsd/servo/pure_delay_plant.h"
#include "rpsd/servo/servo_hydraulic_plant.h"

namespace rpsd::servo {
namespace {

struct Excursion {
  double peak_m = 0.0;
  bool reached_end_stop = false;
  bool end_stop_reported_inside = false;  // at_end_stop while the piston was clear of it
};

// A ramp to 4x the stroke over 2 s and back, measured every millisecond.
Excursion drive_beyond(Plant& plant, double stroke_m) {
  Excursion e;
  plant.reset(0.0);
  const double dt = 1e-3;
  double command = 0.0;
  for (int k = 0; k < 4000; ++k) {
    const double next = 4.0 * stroke_m * (k < 2000 ? (k + 1) / 2000.0 : (4000 - k - 1) / 2000.0);
    plant.advance(command, next, dt);
    command = next;
    const PlantMeasurement m = plant.measure();
    e.peak_m = std::max(e.peak_m, std::abs(m.displacement_m));
    e.reached_end_stop = e.reached_end_stop || m.at_end_stop;
    e.end_stop_reported_inside = e.end_stop_reported_inside || (m.at_end_stop && std::abs(m.displacement_m) < stroke_m);
  }
  return e;
}

TEST(EndStop, TheServoModelsPistonStopsAtItsStroke) {
  const ServoSystemParameters rig = testing::paper_rig();
  ServoHydraulicPlant plant(rig);
  const Excursion e = drive_beyond(plant, rig.actuator.stroke_m);
  EXPECT_LE(e.peak_m, rig.actuator.stroke_m);               // never past the stop
  EXPECT_GE(e.peak_m, rig.actuator.stroke_m * (1 - 1e-9));  // and the stop is where the stroke ends
  EXPECT_TRUE(e.reached_end_stop);
  EXPECT_FALSE(e.end_stop_reported_inside);
}

TEST(EndStop, TheIdealDelayActuatorStopsAtTheRigsStroke) {
  PureDelayParameters p;
  p.delay_s = 0.01;
  p.specimen_stiffness_n_per_m = 1e5;
  p.rig.stroke_m = 0.05;
  p.rig.force_n = 1e5;
  p.rig.velocity_m_per_s = 1.0;
  PureDelayPlant plant(p);
  const Excursion e = drive_beyond(plant, p.rig.stroke_m);
  EXPECT_LE(e.peak_m, p.rig.stroke_m);
  EXPECT_GE(e.peak_m, p.rig.stroke_m * (1 - 1e-9));
  EXPECT_TRUE(e.reached_end_stop);
  EXPECT_FALSE(e.end_stop_reported_inside);
}

}  // namespace
}  // namespace rpsd::servo
