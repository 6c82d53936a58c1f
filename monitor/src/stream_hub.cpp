#include "rpsd/monitor/stream_hub.h"

namespace rpsd::monitor {

StreamHub::StreamHub(StreamHubOptions options) : options_(options) {}

void StreamHub::push_all(const Message& message) {
  for (auto& [id, client] : clients_) {
    if (options_.client_queue_messages == 0) {
      ++client.dropped;
      ++dropped_total_;
      continue;
    }
    while (client.queue.size() >= options_.client_queue_messages) {
      client.queue.pop_front();  // the oldest goes: a live view wants the newest
      ++client.dropped;
      ++dropped_total_;
    }
    client.queue.push_back(message);
  }
  wake_.notify_all();
}

void StreamHub::publish_batch(std::string message, std::uint64_t run_id, double time_s) {
  const Message m = std::make_shared<const std::string>(std::move(message));
  const std::lock_guard lock(mutex_);
  if (run_id != recent_run_id_) {
    recent_batches_.clear();
    recent_run_id_ = run_id;
  }
  recent_batches_.push_back({time_s, m});
  while (!recent_batches_.empty() && (recent_batches_.size() > options_.recent_past_messages ||
                                      recent_batches_.front().time_s < time_s - options_.recent_past_s)) {
    recent_batches_.pop_front();
  }
  push_all(m);
}

void StreamHub::publish_event(std::string message) {
  const Message m = std::make_shared<const std::string>(std::move(message));
  const std::lock_guard lock(mutex_);
  recent_events_.push_back(m);
  while (recent_events_.size() > options_.recent_events) recent_events_.pop_front();
  push_all(m);
}

void StreamHub::publish_transient(std::string message) {
  const Message m = std::make_shared<const std::string>(std::move(message));
  const std::lock_guard lock(mutex_);
  push_all(m);
}

std::optional<StreamHub::ClientId> StreamHub::join() {
  const std::lock_guard lock(mutex_);
  if (closed_ || clients_.size() >= options_.max_clients) return std::nullopt;
  const ClientId id = next_id_++;
  Client& client = clients_[id];
  for (const Message& m : recent_events_) client.queue.push_back(m);
  for (const Kept& k : recent_batches_) client.queue.push_back(k.message);
  return id;
}

void StreamHub::leave(ClientId id) {
  const std::lock_guard lock(mutex_);
  clients_.erase(id);
}

bool StreamHub::next(ClientId id, std::vector<Message>& out, std::chrono::milliseconds timeout,
                     std::uint64_t& dropped) {
  std::unique_lock lock(mutex_);
  auto it = clients_.find(id);
  if (it == clients_.end() || closed_) return false;
  wake_.wait_for(lock, timeout, [&] {
    it = clients_.find(id);
    return closed_ || it == clients_.end() || !it->second.queue.empty();
  });
  if (closed_ || it == clients_.end()) return false;
  for (Message& m : it->second.queue) out.push_back(std::move(m));
  it->second.queue.clear();
  dropped = it->second.dropped;
  return true;
}

void StreamHub::close() {
  {
    const std::lock_guard lock(mutex_);
    closed_ = true;
  }
  wake_.notify_all();
}

std::size_t StreamHub::clients() const {
  const std::lock_guard lock(mutex_);
  return clients_.size();
}

std::uint64_t StreamHub::dropped_total() const {
  const std::lock_guard lock(mutex_);
  return dropped_total_;
}

}  // namespace rpsd::monitor
