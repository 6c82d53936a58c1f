#include "rpsd/telemetry/effective_damping_identifier.h"

#include <cmath>

namespace rpsd::telemetry {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Below this, the fit's normal matrix is taken as singular: displacement and velocity
// not independent enough (relative to the product of their spreads).
constexpr double kMinIndependence = 1e-6;
}  // namespace

void EffectiveDampingIdentifier::configure(const LowestMode& mode, double control_rate_hz) {
  mode_ = mode;
  rate_hz_ = control_rate_hz;
  steps_needed_ =
      mode.known()
          ? static_cast<std::int64_t>(std::ceil(kPeriodsBeforeIdentifying * control_rate_hz / mode.frequency_hz))
          : 0;
  seen_ = 0;
  sums_ = {};
}

void EffectiveDampingIdentifier::observe(const coordinator::StepRecord& r) noexcept {
  if (!mode_.known()) return;
  const auto channels = std::min<std::size_t>(mode_.channel_weight.size(), r.channels);
  for (std::size_t c = 0; c < channels; ++c) {
    const double x = r.target_m[c];
    const double f = r.specimen_restoring_force_n[c];
    if (seen_ == 0) {
      origin_x_[c] = x;
      origin_f_[c] = f;
    }
    if (seen_ >= 2) {
      // The previous step, with its velocity centred on it.
      const double xp = x_previous_[c] - origin_x_[c];
      const double fp = f_previous_[c] - origin_f_[c];
      const double v = (x - x_before_[c]) * 0.5 * rate_hz_;
      Sums& s = sums_[c];
      s.n += 1.0;
      s.x += xp;
      s.v += v;
      s.f += fp;
      s.xx += xp * xp;
      s.xv += xp * v;
      s.vv += v * v;
      s.fx += fp * xp;
      s.fv += fp * v;
    }
    x_before_[c] = x_previous_[c];
    x_previous_[c] = x;
    f_previous_[c] = f;
  }
  ++seen_;
}

double EffectiveDampingIdentifier::damping_ratio() const noexcept {
  if (!mode_.known() || seen_ < steps_needed_ || seen_ < 3) return kNaN;
  double damping = mode_.numerical_damping_n_s_per_m;
  double stiffness = mode_.numerical_stiffness_n_per_m;
  for (std::size_t c = 0; c < mode_.channel_weight.size() && c < sums_.size(); ++c) {
    const double w = mode_.channel_weight[c];
    if (w == 0.0) continue;
    const Sums& s = sums_[c];
    // Centred (co)variances: the intercept c of f = a x + b v + c drops out.
    const double sxx = s.xx - s.x * s.x / s.n, sxv = s.xv - s.x * s.v / s.n, svv = s.vv - s.v * s.v / s.n;
    const double sfx = s.fx - s.f * s.x / s.n, sfv = s.fv - s.f * s.v / s.n;
    const double det = sxx * svv - sxv * sxv;
    if (!(sxx > 0.0 && svv > 0.0) || det <= kMinIndependence * sxx * svv) return kNaN;
    const double a = (sfx * svv - sfv * sxv) / det;
    const double b = (sfv * sxx - sfx * sxv) / det;
    damping += w * b;
    stiffness += w * a;
  }
  if (!(stiffness > 0.0)) return kNaN;  // no oscillating mode to speak of
  return damping / (2.0 * std::sqrt(stiffness));
}

}  // namespace rpsd::telemetry
