// The live stream to every browser: each message (a batch or an event as JSON) goes into a
// bounded queue per browser, so that a slow browser loses its own oldest messages, counted,
// and never slows the others or the reader of the telemetry. A browser that joins gets the
// recent past first (the last recent_past_s of batches of the current run, the recent
// events). Thread-safe; not real-time safe.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace rpsd::monitor {

struct StreamHubOptions {
  std::size_t client_queue_messages = 512;  // per browser; beyond it the oldest are dropped
  std::size_t max_clients = 16;             // streams at once; one more is refused
  double recent_past_s = 10.0;              // test time kept for a browser that joins
  std::size_t recent_past_messages = 2048;  // and never more messages than this
  std::size_t recent_events = 256;          // events kept for a browser that joins
};

class StreamHub {
 public:
  using Message = std::shared_ptr<const std::string>;
  using ClientId = std::uint64_t;

  explicit StreamHub(StreamHubOptions options = {});

  // A batch of run `run_id` ending at test time `time_s`; a new run_id forgets the old run's.
  void publish_batch(std::string message, std::uint64_t run_id, double time_s);
  void publish_event(std::string message);
  // To every browser now, not kept for those who join later (status, notices).
  void publish_transient(std::string message);

  // A new browser, its queue holding the recent past; nullopt when max_clients stream already.
  std::optional<ClientId> join();
  void leave(ClientId id);
  // Moves the browser's queued messages into `out`, waiting up to `timeout` for one. False
  // when the client is unknown or the hub is closed. `dropped` is its count of messages lost.
  bool next(ClientId id, std::vector<Message>& out, std::chrono::milliseconds timeout, std::uint64_t& dropped);
  // Ends every stream (the server is stopping).
  void close();

  std::size_t clients() const;
  std::uint64_t dropped_total() const;

 private:
  struct Client {
    std::deque<Message> queue;
    std::uint64_t dropped = 0;
  };
  void push_all(const Message& message);  // with mutex_ held

  StreamHubOptions options_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool closed_ = false;
  ClientId next_id_ = 1;
  std::map<ClientId, Client> clients_;
  struct Kept {
    double time_s;
    Message message;
  };
  std::deque<Kept> recent_batches_;
  std::uint64_t recent_run_id_ = 0;
  std::deque<Message> recent_events_;
  std::uint64_t dropped_total_ = 0;
};

}  // namespace rpsd::monitor
