// Conversions between rpsd's message structs and the idlc-generated wire types. Plain
// copies of fixed-size fields: real-time safe. Private to the transport library.
#pragma once

#include <algorithm>

#include "rpsd/transport/messages.h"
#include "rpsd_messages.h"

namespace rpsd::transport {

static_assert(rpsd_dds_MAX_CHANNELS == kMaxChannels, "the IDL and messages.h disagree on the channel count");

inline void to_wire(const CommandSample& in, rpsd_dds_Command& out) {
  out.test_id = in.test_id;
  out.site_id = in.site_id;
  out.step = in.step;
  out.time_s = in.time_s;
  out.channels = in.channels;
  std::copy(in.displacement_m.begin(), in.displacement_m.end(), out.displacement_m);
}

inline void from_wire(const rpsd_dds_Command& in, CommandSample& out) {
  out.test_id = in.test_id;
  out.site_id = in.site_id;
  out.step = in.step;
  out.time_s = in.time_s;
  out.channels = in.channels;
  std::copy(in.displacement_m, in.displacement_m + kMaxChannels, out.displacement_m.begin());
}

inline void to_wire(const FeedbackSample& in, rpsd_dds_Feedback& out) {
  out.test_id = in.test_id;
  out.site_id = in.site_id;
  out.step = in.step;
  out.time_s = in.time_s;
  out.channels = in.channels;
  std::copy(in.displacement_m.begin(), in.displacement_m.end(), out.displacement_m);
  std::copy(in.force_n.begin(), in.force_n.end(), out.force_n);
  out.status = in.status;
  out.limit_flags = in.limit_flags;
}

inline void from_wire(const rpsd_dds_Feedback& in, FeedbackSample& out) {
  out.test_id = in.test_id;
  out.site_id = in.site_id;
  out.step = in.step;
  out.time_s = in.time_s;
  out.channels = in.channels;
  std::copy(in.displacement_m, in.displacement_m + kMaxChannels, out.displacement_m.begin());
  std::copy(in.force_n, in.force_n + kMaxChannels, out.force_n.begin());
  out.status = in.status;
  out.limit_flags = in.limit_flags;
}

inline void to_wire(const NodeHeartbeat& in, rpsd_dds_NodeHeartbeat& out) {
  out.test_id = in.test_id;
  out.site_id = in.site_id;
  out.channels = in.channels;
  out.state = in.state;
  out.ticks = in.ticks;
  out.overruns = in.overruns;
  out.dropped_messages = in.dropped_messages;
  out.control_period_s = in.control_period_s;
}

inline void from_wire(const rpsd_dds_NodeHeartbeat& in, NodeHeartbeat& out) {
  out.test_id = in.test_id;
  out.site_id = in.site_id;
  out.channels = in.channels;
  out.state = in.state;
  out.ticks = in.ticks;
  out.overruns = in.overruns;
  out.dropped_messages = in.dropped_messages;
  out.control_period_s = in.control_period_s;
}

}  // namespace rpsd::transport
