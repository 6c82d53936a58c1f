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

MultiSiteLink::MultiSiteLink(std::vector<SiteRoute> sites) {
  if (sites.empty()) throw std::invalid_argument("MultiSiteLink: at least one site");
  std::array<int, kMaxChannels> owners{};
  for (const SiteRoute& site : sites) {
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
  // Every channel belongs to a site, so there are at most as many sites as channels.
  for (const SiteRoute& site : sites) {
    Route& route = routes_[sites_++];
    route.link = site.link;
    route.site_id = site.site_id;
    route.count = static_cast<int>(site.channels.size());
    for (int i = 0; i < route.count; ++i) route.of[i] = static_cast<std::uint8_t>(site.channels[i]);
  }
  one_site_in_order_ = sites_ == 1;
  for (int i = 0; i < routes_[0].count; ++i) one_site_in_order_ = one_site_in_order_ && routes_[0].of[i] == i;
}

// Inline: from send() and send_each_site() alone.
inline LinkStatus MultiSiteLink::send_to(const Route& site, const CommandSample& command) {
  // The command's own fields, then the site's channels only: a site never sees another
  // site's channels (its unused entries stay 0), and no whole sample is copied per site.
  copy_command_header(command, site_command_, site.site_id, static_cast<std::uint8_t>(site.count));
  for (int i = 0; i < site.count; ++i) {
    const int ch = site.of[i];
    site_command_.displacement_m[i] = command.displacement_m[ch];
    site_command_.control_mode[i] = command.control_mode[ch];
    site_command_.force_n[i] = command.force_n[ch];
  }
  return site.link->send(site_command_);
}

LinkStatus MultiSiteLink::send(const CommandSample& command) {
  // One site: its status as it is (the worst of one), without the walk's frame.
  return sites_ == 1 ? send_to(routes_[0], command) : send_each_site(command);
}

LinkStatus MultiSiteLink::send_each_site(const CommandSample& command) {
  LinkStatus status = LinkStatus::kOk;
  for (int s = 0; s < sites_; ++s) status = worse(status, send_to(routes_[s], command));
  return status;
}

// Inline: from receive() alone.
inline LinkStatus MultiSiteLink::one_site_feedback(FeedbackSample& feedback) {
  // The site's channels are the test's: what receive() would merge is the site's sample as it
  // is, but for the fields the merged sample sets itself (its site, channel count and run).
  const std::uint64_t run_id = feedback.run_id;
  feedback.step = kNothingYet;
  const LinkStatus status = routes_[0].link->receive(feedback);
  if (feedback.step == kNothingYet) {  // not answered yet: everything else as it was
    feedback.step = -1;
    feedback.status = kNodeOk;
    feedback.limit_flags = kLimitNone;
  }
  feedback.run_id = run_id;
  feedback.site_id = 0;
  feedback.channels = static_cast<std::uint8_t>(channels_);
  return status;
}

LinkStatus MultiSiteLink::receive(FeedbackSample& feedback) {
  return one_site_in_order_ ? one_site_feedback(feedback) : merge_feedback(feedback);
}

LinkStatus MultiSiteLink::merge_feedback(FeedbackSample& feedback) {
  LinkStatus status = LinkStatus::kOk;
  feedback.status = kNodeOk;
  feedback.limit_flags = kLimitNone;
  feedback.channels = static_cast<std::uint8_t>(channels_);
  for (int s = 0; s < sites_; ++s) {
    const Route& site = routes_[s];
    // Marks the buffer so that a site which has not answered yet (its link leaves the
    // buffer untouched) is not taken for the site before it.
    site_feedback_.step = kNothingYet;
    status = worse(status, site.link->receive(site_feedback_));
    const bool answered = site_feedback_.step != kNothingYet;
    // A step is only as recent as its slowest site; one that never answered is at -1.
    const std::int64_t site_step = answered ? site_feedback_.step : -1;
    feedback.step = s == 0 ? site_step : std::min(feedback.step, site_step);
    if (s == 0 && answered) {
      feedback.test_id = site_feedback_.test_id;
      feedback.time_s = site_feedback_.time_s;
    }
    if (!answered) continue;  // its channels keep what they held
    feedback.status |= site_feedback_.status;
    feedback.limit_flags |= site_feedback_.limit_flags;
    for (int i = 0; i < site.count; ++i) {
      const int ch = site.of[i];
      feedback.displacement_m[ch] = site_feedback_.displacement_m[i];
      feedback.force_n[ch] = site_feedback_.force_n[i];
      feedback.round_trip_ns[ch] = site_feedback_.round_trip_ns[i];
    }
  }
  feedback.site_id = 0;
  return status;
}

}  // namespace rpsd::transport
