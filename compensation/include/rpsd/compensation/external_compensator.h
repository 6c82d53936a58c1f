// The compensator a host program gives (`compensation: {kind: external, name: ...}`): a
// Python callable behind the `rpsd` module, or any C++ object, for rehearsals only (lock-step,
// as fast as possible; a real-time clock is refused where the scenario is read). The file
// names it; the host's ExternalCompensatorSource makes one HostCompensator per channel and
// run, so each keeps its own state between calls. ExternalCompensator wraps it for the loop:
// a host call that throws is caught and kept, the command turns non-finite so that the
// coordinator's stroke check stops the step before anything is sent, and the test ends the
// run with the host's message (hybrid_test: StepOutcome::kHostCallFailed).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "rpsd/compensation/command_compensator.h"
#include "rpsd/config/source.h"

namespace rpsd::compensation {

// The host's compensator of one channel for one run. Its calls may throw (any exception):
// the wrapper catches them. Called on the thread that runs the test, never concurrently.
class HostCompensator {
 public:
  virtual ~HostCompensator() = default;
  // Once, before the run's first reset(): the control period the commands are for.
  virtual void configure(double /*dt_s*/) {}
  // At rest holding initial_displacement_m, before the first command.
  virtual void reset(double /*initial_displacement_m*/) {}
  // The command for this control step's target, once per step.
  virtual double command(double target_m) = 0;
  // This step's target and the displacement measured at its end, after command().
  virtual void observe(double /*target_m*/, double /*measured_m*/) {}
};

// What a host program gives for one name: a new compensator at rest for each channel of
// each run (the test, each case of a sweep or a Monte Carlo batch). make() may throw: the
// run is then refused with its message. Called on the thread that builds the run.
class ExternalCompensatorSource {
 public:
  virtual ~ExternalCompensatorSource() = default;
  virtual std::unique_ptr<HostCompensator> make(int channel) const = 0;
};

class ExternalCompensator;

struct ExternalCompensatorParameters {
  static constexpr std::string_view kName = "external";
  static constexpr std::string_view kSummary =
      "given by a host program by name (a Python callable through rpsd.run(..., callables=...)); lock-step only";
  using Compensator = ExternalCompensator;
  static ExternalCompensatorParameters read(config::Source& section);

  std::string name;  // compensation.name: which of the host's compensators
  // The host's, filled in by the reader from what the host program gave it; a file cannot
  // set it. Shared by every copy of the configuration (a sweep's cases); never copied itself.
  std::shared_ptr<const ExternalCompensatorSource> source;
};

class ExternalCompensator final : public CommandCompensator {
 public:
  // Throws std::invalid_argument naming the key when the parameters carry no source (a
  // file run by the command line), or with the host's message when its make() throws.
  // Not real-time safe.
  explicit ExternalCompensator(const ExternalCompensatorParameters& parameters, int channel = 0);

  // Throws std::invalid_argument with the host's message. Not real-time safe.
  void configure(double dt_s) override;
  // The host's calls, each caught: after a failure, no further call reaches the host, every
  // command is NaN and failed() says why. Not real-time safe (the host's code runs).
  void reset(double initial_displacement_m) noexcept override;
  double command(double target_m) noexcept override;
  void observe(double target_m, double measured_m) noexcept override;
  // The host states no lead: rpsd cannot know it.
  double compensated_delay_s() const noexcept override { return 0.0; }
  std::string_view name() const noexcept override { return ExternalCompensatorParameters::kName; }

  // Whether a host call threw, and its message ("command(): <what>"; truncated to fit).
  bool failed() const noexcept { return failure_[0] != '\0'; }
  const char* failure() const noexcept { return failure_.data(); }
  const std::string& host_name() const noexcept { return name_; }
  int channel() const noexcept { return channel_; }

 private:
  void fail(const char* call, const char* what) noexcept;

  std::string name_;
  int channel_ = 0;
  std::unique_ptr<HostCompensator> host_;
  std::array<char, 256> failure_{};
};

// The message of a file whose external part no host program gave (the command line).
std::string external_not_given(std::string_view key, std::string_view name);

}  // namespace rpsd::compensation
