#include "server/stream_hub.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <random>

#include "server/serialize/station.hpp"

namespace avk::server {

namespace {
const std::vector<std::string> kTopics = {"nav", "helm", "mission", "turn", "status", "current"};

std::string random_id() {
  std::random_device rd;
  std::uniform_int_distribution<std::uint64_t> d;
  const std::uint64_t v = d(rd) ^ static_cast<std::uint64_t>(
                                      std::chrono::steady_clock::now().time_since_epoch().count());
  static const char* hex = "0123456789abcdef";
  std::string s(16, '0');
  for (int i = 0; i < 16; ++i)
    s[static_cast<std::size_t>(i)] = hex[(v >> (4 * i)) & 0xF];
  return s;
}
}  // namespace

StreamHub::StreamHub() : session_id_(random_id()) {}

const std::vector<std::string>& StreamHub::topics() {
  return kTopics;
}

bool StreamHub::is_topic(const std::string& topic) {
  return std::find(kTopics.begin(), kTopics.end(), topic) != kTopics.end();
}

std::string StreamHub::hello(const std::string& server_version) const {
  return stream_hello_json(server_version, session_id_, kTopics).dump();
}

void StreamHub::subscribe(const std::shared_ptr<StreamSink>& sink, const std::string& topic) {
  std::lock_guard lock(mutex_);
  auto& list = subscribers_[topic];
  for (const auto& w : list)
    if (w.lock() == sink) return;
  list.push_back(sink);
}

void StreamHub::unsubscribe(const StreamSink* sink, const std::string& topic) {
  std::lock_guard lock(mutex_);
  auto& list = subscribers_[topic];
  std::erase_if(list, [&](const std::weak_ptr<StreamSink>& w) {
    const auto s = w.lock();
    return !s || s.get() == sink;
  });
}

void StreamHub::unsubscribe_all(const StreamSink* sink) {
  for (const auto& t : kTopics)
    unsubscribe(sink, t);
}

void StreamHub::publish(const std::string& topic, double t_s, const std::string& data_json,
                        const std::string& vehicle_id) {
  std::vector<std::shared_ptr<StreamSink>> targets;
  auto message = std::make_shared<StreamMessage>();
  {
    std::lock_guard lock(mutex_);
    message->topic = topic;
    message->seq = ++seq_[topic];
    message->latest_value_wins = topic == "nav" || topic == "helm" || topic == "current";
    message->latest_key = topic + '/' + vehicle_id;
    message->rate_limitable = topic == "nav" || topic == "helm";
    auto& list = subscribers_[topic];
    std::erase_if(list, [](const std::weak_ptr<StreamSink>& w) { return w.expired(); });
    for (const auto& w : list)
      if (auto s = w.lock()) targets.push_back(std::move(s));
  }
  // Built once for every client; "data" is spliced in as it came, already JSON.
  std::string text = R"({"topic":")" + topic + R"(","seq":)" + std::to_string(message->seq) +
                     R"(,"t":)" + nlohmann::json(t_s).dump() + R"(,"data":)" + data_json + "}";
  message->payload = std::make_shared<const std::string>(std::move(text));
  std::shared_ptr<const StreamMessage> shared = std::move(message);
  for (const auto& s : targets)
    s->deliver(shared);
}

void StreamHub::status(double t_s, const std::string& kind, const std::string& level,
                       const std::string& message, const std::string& vehicle_id) {
  std::uint64_t suppressed = 0;
  {
    std::lock_guard lock(mutex_);
    StatusGate& g = status_gates_[vehicle_id + '/' + kind];
    const auto now = std::chrono::steady_clock::now();
    if (g.last.time_since_epoch().count() != 0 && now - g.last < status_min_interval) {
      ++g.suppressed;
      return;
    }
    g.last = now;
    suppressed = g.suppressed;
    g.suppressed = 0;
  }
  publish("status", t_s, stream_status_json(kind, level, message, suppressed, vehicle_id).dump());
}

void StreamHub::status(double t_s, mission::EventKind kind, const std::string& message,
                       const std::string& vehicle_id) {
  status(t_s, std::string(mission::to_string(kind)),
         std::string(mission::to_string(mission::severity(kind))), message, vehicle_id);
}

std::size_t StreamHub::subscriber_count(const std::string& topic) const {
  std::lock_guard lock(mutex_);
  const auto it = subscribers_.find(topic);
  if (it == subscribers_.end()) return 0;
  return static_cast<std::size_t>(std::count_if(it->second.begin(), it->second.end(),
                                                [](const auto& w) { return !w.expired(); }));
}

std::uint64_t StreamHub::published(const std::string& topic) const {
  std::lock_guard lock(mutex_);
  const auto it = seq_.find(topic);
  return it == seq_.end() ? 0 : it->second;
}

}  // namespace avk::server
