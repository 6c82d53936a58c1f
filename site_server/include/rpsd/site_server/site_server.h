// rpsd as the experimental site of an OpenSees model: each trial displacement of the
// genericClient element goes, at its force request, through one ExperimentalExchange (the
// site's compensators, the coordinator's limits, the actuators in process or the servo
// nodes over DDS) and is recorded; the specimens' forces go back in the element's DOFs.
// OpenSees paces the test (lock-step): one command per trial, at the site's control period.
#pragma once

#include <memory>
#include <string>

#include "rpsd/coordinator/experimental_exchange.h"
#include "rpsd/coordinator/recorder.h"
#include "rpsd/opensees/client_gate.h"
#include "rpsd/opensees/generic_client_session.h"
#include "rpsd/site_server/site_server_config.h"

namespace rpsd::hybrid_test {
class ActuatorLinks;
}

namespace rpsd::site_server {

struct SiteRun {
  opensees::SessionEnd end;
  coordinator::StepOutcome outcome = coordinator::StepOutcome::kOk;  // the exchange that stopped it
  coordinator::LimitStop limit_stop;
  std::string stop_text;  // why the site stopped (a limit, a time step OpenSees and the site disagree on)
  std::int64_t exchanges = 0, commits = 0;
  std::int64_t drained = 0;  // requests answered with not-a-number after the stop
  std::uint64_t run_id = 0;
  std::string write_error;  // the records could not be written
  std::string client_sizes;
  std::vector<double> peak_measured_m, peak_force_n;  // per channel
  opensees::GateReport gate;                          // the connections turned away before OpenSees'
};

class SiteServer : public opensees::GenericClientSite {
 public:
  // Builds the site and puts its actuators at rest at zero. Not real-time safe.
  SiteServer(const SiteServerConfig& config, const std::filesystem::path& csv);
  ~SiteServer() override;

  // How a session with this site's element is served (its DOFs, the listen section's
  // timeouts), ended at once by `stop`.
  opensees::SessionOptions session_options(const opensees::StopRequest& stop) const;
  // Serves one OpenSees client to its end and stops the recorder. Not real-time safe.
  SiteRun serve(opensees::GenericClientSession& session);
  SiteRun serve(opensees::TcpStream stream, const opensees::StopRequest& stop);

  // opensees::GenericClientSite; each allocates nothing.
  bool set_trial(std::span<const double> displacement, std::span<const double> velocity,
                 std::span<const double> acceleration, double time_s) override;
  bool force(std::span<double> force) override;
  void measured_displacement(std::span<double> displacement) override;
  void stiffness(std::span<double> matrix) override;
  void commit() override;

  // The run so far, and the actuators (for tests and reports). Not real-time safe.
  const SiteRun& run() const { return run_; }
  const hybrid_test::ActuatorLinks& actuators() const { return *actuators_; }

 private:
  bool stop(coordinator::StepOutcome outcome);
  // The trial displacement a channel's is measured from (its relative_to DOF's, or zero).
  double reference_of(std::size_t channel) const;

  const SiteServerConfig& config_;
  double control_period_s_ = 0.0;
  std::vector<std::unique_ptr<compensation::CommandCompensator>> compensators_;
  std::unique_ptr<hybrid_test::ActuatorLinks> actuators_;
  std::unique_ptr<coordinator::ExperimentalExchange> exchange_;
  std::unique_ptr<coordinator::Recorder> recorder_;
  Eigen::VectorXd targets_, trial_d_, trial_v_, trial_a_, basic_force_;
  coordinator::StepRecord record_;
  SiteRun run_;
  double trial_time_s_ = 0.0, step_time_s_ = 0.0;
  bool pending_ = false, stopped_ = false, commanded_ = false;
};

}  // namespace rpsd::site_server
