// Synthetic ground-acceleration records: Gaussian white noise through a Kanai-Tajimi, Clough-Penzien or
// band-pass filter, times a deterministic envelope, optionally baseline-corrected, scaled to a target PGA.
// The filter is integrated exactly for noise held over each step and starts stationary. Seeded and
// bit-reproducible on every IEEE-754 machine (own PRNG and elementary functions, fixed-order loops, no
// fused multiply-add), so that the seed alone reproduces a record.
// Filter spectra, time scheme and the reproducibility check: docs/ground-motions.md
#pragma once

#include <cstdint>
#include <limits>
#include <optional>

#include "rpsd/ground_motion/processing.h"
#include "rpsd/ground_motion/record.h"

namespace rpsd::ground_motion {

enum class SpectralModel { kKanaiTajimi, kCloughPenzien, kBandPass };

// Literature values (reference sheet section 5): wg ~ 15.6 rad/s, zg ~ 0.6.
struct KanaiTajimiFilter {
  double omega_g_rad_per_s = 15.6;
  double zeta_g = 0.6;
};

// Literature values: wf ~ 0.1 wg (~1.5 rad/s), zf ~ zg.
struct CloughPenzienFilter {
  double omega_f_rad_per_s = 1.56;
  double zeta_f = 0.6;
};

enum class EnvelopeKind { kStationary, kJenningsHousnerTsai, kShinozukaSato, kGavin };

// (t / t1)^2 for t < t1, 1 up to t2, exp(-c (t - t2)) after. No default on the sheet: set all.
struct JenningsHousnerTsaiEnvelope {
  double rise_end_s = std::numeric_limits<double>::quiet_NaN();        // t1 > 0
  double strong_end_s = std::numeric_limits<double>::quiet_NaN();      // t2 >= t1
  double decay_rate_per_s = std::numeric_limits<double>::quiet_NaN();  // c > 0
};

// beta (exp(-a t) - exp(-b t)), beta chosen for a unit peak. No default on the sheet: set both.
struct ShinozukaSatoEnvelope {
  double a_per_s = std::numeric_limits<double>::quiet_NaN();  // 0 < a < b
  double b_per_s = std::numeric_limits<double>::quiet_NaN();
};

// Gavin eqgm_1d: ((t - t0) / (aa ta))^aa exp(aa - (t - t0) / ta) after t0, 0 before; peak 1
// at t0 + aa ta. Defaults: the far-field preset, t0 = 2 s.
struct GavinEnvelope {
  double t0_s = 2.0;
  double aa = 4.0;
  double ta_s = 2.0;
};

struct SyntheticGroundMotionOptions {
  std::uint64_t seed = 1;
  double dt_s = 0.005;
  double duration_s = 30.0;
  SpectralModel model = SpectralModel::kKanaiTajimi;
  KanaiTajimiFilter kanai_tajimi;
  CloughPenzienFilter clough_penzien;  // used by SpectralModel::kCloughPenzien
  EnvelopeKind envelope = EnvelopeKind::kGavin;
  GavinEnvelope gavin;
  JenningsHousnerTsaiEnvelope jennings_housner_tsai;
  ShinozukaSatoEnvelope shinozuka_sato;
  double white_noise_psd_m2_per_s3 = 1.0;                        // S0; irrelevant when scaling to a target PGA
  std::optional<BaselineCorrectionOptions> baseline_correction;  // applied before scaling
  // Scale last so that max |a| equals this (Gavin far-field: 3.5 m/s^2). Unset: keep the
  // level set by S0 (so the output's PSD is the model's, for checks).
  std::optional<double> target_pga_m_per_s2 = 3.5;
};

// Gavin's eqgm_1d presets (reference sheet): band-pass model, Gavin envelope, PGA.
// Not reproduced: his 25 Hz band limit on the noise, Planck tapers and record length.
SyntheticGroundMotionOptions gavin_far_field(std::uint64_t seed);            // 3.5, 1.5 Hz, 0.9, aa 4, ta 2
SyntheticGroundMotionOptions gavin_near_field_no_pulse(std::uint64_t seed);  // 5.0, 1.3 Hz, 1.1, aa 3, ta 2
SyntheticGroundMotionOptions gavin_near_field_pulse(std::uint64_t seed);     // 4.7, 0.5 Hz, 1.8, aa 1, ta 2

// Throws RecordError naming the option for any invalid parameter. Not real-time safe.
GroundMotionRecord generate_synthetic_ground_motion(const SyntheticGroundMotionOptions& options);

// Envelope value at t (validated options). Exposed for plots and tests.
double envelope_value(const SyntheticGroundMotionOptions& options, double t_s);

}  // namespace rpsd::ground_motion
