#pragma once
// The threads that run the API's request work, so that the I/O threads only read, write and
// route: a slow answer (a model fit, hundreds of maneuver candidates, an export) never holds up
// /health, the live stream or the Foxglove connection. Work waits in one bounded queue.
// `expensive_running` of the workers take expensive work (first; cheap work when none waits) and
// run at a lower priority; the others take cheap work only, so cheap requests (a command, a page
// of turns) find a worker while heavy ones run. Each client address may have at most
// `expensive_per_address` expensive requests running or waiting. Plain threads: nothing here
// knows about sockets.

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace avk::server {

struct RequestPoolLimits {
  std::size_t workers = 4;
  std::size_t queue = 64;  // waiting requests, cheap and expensive together
  std::size_t expensive_running = 2;
  std::size_t expensive_per_address = 4;  // running or waiting
  // How far below the rest of the process expensive work runs (Linux nice, per thread): when
  // it fills the cores, the I/O threads (/health, the stream, Foxglove), cheap requests and the
  // vehicle loop still get theirs at once.
  int nice = 10;
};

class RequestPool {
 public:
  // work(true) runs the request on a worker; work(false) is the request cancelled before it ran
  // (the server stops), called on the thread that called close().
  using Work = std::function<void(bool run)>;
  enum class Submitted { queued, queue_full, address_busy, closed };

  explicit RequestPool(RequestPoolLimits limits);
  ~RequestPool();  // stop()
  RequestPool(const RequestPool&) = delete;
  RequestPool& operator=(const RequestPool&) = delete;

  void start();
  // Queues the work unless the queue is full, the address has its expensive requests already, or
  // the pool is closed; the work is not called then.
  Submitted submit(bool expensive, const std::string& address, Work work);
  // Takes no more work and cancels what waits. Idempotent.
  void close();
  // close(), then waits for the work running now and joins the workers. Idempotent.
  void stop();

  std::size_t waiting() const;
  const RequestPoolLimits& limits() const { return limits_; }

 private:
  struct Item {
    Work work;
    std::string address;  // expensive work only: whose count it holds
  };
  void run_worker(bool expensive_worker);
  bool can_take(bool expensive_worker) const;  // under mutex_

  RequestPoolLimits limits_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<Item> cheap_;
  std::deque<Item> expensive_;
  std::map<std::string, std::size_t> per_address_;  // expensive, running or waiting
  bool closed_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace avk::server
