// Conversions between rpsd's message structs and the idlc-generated wire types. Both sides
// use the same field names (std::array here, C arrays there), so one template per message
// copies either way. Plain copies of fixed-size fields: real-time safe. Private to the
// transport library.
#pragma once

#include <algorithm>

#include "rpsd/transport/messages.h"
#include "rpsd_messages.h"

namespace rpsd::transport {

static_assert(rpsd_dds_MAX_CHANNELS == kMaxChannels, "the IDL and messages.h disagree on the channel count");

// The fields every command and feedback sample starts with.
template <class In, class Out>
void copy_header(const In& in, Out& out) {
  out.test_id = in.test_id;
  out.site_id = in.site_id;
  out.run_id = in.run_id;
  out.step = in.step;
  out.time_s = in.time_s;
  out.channels = in.channels;
}

// CommandSample <-> rpsd_dds_Command (writer is local and not on the wire).
template <class In, class Out>
void copy_command(const In& in, Out& out) {
  copy_header(in, out);
  out.control_period_s = in.control_period_s;
  out.end_of_run = in.end_of_run;
  std::ranges::copy(in.displacement_m, std::begin(out.displacement_m));
  std::ranges::copy(in.control_mode, std::begin(out.control_mode));
  std::ranges::copy(in.force_n, std::begin(out.force_n));
}

// FeedbackSample <-> rpsd_dds_Feedback (round_trip_ns is local and not on the wire).
template <class In, class Out>
void copy_feedback(const In& in, Out& out) {
  copy_header(in, out);
  std::ranges::copy(in.displacement_m, std::begin(out.displacement_m));
  std::ranges::copy(in.force_n, std::begin(out.force_n));
  out.status = in.status;
  out.limit_flags = in.limit_flags;
}

// NodeHeartbeat <-> rpsd_dds_NodeHeartbeat (the fault text always NUL-terminated).
template <class In, class Out>
void copy_heartbeat(const In& in, Out& out) {
  out.test_id = in.test_id;
  out.site_id = in.site_id;
  out.channels = in.channels;
  out.state = in.state;
  out.ticks = in.ticks;
  out.overruns = in.overruns;
  out.dropped_messages = in.dropped_messages;
  out.control_period_s = in.control_period_s;
  out.coordinator_matched = in.coordinator_matched;
  out.serving_run_id = in.serving_run_id;
  static_assert(sizeof(out.fault_text) == kFaultTextBytes);
  std::ranges::copy(in.fault_text, std::begin(out.fault_text));
  out.fault_text[kFaultTextBytes - 1] = '\0';
  out.measured = in.measured;
  std::ranges::copy(in.displacement_m, std::begin(out.displacement_m));
  std::ranges::copy(in.force_n, std::begin(out.force_n));
}

}  // namespace rpsd::transport
