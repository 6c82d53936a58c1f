#include "rpsd/telemetry/telemetry_subscriber.h"

#include <array>

#include "telemetry_topics.h"

namespace rpsd::telemetry {

namespace {

// Samples taken per dds_take call; the loop goes on until a call takes none.
constexpr int kTakeChunk = 16;

template <class Wire, class Out>
std::size_t take_all(dds_entity_t reader, std::vector<Out>& out) {
  std::array<Wire, kTakeChunk> buffers{};
  std::array<void*, kTakeChunk> pointers{};
  std::array<dds_sample_info_t, kTakeChunk> infos{};
  for (int i = 0; i < kTakeChunk; ++i) pointers[static_cast<std::size_t>(i)] = &buffers[static_cast<std::size_t>(i)];
  std::size_t taken = 0;
  for (;;) {
    const dds_return_t n = dds_take(reader, pointers.data(), infos.data(), kTakeChunk, kTakeChunk);
    if (n <= 0) break;
    for (int i = 0; i < n; ++i) {
      if (!infos[static_cast<std::size_t>(i)].valid_data) continue;
      out.emplace_back();
      from_wire(buffers[static_cast<std::size_t>(i)], out.back());
      ++taken;
    }
    if (n < kTakeChunk) break;
  }
  return taken;
}

}  // namespace

struct TelemetrySubscriber::Parts {
  explicit Parts(const TelemetrySubscriberConfig& c)
      : participant(c.domain_id, c.dds_config),
        subscriber(dds_create_subscriber(participant.get(), telemetry_partition_qos(c.test_id).get(), nullptr),
                   "dds_create_subscriber(telemetry)"),
        batch_reader(dds_create_reader(subscriber.get(), participant.batch_topic(), telemetry_qos(kBatchHistory).get(),
                                       nullptr),
                     "dds_create_reader(rpsd_TelemetryBatch)"),
        event_reader(dds_create_reader(subscriber.get(), participant.event_topic(), telemetry_qos(kEventHistory).get(),
                                       nullptr),
                     "dds_create_reader(rpsd_TelemetryEvent)"),
        waitset(dds_create_waitset(participant.get()), "dds_create_waitset(telemetry)"),
        batch_ready(dds_create_readcondition(batch_reader.get(), DDS_ANY_STATE), "dds_create_readcondition(batches)"),
        event_ready(dds_create_readcondition(event_reader.get(), DDS_ANY_STATE), "dds_create_readcondition(events)") {
    transport::dds_check(dds_waitset_attach(waitset.get(), batch_ready.get(), 0), "dds_waitset_attach(batches)");
    transport::dds_check(dds_waitset_attach(waitset.get(), event_ready.get(), 0), "dds_waitset_attach(events)");
  }

  TelemetryParticipant participant;
  transport::DdsEntity subscriber, batch_reader, event_reader, waitset, batch_ready, event_ready;
};

TelemetrySubscriber::TelemetrySubscriber(const TelemetrySubscriberConfig& config)
    : parts_(std::make_unique<Parts>(config)) {}

TelemetrySubscriber::~TelemetrySubscriber() = default;

std::size_t TelemetrySubscriber::take(std::vector<TelemetryBatch>& batches, std::vector<TelemetryEvent>& events) {
  const std::size_t b = take_all<rpsd_telemetry_Batch>(parts_->batch_reader.get(), batches);
  return b + take_all<rpsd_telemetry_Event>(parts_->event_reader.get(), events);
}

bool TelemetrySubscriber::wait(std::chrono::milliseconds timeout) {
  const dds_return_t n = dds_waitset_wait(parts_->waitset.get(), nullptr, 0, DDS_MSECS(timeout.count()));
  return n > 0;
}

bool TelemetrySubscriber::publisher_alive() const {
  dds_liveliness_changed_status_t status{};
  if (dds_get_liveliness_changed_status(parts_->batch_reader.get(), &status) < 0) return false;
  return status.alive_count > 0;
}

}  // namespace rpsd::telemetry
