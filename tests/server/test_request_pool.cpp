// The request workers alone, without sockets: cheap work first, expensive work on a limited
// number of workers and per client address, the bounded queue, and a close that cancels what
// waits. Work is held by gates the test opens, and every wait is for a state with a deadline.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "server/http/request_pool.hpp"

namespace {

using avk::server::RequestPool;
using avk::server::RequestPoolLimits;
using Submitted = RequestPool::Submitted;
using namespace std::chrono_literals;

template <class Predicate>
bool wait_for(Predicate done, std::chrono::milliseconds limit = 20000ms) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(1ms);
  }
  return true;
}

// Work that says when it runs and then waits until the test opens the gate.
class Gate {
 public:
  RequestPool::Work work(std::atomic<int>* cancelled = nullptr) {
    return [this, cancelled](bool run) {
      if (!run) {
        if (cancelled) ++*cancelled;
        return;
      }
      ++running;
      std::unique_lock lock(mutex_);
      opened_.wait(lock, [&] { return open_; });
      --running;
      ++done;
    };
  }
  void open() {
    {
      std::lock_guard lock(mutex_);
      open_ = true;
    }
    opened_.notify_all();
  }
  std::atomic<int> running{0};
  std::atomic<int> done{0};

 private:
  std::mutex mutex_;
  std::condition_variable opened_;
  bool open_ = false;
};

TEST(RequestPool, ExpensiveWorkLeavesAWorkerForCheapWork) {
  RequestPool pool(RequestPoolLimits{3, 16, 2, 8});
  pool.start();
  Gate heavy;
  for (int i = 0; i < 3; ++i)
    ASSERT_EQ(pool.submit(true, "a", heavy.work()), Submitted::queued);
  ASSERT_TRUE(wait_for([&] { return heavy.running.load() == 2; }));
  // The third expensive one waits although a worker is free; cheap work takes that worker.
  EXPECT_EQ(pool.waiting(), 1u);
  std::atomic<int> cheap{0};
  for (int i = 0; i < 5; ++i)
    ASSERT_EQ(pool.submit(false, "a", [&](bool run) { cheap += run ? 1 : 0; }), Submitted::queued);
  EXPECT_TRUE(wait_for([&] { return cheap.load() == 5; }));
  EXPECT_EQ(heavy.running.load(), 2);
  heavy.open();
  EXPECT_TRUE(wait_for([&] { return heavy.done.load() == 3; }));
  pool.stop();
}

TEST(RequestPool, AFullQueueRefusesAndAnAddressHasItsShareOfExpensiveWork) {
  RequestPool pool(RequestPoolLimits{1, 2, 1, 2});
  pool.start();
  Gate gate;
  ASSERT_EQ(pool.submit(true, "a", gate.work()), Submitted::queued);
  ASSERT_TRUE(wait_for([&] { return gate.running.load() == 1; }));
  ASSERT_EQ(pool.submit(true, "a", gate.work()), Submitted::queued);  // waits
  // Address a has two expensive requests running or waiting: a third is refused, whatever room.
  EXPECT_EQ(pool.submit(true, "a", gate.work()), Submitted::address_busy);
  EXPECT_EQ(pool.submit(true, "b", gate.work()), Submitted::queued);
  // Two waiting: the queue is full for everyone, cheap work too.
  EXPECT_EQ(pool.waiting(), 2u);
  EXPECT_EQ(pool.submit(false, "c", gate.work()), Submitted::queue_full);
  gate.open();
  EXPECT_TRUE(wait_for([&] { return gate.done.load() == 3; }));
  // Finished work gives its address its share back.
  Gate again;
  EXPECT_EQ(pool.submit(true, "a", again.work()), Submitted::queued);
  EXPECT_EQ(pool.submit(true, "a", again.work()), Submitted::queued);
  again.open();
  EXPECT_TRUE(wait_for([&] { return again.done.load() == 2; }));
  pool.stop();
}

TEST(RequestPool, CloseCancelsWhatWaitsAndTakesNothingMore) {
  RequestPool pool(RequestPoolLimits{1, 8, 1, 8});
  pool.start();
  Gate gate;
  std::atomic<int> cancelled{0};
  ASSERT_EQ(pool.submit(false, "a", gate.work(&cancelled)), Submitted::queued);
  ASSERT_TRUE(wait_for([&] { return gate.running.load() == 1; }));
  ASSERT_EQ(pool.submit(false, "a", gate.work(&cancelled)), Submitted::queued);
  ASSERT_EQ(pool.submit(true, "a", gate.work(&cancelled)), Submitted::queued);
  pool.close();
  EXPECT_EQ(cancelled.load(), 2);
  EXPECT_EQ(pool.waiting(), 0u);
  EXPECT_EQ(pool.submit(false, "a", gate.work()), Submitted::closed);
  // The running one finishes; stop waits for it.
  std::thread stopper([&] { pool.stop(); });
  gate.open();
  stopper.join();
  EXPECT_EQ(gate.done.load(), 1);
}

TEST(RequestPool, WorkThatThrowsLeavesTheWorkerRunning) {
  RequestPool pool(RequestPoolLimits{1, 8, 1, 8});
  pool.start();
  ASSERT_EQ(pool.submit(true, "a", [](bool) { throw std::runtime_error("boom"); }),
            Submitted::queued);
  std::atomic<bool> ran{false};
  ASSERT_EQ(pool.submit(true, "a", [&](bool run) { ran = run; }), Submitted::queued);
  EXPECT_TRUE(wait_for([&] { return ran.load(); }));
  pool.stop();
}

// Expensive work must not take the CPU from the I/O threads and the vehicle loop: it runs at a
// lower priority than the thread that made the pool; cheap work on the others does not.
TEST(RequestPool, ExpensiveWorkRunsBelowTheRestOfTheProcess) {
  errno = 0;
  const int own = ::getpriority(PRIO_PROCESS, static_cast<id_t>(::gettid()));
  ASSERT_EQ(errno, 0);
  if (own >= 19) GTEST_SKIP() << "this process runs at the lowest priority already";
  RequestPool pool(RequestPoolLimits{2, 8, 1, 8});
  pool.start();
  std::atomic<int> expensive{-100};
  Gate gate;  // holds the worker for expensive work, so the cheap one runs on the other
  auto hold = gate.work();
  ASSERT_EQ(pool.submit(true, "a",
                        [&](bool run) {
                          expensive = ::getpriority(PRIO_PROCESS, static_cast<id_t>(::gettid()));
                          hold(run);
                        }),
            Submitted::queued);
  ASSERT_TRUE(wait_for([&] { return gate.running.load() == 1; }));
  std::atomic<int> cheap{-100};
  ASSERT_EQ(pool.submit(
                false, "a",
                [&](bool) { cheap = ::getpriority(PRIO_PROCESS, static_cast<id_t>(::gettid())); }),
            Submitted::queued);
  ASSERT_TRUE(wait_for([&] { return cheap.load() != -100; }));
  EXPECT_GT(expensive.load(), own);
  EXPECT_EQ(cheap.load(), own);
  gate.open();
  pool.stop();
}

}  // namespace
