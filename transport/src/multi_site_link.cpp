#include "rpsd/transport/multi_site_link.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace rpsd::transport {

namespace {
// kOk < kTimeout < kStaleStep < kPeerLost < kRefused: the worst site decides.
LinkStatus worse(LinkStatus a, LinkStatus b) { return static_cast<int>(a) >= static_cast<int>(b) ? a : b; }
constexpr std::int64_t kNothingYet = std::numeric_limits<std::int64_t>::min();
}  // namespace

MultiSiteLink::MultiSiteLink(std::vector<SiteRoute> sites) : sites_(std::move(sites)) {
  if (sites_.empty()) throw std::invalid_argument("MultiSiteLink: at least one site");
  std::array<int, kMaxChannels> owners{};
  for (const SiteRoute& site : sites_) {
    if (site.link == nullptr)
      throw std::invalid_argument("MultiSiteLink: site " + std::to_string(site.site_id) + " has no link");
    if (site.channels.empty() || site.channels.size() > static_cast<std::size_t>(kMaxChannels)) {
      throw std::invalid_argument("MultiSiteLink: site " + std::to_string(site.site_id) + " needs 1 to " +
                                  std::to_string(kMaxChannels) + " channels");
    }
    for (int ch : site.channels) {
      if (ch < 0 || ch >= kMaxChannels)
        throw std::invalid_argument("MultiSiteLink: channel " + std::to_string(ch) + " out of range");
      if (owners[ch]++ > 0)
        throw std::invalid_argument("MultiSiteLink: channel " + std::to_string(ch) + " belongs to two sites");
      channels_ = std::max(channels_, ch + 1);
    }
  }
  for (int ch = 0; ch < channels_; ++ch) {
    if (owners[ch] == 0)
      throw std::invalid_argument("MultiSiteLink: channel " + std::to_string(ch) + " belongs to no site");
  }
}

LinkStatus MultiSiteLink::send(const CommandSample& command) {
  LinkStatus status = LinkStatus::kOk;
  for (const SiteRoute& site : sites_) {
    // The command's own fields, then the site's channels only: a site never sees another
    // site's channels (its unused entries stay 0), and no whole sample is copied per site.
    copy_command_header(command, site_command_);
    site_command_.site_id = site.site_id;
    site_command_.channels = static_cast<std::uint8_t>(site.channels.size());
    for (std::size_t i = 0; i < site.channels.size(); ++i) {
      site_command_.displacement_m[i] = command.displacement_m[site.channels[i]];
      site_command_.control_mode[i] = command.control_mode[site.channels[i]];
      site_command_.force_n[i] = command.force_n[site.channels[i]];
    }
    status = worse(status, site.link->send(site_command_));
  }
  return status;
}

LinkStatus MultiSiteLink::receive(FeedbackSample& feedback) {
  LinkStatus status = LinkStatus::kOk;
  feedback.status = kNodeOk;
  feedback.limit_flags = kLimitNone;
  feedback.channels = static_cast<std::uint8_t>(channels_);
  bool first = true;
  for (const SiteRoute& site : sites_) {
    // Marks the buffer so that a site which has not answered yet (its link leaves the
    // buffer untouched) is not taken for the site before it.
    site_feedback_.step = kNothingYet;
    status = worse(status, site.link->receive(site_feedback_));
    const bool answered = site_feedback_.step != kNothingYet;
    // A step is only as recent as its slowest site; one that never answered is at -1.
    const std::int64_t site_step = answered ? site_feedback_.step : -1;
    feedback.step = first ? site_step : std::min(feedback.step, site_step);
    if (first && answered) {
      feedback.test_id = site_feedback_.test_id;
      feedback.time_s = site_feedback_.time_s;
    }
    first = false;
    if (!answered) continue;  // its channels keep what they held
    feedback.status |= site_feedback_.status;
    feedback.limit_flags |= site_feedback_.limit_flags;
    for (std::size_t i = 0; i < site.channels.size(); ++i) {
      const int ch = site.channels[i];
      feedback.displacement_m[ch] = site_feedback_.displacement_m[i];
      feedback.force_n[ch] = site_feedback_.force_n[i];
      feedback.round_trip_ns[ch] = site_feedback_.round_trip_ns[i];
    }
  }
  feedback.site_id = 0;
  return status;
}

}  // namespace rpsd::transport
