// One link that fans a test's commands out to several sites and merges their feedback:
// each site gets its own channels (renumbered from 0), its own link (in-process or DDS)
// and its own latency. The coordinator loop sees one link with all channels; a step is
// complete when every site has answered. A site's command carries its own channels only (the
// entries beyond them are 0).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "rpsd/transport/link.h"

namespace rpsd::transport {

struct SiteRoute {
  std::uint32_t site_id = 1;
  Link* link = nullptr;       // not owned
  std::vector<int> channels;  // the test's channel of each of the site's channels
};

class MultiSiteLink final : public Link {
 public:
  // Checks that every channel 0..n-1 belongs to exactly one site. Not real-time safe;
  // throws std::invalid_argument.
  explicit MultiSiteLink(std::vector<SiteRoute> sites);

  int channels() const { return channels_; }
  // Real-time safe.
  LinkStatus send(const CommandSample& command) override;
  // Worst status over the sites; the feedback holds every site's newest sample. Real-time safe.
  // With one site owning every channel in order (a test of one site), that site's link writes
  // the feedback itself, not through a copy of its own; beyond the test's channels it then holds
  // what the site sent there (a node sends 0), where several sites leave what it held.
  LinkStatus receive(FeedbackSample& feedback) override;

 private:
  // A site as send() and receive() walk it: its link, id and channels, in place.
  struct Route {
    Link* link = nullptr;
    std::uint32_t site_id = 0;
    int count = 0;                                // its channels
    std::array<std::uint8_t, kMaxChannels> of{};  // the test's channel of each of its channels
  };
  LinkStatus send_to(const Route& site, const CommandSample& command);
  // Out of line, so that a test of one site does not pay the frame of a walk over several.
  [[gnu::noinline]] LinkStatus send_each_site(const CommandSample& command);
  LinkStatus one_site_feedback(FeedbackSample& feedback);
  [[gnu::noinline]] LinkStatus merge_feedback(FeedbackSample& feedback);

  std::array<Route, kMaxChannels> routes_{};  // each site owns a channel: at most kMaxChannels
  int sites_ = 0;
  int channels_ = 0;
  bool one_site_in_order_ = false;
  CommandSample site_command_;
  FeedbackSample site_feedback_;
};

}  // namespace rpsd::transport
