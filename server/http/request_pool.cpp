#include "server/http/request_pool.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
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
    workers_.emplace_back(
        [this, expensive = i < limits_.expensive_running] { run_worker(expensive); });
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
  // Any worker takes cheap work: one is enough. Only some take expensive work: wake them all.
  if (expensive)
    ready_.notify_all();
  else
    ready_.notify_one();
  return Submitted::queued;
}

bool RequestPool::can_take(bool expensive_worker) const {
  return !cheap_.empty() || (expensive_worker && !expensive_.empty());
}

void RequestPool::run_worker(bool expensive_worker) {
  if (expensive_worker && limits_.nice > 0) {
    // Best effort, once (lowering one's own priority needs no privilege; raising it back would):
    // where it cannot be changed, expensive work runs at the process's priority.
    const auto self = static_cast<id_t>(::gettid());
    errno = 0;
    const int own = ::getpriority(PRIO_PROCESS, self);
    if (errno == 0) (void)::setpriority(PRIO_PROCESS, self, std::min(19, own + limits_.nice));
  }
  for (;;) {
    Item item;
    bool expensive = false;
    {
      std::unique_lock lock(mutex_);
      ready_.wait(lock, [&] { return closed_ || can_take(expensive_worker); });
      // close() has cancelled whatever waited: the pool is done.
      if (!can_take(expensive_worker)) return;
      // A worker for expensive work takes it first, so that cheap work cannot starve it; the
      // other workers are there for cheap work.
      expensive = expensive_worker && !expensive_.empty();
      auto& from = expensive ? expensive_ : cheap_;
      item = std::move(from.front());
      from.pop_front();
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
    std::lock_guard lock(mutex_);
    if (const auto it = per_address_.find(item.address);
        it != per_address_.end() && --it->second == 0)
      per_address_.erase(it);
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
