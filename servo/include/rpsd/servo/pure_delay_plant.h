// An ideal actuator that reproduces its command exactly, a fixed time later:
// x_m(t) = u(t - tau). The reference case of delay theory (the DDE m x'' + c x' + k x(t - tau)),
// against which compensators and the coordinator loop are checked.
#pragma once

#include <string_view>

#include "rpsd/config/source.h"
#include "rpsd/servo/channel_converters.h"
#include "rpsd/servo/envelope.h"

#include <vector>

#include "rpsd/servo/plant.h"

namespace rpsd::servo {

class PureDelayPlant;

struct PureDelayParameters {
  using Model = PureDelayPlant;  // the Plant these parameters build
  static constexpr std::string_view kName = "ideal_delay";
  static constexpr std::string_view kSummary = "an actuator that follows its command exactly, delay_s later";
  static PureDelayParameters read(config::Source& section, double specimen_stiffness_n_per_m);

  double delay_s = 0.0;
  double specimen_stiffness_n_per_m = 0.0;  // the load cell reads k x_m (an elastic specimen)
  double sample_rate_hz = 8192.0;           // command history resolution; advances split to <= 1/rate
  Envelope rig;                             // the piston stops at +/- rig.stroke_m
  ChannelConverters converters{};           // servo.converters (none unless stated)

  // Throws std::invalid_argument naming the bad field. Not real-time safe.
  void validate() const;
};

class PureDelayPlant final : public Plant {
 public:
  // Sizes the command history for the delay. Not real-time safe.
  explicit PureDelayPlant(const PureDelayParameters& parameters);

  void reset(double displacement_m) override;
  // The command is linear over the interval; the history keeps one point per sub-interval.
  // Sub-intervals shorter than 1/sample_rate_hz use more history than sized: keep the
  // advance durations at or above it. Real-time safe.
  void advance(double command_start_m, double command_end_m, double duration_s) override;
  PlantMeasurement measure() const override;
  // The load cell reads the outside load too; the motion does not depend on it.
  bool accepts_external_load() const noexcept override { return true; }
  void set_external_load_n(double force_n) noexcept override { external_load_n_ = force_n; }

  double time_s() const { return time_s_; }

 private:
  struct Point {
    double time_s;
    double command_m;
  };
  double command_at(double time_s) const;
  void push(Point point);

  PureDelayParameters parameters_;
  std::vector<Point> history_;  // ring buffer, oldest at head_
  std::size_t head_ = 0;
  std::size_t size_ = 0;
  double time_s_ = 0.0;
  double external_load_n_ = 0.0;
};

}  // namespace rpsd::servo
