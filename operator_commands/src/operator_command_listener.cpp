#include "rpsd/operator_commands/operator_command_listener.h"

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>

#include "operator_dds.h"
#include "operator_wire.h"

namespace rpsd::operator_commands {

namespace {

bool names_security(const std::string& xml) { return xml.find("<Security") != std::string::npos; }

std::string file_text(std::string path) {
  if (path.rfind("file://", 0) == 0) path.erase(0, 7);
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

bool dds_security_configured(const std::string& config_file) {
  if (!config_file.empty()) return names_security(file_text(config_file));
  const char* uri = std::getenv("CYCLONEDDS_URI");
  if (!uri) return false;
  // A comma-separated list of files and inline XML fragments.
  std::stringstream list(uri);
  std::string item;
  while (std::getline(list, item, ',')) {
    const auto first = item.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    item.erase(0, first);
    if (item[0] == '<' ? names_security(item) : names_security(file_text(item))) return true;
  }
  return false;
}

struct OperatorCommandListener::Impl {
  Impl(const OperatorLinkConfig& link, OperatorHandlerOptions options, OperatorControl& control)
      : handler(std::move(options), control), participant(link.domain_id, link.dds_config) {
    const transport::DdsQos partition = operator_partition_qos(link.test_id);
    subscriber = transport::DdsEntity(dds_create_subscriber(participant.get(), partition.get(), nullptr),
                                      "dds_create_subscriber");
    publisher =
        transport::DdsEntity(dds_create_publisher(participant.get(), partition.get(), nullptr), "dds_create_publisher");
    reader = transport::DdsEntity(
        dds_create_reader(subscriber.get(), participant.command_topic(), command_qos().get(), nullptr),
        "dds_create_reader(rpsd_OperatorCommand)");
    writer =
        transport::DdsEntity(dds_create_writer(publisher.get(), participant.reply_topic(), reply_qos().get(), nullptr),
                             "dds_create_writer(rpsd_OperatorReply)");
    waitset = transport::DdsEntity(dds_create_waitset(participant.get()), "dds_create_waitset");
    data = transport::DdsEntity(dds_create_readcondition(reader.get(), DDS_ANY_STATE), "dds_create_readcondition");
    wake = transport::DdsEntity(dds_create_guardcondition(participant.get()), "dds_create_guardcondition");
    transport::dds_check(dds_waitset_attach(waitset.get(), data.get(), 0), "dds_waitset_attach");
    transport::dds_check(dds_waitset_attach(waitset.get(), wake.get(), 1), "dds_waitset_attach");
    thread = std::thread([this] { serve(); });
  }

  ~Impl() {
    done.store(true);
    dds_set_guardcondition(wake.get(), true);
    thread.join();
  }

  void serve() {
    while (!done.load()) {
      dds_waitset_wait(waitset.get(), nullptr, 0, DDS_SECS(1));
      rpsd_operator_Command wire{};
      void* samples[1] = {&wire};
      dds_sample_info_t info[1];
      while (!done.load() && dds_take(reader.get(), samples, info, 1, 1) > 0) {
        OperatorCommand command;
        if (!info[0].valid_data || !from_wire(wire, command)) continue;
        if (const auto reply = handler.handle(command, unix_now_ns())) {
          rpsd_operator_Reply out{};
          to_wire(*reply, out);
          dds_write(writer.get(), &out);
        }
      }
    }
  }

  OperatorCommandHandler handler;
  OperatorParticipant participant;
  transport::DdsEntity subscriber, publisher, reader, writer, waitset, data, wake;
  std::atomic<bool> done{false};
  std::thread thread;
};

OperatorCommandListener::OperatorCommandListener(const OperatorLinkConfig& link, OperatorHandlerOptions options,
                                                 OperatorControl& control)
    : impl_(std::make_unique<Impl>(link, std::move(options), control)) {}

OperatorCommandListener::~OperatorCommandListener() = default;

std::vector<OperatorCommandEvent> OperatorCommandListener::log() const { return impl_->handler.log(); }

}  // namespace rpsd::operator_commands
