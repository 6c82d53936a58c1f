#include "rpsd/compensation/compensator_factory.h"

namespace rpsd::compensation {

namespace {

struct Make {
  std::unique_ptr<CommandCompensator> operator()(const PassThroughParameters& p) const {
    return std::make_unique<PassThroughCompensator>(p);
  }
  std::unique_ptr<CommandCompensator> operator()(const DiscretePhaseLeadParameters& p) const {
    return std::make_unique<DiscretePhaseLeadCompensator>(p);
  }
  std::unique_ptr<CommandCompensator> operator()(const PolynomialExtrapolationParameters& p) const {
    return std::make_unique<PolynomialExtrapolationCompensator>(p);
  }
  std::unique_ptr<CommandCompensator> operator()(const InverseCompensationParameters& p) const {
    return std::make_unique<InverseCompensator>(p);
  }
  std::unique_ptr<CommandCompensator> operator()(const AdaptiveInverseCompensationParameters& p) const {
    return std::make_unique<AdaptiveInverseCompensator>(p);
  }
  std::unique_ptr<CommandCompensator> operator()(const AdaptiveTimeSeriesParameters& p) const {
    return std::make_unique<AdaptiveTimeSeriesCompensator>(p);
  }
};

struct Name {
  std::string_view operator()(const PassThroughParameters&) const { return "none"; }
  std::string_view operator()(const DiscretePhaseLeadParameters&) const { return "phase_lead"; }
  std::string_view operator()(const PolynomialExtrapolationParameters&) const { return "polynomial_extrapolation"; }
  std::string_view operator()(const InverseCompensationParameters&) const { return "inverse"; }
  std::string_view operator()(const AdaptiveInverseCompensationParameters&) const { return "adaptive_inverse"; }
  std::string_view operator()(const AdaptiveTimeSeriesParameters&) const { return "adaptive_time_series"; }
};

}  // namespace

std::unique_ptr<CommandCompensator> make_compensator(const CompensatorConfig& config, double dt_s) {
  std::unique_ptr<CommandCompensator> compensator = std::visit(Make{}, config);
  compensator->configure(dt_s);
  return compensator;
}

std::string_view compensator_name(const CompensatorConfig& config) noexcept { return std::visit(Name{}, config); }

}  // namespace rpsd::compensation
