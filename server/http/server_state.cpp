#include "server/http/server_state.hpp"

#include <string_view>
#include <utility>
#include <vector>

#include "server/http/http_session.hpp"
#include "server/http/live_session.hpp"

namespace avk::server {

ServerState::ServerState(HttpServerOptions options, Api& api, StreamSource& hub)
    : options_(std::move(options)),
      api_(api),
      hub_(hub),
      static_files_(options_.web_root),
      pool_({options_.request_workers, options_.request_queue, options_.expensive_requests,
             options_.expensive_requests_per_address}) {}

void ServerState::add(const std::shared_ptr<HttpSession>& session) {
  std::lock_guard lock(mutex_);
  http_sessions_[session.get()] = HttpEntry{session, session->remote_address(), ++accepted_};
}

bool ServerState::make_room() {
  std::shared_ptr<HttpSession> victim;
  {
    std::lock_guard lock(mutex_);
    std::map<std::string_view, std::size_t> by_address;
    std::size_t total = stream_sessions_.size();
    for (const auto& [key, entry] : http_sessions_) {
      if (entry.evicted) continue;
      ++total;
      ++by_address[entry.address];
    }
    if (total < options_.max_connections) return true;
    HttpEntry* chosen = nullptr;
    std::size_t chosen_count = 0;
    for (auto& [key, entry] : http_sessions_) {
      if (entry.evicted) continue;
      const std::size_t count = by_address[entry.address];
      if (chosen &&
          (count < chosen_count || (count == chosen_count && entry.order > chosen->order)))
        continue;
      const auto s = entry.session.lock();
      if (!s || !s->evictable()) continue;
      chosen = &entry;
      chosen_count = count;
    }
    if (!chosen) return false;
    chosen->evicted = true;
    victim = chosen->session.lock();
  }
  if (victim) victim->evict();
  return true;
}

bool ServerState::establish(const HttpSession* session) {
  std::shared_ptr<HttpSession> victim;
  {
    std::lock_guard lock(mutex_);
    const auto self = http_sessions_.find(session);
    if (self == http_sessions_.end() || self->second.established) return true;
    const std::string& address = self->second.address;
    std::size_t established = 0;
    HttpEntry* oldest = nullptr;
    for (auto& [key, entry] : http_sessions_) {
      if (entry.evicted || !entry.established || entry.address != address) continue;
      ++established;
      if (oldest && entry.order > oldest->order) continue;
      const auto s = entry.session.lock();
      if (s && s->evictable()) oldest = &entry;
    }
    if (established >= options_.max_connections_per_address) {
      if (!oldest) return false;
      oldest->evicted = true;
      victim = oldest->session.lock();
    }
    self->second.established = true;
  }
  if (victim) victim->evict();
  return true;
}

void ServerState::remove(const HttpSession* session) {
  std::lock_guard lock(mutex_);
  http_sessions_.erase(session);
  if (http_sessions_.empty() && stream_sessions_.empty()) idle_.notify_all();
}

bool ServerState::reserve_stream(const std::string& address) {
  std::lock_guard lock(mutex_);
  auto& n = streams_by_address_[address];
  if (n >= options_.max_streams_per_address) return false;
  ++n;
  return true;
}

void ServerState::add(const std::shared_ptr<LiveSession>& session,
                      const std::shared_ptr<DetachableSink>& sink, const std::string& address) {
  std::lock_guard lock(mutex_);
  stream_sessions_[session.get()] = StreamEntry{session, sink, address};
}

void ServerState::remove(const LiveSession* session) {
  std::lock_guard lock(mutex_);
  if (const auto it = stream_sessions_.find(session); it != stream_sessions_.end()) {
    if (const auto n = streams_by_address_.find(it->second.address);
        n != streams_by_address_.end() && --n->second == 0)
      streams_by_address_.erase(n);
    stream_sessions_.erase(it);
  }
  if (http_sessions_.empty() && stream_sessions_.empty()) idle_.notify_all();
}

void ServerState::begin_stop() {
  std::vector<std::shared_ptr<HttpSession>> http;
  std::vector<std::shared_ptr<LiveSession>> streams;
  {
    // Under the lock so that a session added later sees the flag when it starts.
    std::lock_guard lock(mutex_);
    stopping_ = true;
    for (const auto& [key, weak] : http_sessions_)
      if (auto s = weak.session.lock()) http.push_back(std::move(s));
    for (const auto& [key, entry] : stream_sessions_)
      if (auto s = entry.session.lock()) streams.push_back(std::move(s));
  }
  pool_.close();
  for (const auto& s : http)
    s->shutdown();
  for (const auto& s : streams)
    s->shutdown();
}

bool ServerState::wait_until_idle(std::chrono::steady_clock::time_point deadline) {
  std::unique_lock lock(mutex_);
  return idle_.wait_until(lock, deadline,
                          [&] { return http_sessions_.empty() && stream_sessions_.empty(); });
}

void ServerState::detach_sinks() {
  std::vector<std::shared_ptr<DetachableSink>> sinks;
  {
    // Detached outside the lock: a delivery in progress holds the sink's lock and may end by
    // destroying its session, which takes this one.
    std::lock_guard lock(mutex_);
    for (const auto& [key, entry] : stream_sessions_)
      sinks.push_back(entry.sink);
  }
  for (const auto& s : sinks)
    s->detach();
}

}  // namespace avk::server
