#include "server/http/request_pool.hpp"

#include <algorithm>
#include <exception>
#include <iostream>
#include <utility>

namespace avk::server {

RequestPool::RequestPool(RequestPoolLimits limits) : limits_(limits) {
  limits_.workers = std::max<std::size_t>(1, limits_.workers);
  limits_.expensive_running =
      std::clamp<std::size_t>(limits_.expensive_running, 1, limits_.workers);
  limits_.expensive_per_address = std::max<std::size_t>(1, limits_.expensive_per_address);
}

RequestPool::~RequestPool() {
  stop();
}

void RequestPool::start() {
  std::lock_guard lock(mutex_);
  if (!workers_.empty() || closed_) return;
  workers_.reserve(limits_.workers);
  for (std::size_t i = 0; i < limits_.workers; ++i)
    workers_.emplace_back([this] { run_worker(); });
}

RequestPool::Submitted RequestPool::submit(bool expensive, const std::string& address, Work work) {
  {
    std::lock_guard lock(mutex_);
    if (closed_) return Submitted::closed;
    if (cheap_.size() + expensive_.size() >= limits_.queue) return Submitted::queue_full;
    if (expensive) {
      auto& n = per_address_[address];
      if (n >= limits_.expensive_per_address) return Submitted::address_busy;
      ++n;
      expensive_.push_back({std::move(work), address});
    } else {
      cheap_.push_back({std::move(work), {}});
    }
  }
  // Every worker may be waiting for a kind of work that did not come: each looks again.
  ready_.notify_all();
  return Submitted::queued;
}

bool RequestPool::can_take() const {
  return !cheap_.empty() || (!expensive_.empty() && expensive_now_ < limits_.expensive_running);
}

void RequestPool::run_worker() {
  for (;;) {
    Item item;
    bool expensive = false;
    {
      std::unique_lock lock(mutex_);
      ready_.wait(lock, [&] { return closed_ || can_take(); });
      // close() has cancelled whatever waited: the pool is done.
      if (!can_take()) return;
      expensive = cheap_.empty();
      auto& from = expensive ? expensive_ : cheap_;
      item = std::move(from.front());
      from.pop_front();
      if (expensive) ++expensive_now_;
    }
    try {
      item.work(true);
    } catch (const std::exception& e) {
      // The work answers its own errors; this only keeps the worker alive if one slipped out.
      std::cerr << "avk http: unexpected exception in a request worker: " << e.what() << "\n";
    } catch (...) {
      std::cerr << "avk http: unexpected exception in a request worker\n";
    }
    if (!expensive) continue;
    {
      std::lock_guard lock(mutex_);
      --expensive_now_;
      if (const auto it = per_address_.find(item.address);
          it != per_address_.end() && --it->second == 0)
        per_address_.erase(it);
    }
    // A slot for expensive work is free: a worker that could not take any may now.
    ready_.notify_all();
  }
}

void RequestPool::close() {
  std::deque<Item> cancelled;
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
    cancelled.swap(cheap_);
    for (auto& item : expensive_) {
      if (const auto it = per_address_.find(item.address);
          it != per_address_.end() && --it->second == 0)
        per_address_.erase(it);
      cancelled.push_back(std::move(item));
    }
    expensive_.clear();
  }
  ready_.notify_all();
  for (auto& item : cancelled) {
    try {
      item.work(false);
    } catch (...) {
      // A request that cannot even be told it was cancelled is dropped with its connection.
    }
  }
}

void RequestPool::stop() {
  close();
  std::vector<std::thread> workers;
  {
    std::lock_guard lock(mutex_);
    workers.swap(workers_);
  }
  for (auto& t : workers)
    t.join();
}

std::size_t RequestPool::waiting() const {
  std::lock_guard lock(mutex_);
  return cheap_.size() + expensive_.size();
}

}  // namespace avk::server
