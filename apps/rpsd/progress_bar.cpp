#include "progress_bar.h"

#include <unistd.h>

#include <string>

namespace rpsd::cli {

namespace {
double seconds(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }
}  // namespace

ProgressBar::ProgressBar(double control_rate_hz, std::FILE* out, bool terminal)
    : rate_hz_(control_rate_hz), out_(out), terminal_(terminal), start_(Clock::now()), case_start_(start_),
      last_plain_(start_) {}

ProgressBar::ProgressBar(double control_rate_hz) : ProgressBar(control_rate_hz, stderr, isatty(STDERR_FILENO) != 0) {}

ProgressBar::~ProgressBar() {
  if (drawn_ && terminal_) std::fprintf(out_, "\n");
}

void ProgressBar::operator()(const hybrid_test::ProgressReport& r) {
  const std::lock_guard lock(mutex_);
  const auto now = Clock::now();
  if (r.case_number != case_number_) case_number_ = r.case_number, case_start_ = now;
  if (terminal_ ? seconds(now - start_) < 1.0 : seconds(now - last_plain_) < kPlainEveryS) return;
  if (!terminal_ && r.planned <= 0) return;  // a log gets the steps only
  char where[48] = "";
  if (r.cases > 1) std::snprintf(where, sizeof where, "case %zu/%zu  ", r.case_number, r.cases);
  if (r.planned <= 0) {
    std::fprintf(out_, "\r%s%-12s%110s", where, std::string(r.phase).c_str(), "");
    drawn_ = true;
    return;
  }
  const double wall = seconds(now - case_start_), simulated = static_cast<double>(r.done) / rate_hz_;
  const double speed = wall > 0.0 ? simulated / wall : 0.0;
  const double fraction = static_cast<double>(r.done) / static_cast<double>(r.planned);
  // The case under way at its own pace, and every case after it as long as this one.
  double left = speed > 0.0 ? (static_cast<double>(r.planned - r.done) / rate_hz_) / speed : 0.0;
  if (fraction > 0.0) left += static_cast<double>(r.cases - r.case_number) * wall / fraction;
  char timing[80] = "";
  if (r.real_time) {
    std::snprintf(timing, sizeof timing, "  overruns %lld  worst feedback age %d", static_cast<long long>(r.overruns),
                  r.worst_feedback_age_periods);
  }
  if (terminal_) {
    const int width = 30, filled = static_cast<int>(width * fraction);
    std::fprintf(out_, "\r%s%-5s [%.*s%*s] %lld/%lld steps  %.1f s simulated  %.1fx real time  ETA %.0f s%s ", where,
                 std::string(r.phase).c_str(), filled, "##############################", width - filled, "",
                 static_cast<long long>(r.done), static_cast<long long>(r.planned), simulated, speed, left, timing);
  } else {
    std::fprintf(out_, "rpsd: %s%s %lld/%lld steps (%.0f %%)  %.1f s simulated  %.0f s left%s\n", where,
                 std::string(r.phase).c_str(), static_cast<long long>(r.done), static_cast<long long>(r.planned),
                 100.0 * fraction, simulated, left, timing);
    last_plain_ = now;
  }
  std::fflush(out_);
  drawn_ = true;
}

}  // namespace rpsd::cli
