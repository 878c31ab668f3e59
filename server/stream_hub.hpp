#pragma once
// Fan-out of the live stream: the mission thread publishes, each subscribed session gets the same
// shared payload. Topics: nav, helm, mission, turn, status. Sequence numbers are per topic so a
// client sees gaps. Status messages (what an operator must read) are rate-limited per kind.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "mission/event_kind.hpp"
#include "server/api_types.hpp"
#include "server/foxglove_hub.hpp"
#include "server/http/live_sources.hpp"

namespace avk::server {

class StreamHub final : public StreamSource {
 public:
  StreamHub();

  static const std::vector<std::string>& topics();
  static bool is_topic(const std::string& topic);
  const std::vector<std::string>& topic_names() const override { return topics(); }
  bool has_topic(const std::string& topic) const override { return is_topic(topic); }

  // A random id per server start: a client that sees a new one knows the server restarted.
  const std::string& session_id() const { return session_id_; }
  // The hello a new connection receives; it carries vocabulary_json() for the dashboard.
  std::string hello(const std::string& server_version) const override;

  // The hub keeps weak references: a closed session simply stops receiving.
  void subscribe(const std::shared_ptr<StreamSink>& sink, const std::string& topic) override;
  void unsubscribe(const StreamSink* sink, const std::string& topic) override;
  void unsubscribe_all(const StreamSink* sink) override;

  // data_json is the "data" member, already serialised. t_s is the mission (or wall) clock.
  // vehicle_id: the vehicle the message is about, so that latest-value-wins telemetry of one
  // vehicle never replaces another's.
  void publish(const std::string& topic, double t_s, const std::string& data_json,
               const std::string& vehicle_id = {});
  // Status: at most one message per vehicle and kind per min_interval (one vehicle's burst does
  // not hide another's); suppressed ones are counted into the next message that goes out.
  // vehicle_id: the vehicle the event is about; empty for the station as a whole.
  void status(double t_s, const std::string& kind, const std::string& level,
              const std::string& message, const std::string& vehicle_id = {});
  // The level is the kind's severity.
  void status(double t_s, mission::EventKind kind, const std::string& message,
              const std::string& vehicle_id = {});

  std::size_t subscriber_count(const std::string& topic) const;
  std::uint64_t published(const std::string& topic) const;

  std::chrono::milliseconds status_min_interval{1000};

  // The same live data for clients of the Foxglove WebSocket protocol (docs/foxglove.md).
  FoxgloveHub& foxglove() { return foxglove_; }
  FoxgloveSource& foxglove_source() override { return foxglove_; }

 private:
  std::string session_id_;
  FoxgloveHub foxglove_{session_id_};
  mutable std::mutex mutex_;
  std::map<std::string, std::vector<std::weak_ptr<StreamSink>>> subscribers_;
  std::map<std::string, std::uint64_t> seq_;
  struct StatusGate {
    std::chrono::steady_clock::time_point last{};
    std::uint64_t suppressed = 0;
  };
  std::map<std::string, StatusGate> status_gates_;
};

}  // namespace avk::server
