#include "server/foxglove_hub.hpp"

#include <nlohmann/json.hpp>
#include <utility>

namespace avk::server {

using nlohmann::json;

namespace {

json channel_json(std::uint32_t id, const app::foxglove::ChannelSpec& s) {
  return {{"id", id},
          {"topic", s.topic},
          {"encoding", app::foxglove::kMessageEncoding},
          {"schemaName", s.schema_name},
          {"schema", std::string(s.schema)},
          {"schemaEncoding", app::foxglove::kSchemaEncoding}};
}

std::shared_ptr<const std::string> shared_text(const json& j) {
  return std::make_shared<const std::string>(
      j.dump(-1, ' ', false, json::error_handler_t::replace));
}

// The protocol's status levels: 0 info, 1 warning, 2 error.
int status_level(app::foxglove::LogLevel l) {
  switch (l) {
    case app::foxglove::LogLevel::info:
      return 0;
    case app::foxglove::LogLevel::warning:
      return 1;
    case app::foxglove::LogLevel::error:
      return 2;
  }
  return 0;
}

}  // namespace

FoxgloveHub::FoxgloveHub(std::string session_id) : session_id_(std::move(session_id)) {}

std::string FoxgloveHub::server_info(const std::string& server_version) const {
  return json{{"op", "serverInfo"},
              {"name", server_version},
              {"capabilities", json::array({"time"})},
              {"metadata", {{"grid_frame", app::foxglove::kGridFrame}}},
              {"sessionId", session_id_}}
      .dump();
}

std::string FoxgloveHub::join(const std::shared_ptr<FoxgloveClient>& client) {
  std::lock_guard lock(mutex_);
  clients_[client.get()] = client;
  json channels = json::array();
  for (const auto& [id, c] : channels_)
    if (c.advertised) channels.push_back(channel_json(id, c.spec));
  return json{{"op", "advertise"}, {"channels", std::move(channels)}}.dump(
      -1, ' ', false, json::error_handler_t::replace);
}

void FoxgloveHub::leave(const FoxgloveClient* client) {
  std::lock_guard lock(mutex_);
  clients_.erase(client);
  for (auto& [id, c] : channels_)
    c.subscribers.erase(client);
}

FoxgloveHub::SubscribeOutcome FoxgloveHub::subscribe(
    const FoxgloveClient* client, std::uint32_t channel_id,
    std::shared_ptr<const FoxgloveFrame>* latched) {
  std::lock_guard lock(mutex_);
  const auto it = channels_.find(channel_id);
  if (it == channels_.end() || !it->second.advertised) return SubscribeOutcome::unknown_channel;
  it->second.subscribers.insert(client);
  if (latched) *latched = it->second.last;
  return SubscribeOutcome::ok;
}

void FoxgloveHub::unsubscribe(const FoxgloveClient* client, std::uint32_t channel_id) {
  std::lock_guard lock(mutex_);
  if (const auto it = channels_.find(channel_id); it != channels_.end())
    it->second.subscribers.erase(client);
}

std::vector<std::shared_ptr<FoxgloveClient>> FoxgloveHub::clients_locked() const {
  std::vector<std::shared_ptr<FoxgloveClient>> out;
  for (const auto& [key, weak] : clients_)
    if (auto c = weak.lock()) out.push_back(std::move(c));
  return out;
}

std::vector<std::shared_ptr<FoxgloveClient>> FoxgloveHub::subscribers_locked(
    const Channel& c) const {
  std::vector<std::shared_ptr<FoxgloveClient>> out;
  for (const auto* key : c.subscribers)
    if (const auto it = clients_.find(key); it != clients_.end())
      if (auto client = it->second.lock()) out.push_back(std::move(client));
  return out;
}

void FoxgloveHub::advertise(const std::string& vehicle_id,
                            const std::vector<app::foxglove::ChannelSpec>& specs) {
  json channels = json::array();
  std::vector<std::shared_ptr<FoxgloveClient>> to;
  {
    std::lock_guard lock(mutex_);
    for (const auto& spec : specs) {
      // A topic keeps its id across unadvertise/advertise: the protocol allows the reuse only
      // for an identical channel, which the same topic of this station is.
      auto [pos, fresh] = ids_by_topic_.try_emplace(spec.topic, next_id_);
      if (fresh) ++next_id_;
      Channel& c = channels_[pos->second];
      if (c.advertised) continue;
      c.spec = spec;
      c.vehicle_id = vehicle_id;
      c.advertised = true;
      channels.push_back(channel_json(pos->second, spec));
    }
    to = clients_locked();
  }
  if (channels.empty()) return;
  const auto text = shared_text(json{{"op", "advertise"}, {"channels", std::move(channels)}});
  for (const auto& c : to)
    c->send_text(text);
}

void FoxgloveHub::unadvertise(const std::string& vehicle_id) {
  std::vector<std::uint32_t> ids;
  std::vector<std::shared_ptr<FoxgloveClient>> to;
  {
    std::lock_guard lock(mutex_);
    for (auto& [id, c] : channels_) {
      if (!c.advertised || c.vehicle_id != vehicle_id) continue;
      c.advertised = false;
      c.subscribers.clear();
      c.last.reset();
      ids.push_back(id);
    }
    to = clients_locked();
  }
  if (ids.empty()) return;
  const auto text = shared_text(json{{"op", "unadvertise"}, {"channelIds", ids}});
  for (const auto& c : to)
    c->channels_removed(ids, text);
}

bool FoxgloveHub::wanted(const std::string& topic) const {
  std::lock_guard lock(mutex_);
  const auto id = ids_by_topic_.find(topic);
  if (id == ids_by_topic_.end()) return false;
  const auto& c = channels_.at(id->second);
  return c.advertised && !c.subscribers.empty();
}

void FoxgloveHub::publish(const std::string& topic, std::uint64_t t_ns, std::string payload) {
  std::vector<std::shared_ptr<FoxgloveClient>> to;
  std::shared_ptr<const FoxgloveFrame> frame;
  {
    std::lock_guard lock(mutex_);
    const auto id = ids_by_topic_.find(topic);
    if (id == ids_by_topic_.end()) return;
    Channel& c = channels_.at(id->second);
    if (!c.advertised || (c.subscribers.empty() && !c.spec.latched)) return;
    auto f = std::make_shared<FoxgloveFrame>();
    f->channel_id = id->second;
    f->t_ns = t_ns;
    f->latest_value_wins = c.spec.latest_value_wins;
    f->payload = std::make_shared<const std::string>(std::move(payload));
    frame = std::move(f);
    if (c.spec.latched) c.last = frame;
    to = subscribers_locked(c);
    ++published_;
  }
  for (const auto& c : to)
    c->deliver(frame);
}

void FoxgloveHub::status(app::foxglove::LogLevel level, const std::string& message) {
  std::vector<std::shared_ptr<FoxgloveClient>> to;
  {
    std::lock_guard lock(mutex_);
    to = clients_locked();
  }
  if (to.empty()) return;
  const auto text =
      shared_text(json{{"op", "status"}, {"level", status_level(level)}, {"message", message}});
  for (const auto& c : to)
    c->send_text(text);
}

void FoxgloveHub::time(std::uint64_t t_ns) {
  std::vector<std::shared_ptr<FoxgloveClient>> to;
  {
    std::lock_guard lock(mutex_);
    to = clients_locked();
  }
  for (const auto& c : to)
    c->send_time(t_ns);
}

std::size_t FoxgloveHub::client_count() const {
  std::lock_guard lock(mutex_);
  return clients_.size();
}

std::size_t FoxgloveHub::subscriber_count(const std::string& topic) const {
  std::lock_guard lock(mutex_);
  const auto id = ids_by_topic_.find(topic);
  return id == ids_by_topic_.end() ? 0 : channels_.at(id->second).subscribers.size();
}

std::uint64_t FoxgloveHub::published() const {
  std::lock_guard lock(mutex_);
  return published_;
}

}  // namespace avk::server
