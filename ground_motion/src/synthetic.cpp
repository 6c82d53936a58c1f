#include "rpsd/ground_motion/synthetic.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "no_fp_contract.h"  // before small_matrix.h, whose loops it must cover
#include "rpsd/ground_motion/deterministic_math.h"
#include "rpsd/ground_motion/random.h"
#include "rpsd/ground_motion/record_error.h"
#include "small_matrix.h"

namespace rpsd::ground_motion {
namespace {

constexpr const char* kPrefix = "synthetic ground motion: ";

std::string short_text_of(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

void require(bool ok, const std::string& what) {
  if (!ok) throw RecordError(kPrefix + what);
}

bool positive(double x) { return x > 0.0 && std::isfinite(x); }

void validate(const SyntheticGroundMotionOptions& o) {
  require(positive(o.dt_s), "dt_s: expected a positive time step, got " + short_text_of(o.dt_s));
  require(positive(o.duration_s) && o.duration_s / o.dt_s <= 1e8,
          "duration_s: expected a positive duration of at most 1e8 steps, got " + short_text_of(o.duration_s));
  require(positive(o.kanai_tajimi.omega_g_rad_per_s),
          "kanai_tajimi.omega_g_rad_per_s: expected > 0, got " + short_text_of(o.kanai_tajimi.omega_g_rad_per_s));
  require(positive(o.kanai_tajimi.zeta_g),
          "kanai_tajimi.zeta_g: expected > 0, got " + short_text_of(o.kanai_tajimi.zeta_g));
  if (o.model == SpectralModel::kCloughPenzien) {
    require(positive(o.clough_penzien.omega_f_rad_per_s),
            "clough_penzien.omega_f_rad_per_s: expected > 0, got " + short_text_of(o.clough_penzien.omega_f_rad_per_s));
    require(positive(o.clough_penzien.zeta_f),
            "clough_penzien.zeta_f: expected > 0, got " + short_text_of(o.clough_penzien.zeta_f));
  }
  require(positive(o.white_noise_psd_m2_per_s3),
          "white_noise_psd_m2_per_s3: expected > 0, got " + short_text_of(o.white_noise_psd_m2_per_s3));
  if (o.target_pga_m_per_s2) {
    require(positive(*o.target_pga_m_per_s2),
            "target_pga_m_per_s2: expected > 0, got " + short_text_of(*o.target_pga_m_per_s2));
  }
  switch (o.envelope) {
    case EnvelopeKind::kStationary:
      break;
    case EnvelopeKind::kJenningsHousnerTsai: {
      const auto& e = o.jennings_housner_tsai;
      require(positive(e.rise_end_s), "jennings_housner_tsai.rise_end_s: expected > 0 (no default)");
      require(std::isfinite(e.strong_end_s) && e.strong_end_s >= e.rise_end_s,
              "jennings_housner_tsai.strong_end_s: expected >= rise_end_s (no default)");
      require(positive(e.decay_rate_per_s), "jennings_housner_tsai.decay_rate_per_s: expected > 0 (no default)");
      break;
    }
    case EnvelopeKind::kShinozukaSato: {
      const auto& e = o.shinozuka_sato;
      require(positive(e.a_per_s) && positive(e.b_per_s) && e.a_per_s < e.b_per_s,
              "shinozuka_sato: expected 0 < a_per_s < b_per_s (no default)");
      break;
    }
    case EnvelopeKind::kGavin: {
      const auto& e = o.gavin;
      require(std::isfinite(e.t0_s) && e.t0_s >= 0.0, "gavin.t0_s: expected >= 0, got " + short_text_of(e.t0_s));
      require(positive(e.aa), "gavin.aa: expected > 0, got " + short_text_of(e.aa));
      require(positive(e.ta_s), "gavin.ta_s: expected > 0, got " + short_text_of(e.ta_s));
      break;
    }
  }
}

// Decay rate of the slowest pole of s^2 + 2 zeta omega s + omega^2.
double slowest_decay_rate(double omega, double zeta) {
  return zeta < 1.0 ? zeta * omega : omega * (zeta - std::sqrt(zeta * zeta - 1.0));
}

std::string describe(const SyntheticGroundMotionOptions& o) {
  std::string text;
  const auto& kt = o.kanai_tajimi;
  switch (o.model) {
    case SpectralModel::kKanaiTajimi:
      text = "Kanai-Tajimi";
      break;
    case SpectralModel::kCloughPenzien:
      text = "Clough-Penzien";
      break;
    case SpectralModel::kBandPass:
      text = "band-pass (Gavin)";
      break;
  }
  text += " filter wg " + short_text_of(kt.omega_g_rad_per_s) + " rad/s zg " + short_text_of(kt.zeta_g);
  if (o.model == SpectralModel::kCloughPenzien) {
    text += ", wf " + short_text_of(o.clough_penzien.omega_f_rad_per_s) + " rad/s zf " +
            short_text_of(o.clough_penzien.zeta_f);
  }
  switch (o.envelope) {
    case EnvelopeKind::kStationary:
      text += "; stationary";
      break;
    case EnvelopeKind::kJenningsHousnerTsai:
      text += "; Jennings-Housner-Tsai envelope t1 " + short_text_of(o.jennings_housner_tsai.rise_end_s) + " s t2 " +
              short_text_of(o.jennings_housner_tsai.strong_end_s) + " s c " +
              short_text_of(o.jennings_housner_tsai.decay_rate_per_s) + " 1/s";
      break;
    case EnvelopeKind::kShinozukaSato:
      text += "; Shinozuka-Sato envelope a " + short_text_of(o.shinozuka_sato.a_per_s) + " 1/s b " +
              short_text_of(o.shinozuka_sato.b_per_s) + " 1/s";
      break;
    case EnvelopeKind::kGavin:
      text += "; Gavin envelope t0 " + short_text_of(o.gavin.t0_s) + " s aa " + short_text_of(o.gavin.aa) + " ta " +
              short_text_of(o.gavin.ta_s) + " s";
      break;
  }
  text += "; seed " + std::to_string(o.seed);
  return text;
}

SyntheticGroundMotionOptions gavin_preset(std::uint64_t seed, double pga, double f_g_hz, double zeta_g, double aa,
                                          double ta) {
  SyntheticGroundMotionOptions o;
  o.seed = seed;
  o.model = SpectralModel::kBandPass;
  o.kanai_tajimi.omega_g_rad_per_s = 2.0 * std::numbers::pi * f_g_hz;
  o.kanai_tajimi.zeta_g = zeta_g;
  o.envelope = EnvelopeKind::kGavin;
  o.gavin.aa = aa;
  o.gavin.ta_s = ta;
  o.target_pga_m_per_s2 = pga;
  return o;
}

}  // namespace

SyntheticGroundMotionOptions gavin_far_field(std::uint64_t seed) { return gavin_preset(seed, 3.5, 1.5, 0.9, 4.0, 2.0); }
SyntheticGroundMotionOptions gavin_near_field_no_pulse(std::uint64_t seed) {
  return gavin_preset(seed, 5.0, 1.3, 1.1, 3.0, 2.0);
}
SyntheticGroundMotionOptions gavin_near_field_pulse(std::uint64_t seed) {
  return gavin_preset(seed, 4.7, 0.5, 1.8, 1.0, 2.0);
}

double envelope_value(const SyntheticGroundMotionOptions& o, double t) {
  switch (o.envelope) {
    case EnvelopeKind::kStationary:
      return 1.0;
    case EnvelopeKind::kJenningsHousnerTsai: {
      const auto& e = o.jennings_housner_tsai;
      if (t < e.rise_end_s) return (t / e.rise_end_s) * (t / e.rise_end_s);
      if (t <= e.strong_end_s) return 1.0;
      return deterministic::exp(-e.decay_rate_per_s * (t - e.strong_end_s));
    }
    case EnvelopeKind::kShinozukaSato: {
      const double a = o.shinozuka_sato.a_per_s;
      const double b = o.shinozuka_sato.b_per_s;
      const double t_peak = deterministic::log(b / a) / (b - a);
      const double peak = deterministic::exp(-a * t_peak) - deterministic::exp(-b * t_peak);
      return (deterministic::exp(-a * t) - deterministic::exp(-b * t)) / peak;
    }
    case EnvelopeKind::kGavin: {
      const auto& e = o.gavin;
      if (t <= e.t0_s) return 0.0;
      const double x = (t - e.t0_s) / (e.aa * e.ta_s);
      return deterministic::exp(e.aa * (deterministic::log(x) + 1.0) - (t - e.t0_s) / e.ta_s);
    }
  }
  return 0.0;
}

GroundMotionRecord generate_synthetic_ground_motion(const SyntheticGroundMotionOptions& o) {
  validate(o);
  const double wg = o.kanai_tajimi.omega_g_rad_per_s;
  const double zg = o.kanai_tajimi.zeta_g;
  const double wf = o.clough_penzien.omega_f_rad_per_s;
  const double zf = o.clough_penzien.zeta_f;
  const bool cp = o.model == SpectralModel::kCloughPenzien;

  // State s = (x, x', y, y'); ZOH input w. Augmented [[A dt, B dt], [0, 0]].
  detail::SquareMatrix<5> m{};
  const double h = o.dt_s;
  m[0][1] = h;
  m[1][0] = -wg * wg * h;
  m[1][1] = -2.0 * zg * wg * h;
  m[1][4] = h;
  if (cp) {
    m[2][3] = h;
    m[3][0] = wg * wg * h;
    m[3][1] = 2.0 * zg * wg * h;
    m[3][2] = -wf * wf * h;
    m[3][3] = -2.0 * zf * wf * h;
  }
  const auto e = detail::matrix_exponential(m);
  double c[4] = {wg * wg, 2.0 * zg * wg, 0.0, 0.0};
  if (o.model == SpectralModel::kBandPass) c[0] = 0.0;
  if (cp) {
    c[2] = -wf * wf;
    c[3] = -2.0 * zf * wf;
  }

  double rate = slowest_decay_rate(wg, zg);
  if (cp) rate = std::min(rate, slowest_decay_rate(wf, zf));
  const double warm_up_steps = std::min(1e6, std::ceil(8.0 / rate / h));
  const auto n = static_cast<std::size_t>(std::floor(o.duration_s / h + 1e-9)) + 1;

  StandardNormal normal(o.seed);
  const double noise_scale = std::sqrt(2.0 * std::numbers::pi * o.white_noise_psd_m2_per_s3 / h);
  double s[4] = {0.0, 0.0, 0.0, 0.0};
  const auto advance = [&] {
    const double w = noise_scale * normal.next();
    double next[4];
    for (int i = 0; i < 4; ++i) {
      next[i] = e[i][0] * s[0] + e[i][1] * s[1] + e[i][2] * s[2] + e[i][3] * s[3] + e[i][4] * w;
    }
    for (int i = 0; i < 4; ++i) s[i] = next[i];
  };
  for (double k = 0; k < warm_up_steps; k += 1.0) advance();

  GroundMotionRecord record;
  record.source = "synthetic (seed " + std::to_string(o.seed) + ")";
  record.description = describe(o);
  record.format = RecordFormat::kSynthetic;
  record.original_unit = AccelerationUnit::kMPerS2;
  record.dt_s = h;
  record.acceleration_m_per_s2.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double output = c[0] * s[0] + c[1] * s[1] + c[2] * s[2] + c[3] * s[3];
    record.acceleration_m_per_s2[k] = envelope_value(o, static_cast<double>(k) * h) * output;
    advance();
  }
  if (o.baseline_correction) record = baseline_correct(record, *o.baseline_correction);
  if (o.target_pga_m_per_s2) {
    ScaleOptions scaling;
    scaling.target_pga_m_per_s2 = *o.target_pga_m_per_s2;
    record = scale(record, scaling);
  }
  return record;
}

}  // namespace rpsd::ground_motion
