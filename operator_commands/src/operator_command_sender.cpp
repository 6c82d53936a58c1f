#include "rpsd/operator_commands/operator_command_sender.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <mutex>
#include <thread>

#include "operator_dds.h"
#include "operator_wire.h"
#include "rpsd/operator_commands/operator_command_handler.h"

namespace rpsd::operator_commands {

const char* operator_action_name(OperatorAction action) {
  switch (action) {
    case OperatorAction::kStop:
      return "stop";
    case OperatorAction::kAbort:
      return "abort";
    case OperatorAction::kHold:
      return "hold";
    case OperatorAction::kResume:
      return "resume";
  }
  return "unknown";
}

struct OperatorCommandSender::Impl {
  Impl(const OperatorLinkConfig& c, std::string name)
      : config(c), sender_name(std::move(name)), participant(c.domain_id, c.dds_config) {
    if (sender_name.size() > 63) sender_name.resize(63);
    const transport::DdsQos partition = operator_partition_qos(c.test_id);
    publisher =
        transport::DdsEntity(dds_create_publisher(participant.get(), partition.get(), nullptr), "dds_create_publisher");
    subscriber = transport::DdsEntity(dds_create_subscriber(participant.get(), partition.get(), nullptr),
                                      "dds_create_subscriber");
    writer = transport::DdsEntity(
        permitted(dds_create_writer(publisher.get(), participant.command_topic(), command_qos().get(), nullptr),
                  "dds_create_writer(rpsd_OperatorCommand)"),
        "dds_create_writer(rpsd_OperatorCommand)");
    reader = transport::DdsEntity(
        permitted(dds_create_reader(subscriber.get(), participant.reply_topic(), reply_qos().get(), nullptr),
                  "dds_create_reader(rpsd_OperatorReply)"),
        "dds_create_reader(rpsd_OperatorReply)");
    waitset = transport::DdsEntity(dds_create_waitset(participant.get()), "dds_create_waitset");
    data = transport::DdsEntity(dds_create_readcondition(reader.get(), DDS_ANY_STATE), "dds_create_readcondition");
    transport::dds_check(dds_waitset_attach(waitset.get(), data.get(), 0), "dds_waitset_attach");
    // Sequence numbers start at the clock, so a sender started again under the same name is
    // never answered with an earlier one's reply (the replies are transient-local).
    next_sequence = static_cast<std::uint64_t>(unix_now_ns());
  }

  OperatorLinkConfig config;
  std::string sender_name;
  OperatorParticipant participant;
  transport::DdsEntity publisher, subscriber, writer, reader, waitset, data;
  std::mutex mutex;  // one command in flight at a time: its reply is read by its own caller
  std::uint64_t next_sequence = 1;
};

OperatorCommandSender::OperatorCommandSender(const OperatorLinkConfig& config, std::string sender_name)
    : impl_(std::make_unique<Impl>(config, std::move(sender_name))) {}

OperatorCommandSender::~OperatorCommandSender() = default;

const std::string& OperatorCommandSender::sender_name() const { return impl_->sender_name; }

std::optional<OperatorReply> OperatorCommandSender::send(OperatorAction action, double timeout_s) {
  Impl& s = *impl_;
  const std::lock_guard lock(s.mutex);
  OperatorCommand command;
  command.test_id = s.config.test_id;
  command.action = action;
  copy_text(s.sender_name, command.sender);
  command.sequence = s.next_sequence++;
  command.sent_unix_ns = unix_now_ns();
  rpsd_operator_Command wire{};
  to_wire(command, wire);
  const auto start = std::chrono::steady_clock::now();
  const auto deadline = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                    std::chrono::duration<double>(timeout_s > 0.0 ? timeout_s : 0.0));
  // The first write waits for a coordinator's reader (discovery), up to the timeout. Until
  // answered, the command is repeated every 200 ms: one written before that reader had
  // discovered this writer too is lost (volatile), a repeat is not.
  for (;;) {
    dds_publication_matched_status_t matched{};
    if (dds_get_publication_matched_status(s.writer.get(), &matched) == 0 && matched.current_count > 0) break;
    if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  for (;;) {
    dds_write(s.writer.get(), &wire);
    const auto resend_at = std::chrono::steady_clock::now() + std::chrono::milliseconds(200);
    for (;;) {
      rpsd_operator_Reply reply_wire{};
      void* samples[1] = {&reply_wire};
      dds_sample_info_t info[1];
      while (dds_take(s.reader.get(), samples, info, 1, 1) > 0) {
        if (!info[0].valid_data) continue;
        OperatorReply reply;
        from_wire(reply_wire, reply);
        if (reply.sequence == command.sequence && reply.test_id == command.test_id &&
            std::strncmp(reply.sender.data(), command.sender.data(), command.sender.size()) == 0) {
          return reply;
        }
      }
      const auto now = std::chrono::steady_clock::now();
      if (now >= deadline) return std::nullopt;
      if (now >= resend_at) break;
      const auto wait = std::min(deadline, resend_at) - now;
      dds_waitset_wait(s.waitset.get(), nullptr, 0, std::chrono::duration_cast<std::chrono::nanoseconds>(wait).count());
    }
  }
}

}  // namespace rpsd::operator_commands
