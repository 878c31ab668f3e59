#pragma once
// The outgoing queue of one live client (the stream and the Foxglove connection): a publisher
// must never wait for a client, so each session queues what it has not sent yet. Telemetry is
// latest-value-wins — an unsent older item with the same key is replaced in place, keeping its
// position — and events are queued; more than `event_limit` unsent events means the client is
// too slow, and the session closes it rather than hold memory for it or slow the others.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <utility>

namespace avk::server {

template <class Item>
class SendQueue {
 public:
  explicit SendQueue(std::size_t event_limit) : event_limit_(event_limit) {}

  // key: latest-value-wins under this key; none: an event. False when the event limit is passed.
  bool push(Item item, std::optional<std::uint64_t> key) {
    if (key) {
      for (auto& e : queue_) {
        if (e.key == key) {
          e.item = std::move(item);
          return true;
        }
      }
    } else if (++events_ > event_limit_) {
      return false;
    }
    queue_.push_back({std::move(item), key});
    return true;
  }

  Item pop() {
    Item item = std::move(queue_.front().item);
    if (!queue_.front().key) --events_;
    queue_.pop_front();
    return item;
  }

  bool empty() const { return queue_.empty(); }
  void clear() {
    queue_.clear();
    events_ = 0;
  }

 private:
  struct Entry {
    Item item;
    std::optional<std::uint64_t> key;
  };
  std::deque<Entry> queue_;
  std::size_t events_ = 0;
  std::size_t event_limit_;
};

}  // namespace avk::server
