#include "rpsd/servo/pure_delay_plant.h"

#include <algorithm>
#include <cmath>

#include <stdexcept>
#include "substeps.h"

namespace rpsd::servo {

void PureDelayParameters::validate() const {
  if (!(delay_s >= 0.0) || !std::isfinite(delay_s)) throw std::invalid_argument("delay_s: must be zero or positive");
  if (!(specimen_stiffness_n_per_m >= 0.0))
    throw std::invalid_argument("specimen_stiffness_n_per_m: must be zero or positive");
  if (!(sample_rate_hz > 0.0) || sample_rate_hz > 1e6)
    throw std::invalid_argument("sample_rate_hz: must be positive, at most 1e6 Hz");
  if (delay_s * sample_rate_hz > 1e7) throw std::invalid_argument("delay_s: longer than 1e7 history points");
  rig.validate();
}

PureDelayPlant::PureDelayPlant(const PureDelayParameters& parameters) : parameters_(parameters) {
  parameters_.validate();
  // Twice the points the delay spans at the sample rate, plus the bracketing ones.
  history_.resize(2 * static_cast<std::size_t>(std::ceil(parameters_.delay_s * parameters_.sample_rate_hz)) + 8);
  reset(0.0);
}

void PureDelayPlant::reset(double displacement_m) {
  time_s_ = 0.0;
  head_ = 0;
  size_ = 0;
  push({0.0, displacement_m});
}

void PureDelayPlant::push(Point point) {
  if (size_ == history_.size()) {
    head_ = (head_ + 1) % history_.size();
    --size_;
  }
  history_[(head_ + size_) % history_.size()] = point;
  ++size_;
}

void PureDelayPlant::advance(double command_start_m, double command_end_m, double duration_s) {
  if (!(duration_s > 0.0)) return;
  const int pieces = detail::substeps(duration_s * parameters_.sample_rate_hz);
  const double t0 = time_s_;
  // The command may jump at the interval start (a new command); record that start point.
  const Point& newest = history_[(head_ + size_ - 1) % history_.size()];
  if (newest.command_m != command_start_m) push({t0, command_start_m});
  for (int i = 1; i <= pieces; ++i) {
    const double fraction = static_cast<double>(i) / pieces;
    push({t0 + fraction * duration_s, command_start_m + fraction * (command_end_m - command_start_m)});
  }
  time_s_ = t0 + duration_s;
}

double PureDelayPlant::command_at(double t) const {
  const auto at = [&](std::size_t i) -> const Point& { return history_[(head_ + i) % history_.size()]; };
  if (t <= at(0).time_s) return at(0).command_m;  // before the test began: the reset position
  // Binary search for the last point at or before t; a repeated time (a jump) takes the later value.
  std::size_t low = 0, high = size_ - 1;
  if (t >= at(high).time_s) return at(high).command_m;
  while (high - low > 1) {
    const std::size_t middle = (low + high) / 2;
    (at(middle).time_s <= t ? low : high) = middle;
  }
  const Point& a = at(low);
  const Point& b = at(high);
  return a.command_m + (b.command_m - a.command_m) * (t - a.time_s) / (b.time_s - a.time_s);
}

PlantMeasurement PureDelayPlant::measure() const {
  const double commanded = command_at(time_s_ - parameters_.delay_s);
  const double stroke = parameters_.rig.stroke_m;
  const double x = std::clamp(commanded, -stroke, stroke);  // the end stops
  return {x, parameters_.specimen_stiffness_n_per_m * x + external_load_n_, std::abs(commanded) >= stroke, false};
}

PureDelayParameters PureDelayParameters::read(config::Source& section, double specimen_stiffness_n_per_m) {
  PureDelayParameters d;
  d.delay_s = section.number(
      "delay_s", config::Number::between(0.0, 1.0, "s", "how long after its command the actuator is there"));
  d.specimen_stiffness_n_per_m = specimen_stiffness_n_per_m;
  d.rig = Envelope::read(*section.section("rig", "what the simulated rig can do"));
  return d;
}

}  // namespace rpsd::servo
