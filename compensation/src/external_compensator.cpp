#include "rpsd/compensation/external_compensator.h"

#include <cstdio>
#include <exception>
#include <limits>
#include <stdexcept>

#include "validation.h"

namespace rpsd::compensation {

std::string external_not_given(std::string_view key, std::string_view name) {
  return std::string(key) + " external `" + std::string(name) +
         "`: given only by a host program (rpsd.run(..., callables=...)); the command line cannot run it";
}

ExternalCompensatorParameters ExternalCompensatorParameters::read(config::Source& section) {
  ExternalCompensatorParameters p;
  p.name = section.text("name", "which of the host program's compensators (a Python callable's name in callables=)");
  const bool well_formed =
      !p.name.empty() && p.name.size() <= 64 &&
      p.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") ==
          std::string::npos;
  if (!well_formed) section.fail("name", "expected 1 to 64 letters, digits, '_', '-' or '.'");
  return p;
}

ExternalCompensator::ExternalCompensator(const ExternalCompensatorParameters& parameters, int channel)
    : name_(parameters.name), channel_(channel) {
  if (!parameters.source) throw std::invalid_argument(external_not_given("compensation.kind", parameters.name));
  try {
    host_ = parameters.source->make(channel);
  } catch (const std::exception& e) {
    throw std::invalid_argument("compensation external `" + name_ + "`: the host could not make channel " +
                                std::to_string(channel) + "'s compensator: " + e.what());
  }
  if (!host_) {
    throw std::invalid_argument("compensation external `" + name_ + "`: the host made no compensator for channel " +
                                std::to_string(channel));
  }
}

void ExternalCompensator::configure(double dt_s) {
  detail::require_positive("external compensator: dt_s", dt_s);
  failure_[0] = '\0';
  try {
    host_->configure(dt_s);
  } catch (const std::exception& e) {
    throw std::invalid_argument("compensation external `" + name_ + "`: configure(): " + e.what());
  }
  reset(0.0);
  if (failed()) throw std::invalid_argument("compensation external `" + name_ + "`: " + failure());
}

void ExternalCompensator::fail(const char* call, const char* what) noexcept {
  if (failed()) return;  // the first failure is the one that stopped the run
  std::snprintf(failure_.data(), failure_.size(), "%s: %s", call, what);
}

void ExternalCompensator::reset(double initial_displacement_m) noexcept {
  if (failed()) return;
  try {
    host_->reset(initial_displacement_m);
  } catch (const std::exception& e) {
    fail("reset()", e.what());
  } catch (...) {
    fail("reset()", "an exception that is no std::exception");
  }
}

double ExternalCompensator::command(double target_m) noexcept {
  constexpr double kStop = std::numeric_limits<double>::quiet_NaN();
  if (failed()) return kStop;
  try {
    return host_->command(target_m);
  } catch (const std::exception& e) {
    fail("command()", e.what());
  } catch (...) {
    fail("command()", "an exception that is no std::exception");
  }
  return kStop;
}

void ExternalCompensator::observe(double target_m, double measured_m) noexcept {
  if (failed()) return;
  try {
    host_->observe(target_m, measured_m);
  } catch (const std::exception& e) {
    fail("observe()", e.what());
  } catch (...) {
    fail("observe()", "an exception that is no std::exception");
  }
}

}  // namespace rpsd::compensation
