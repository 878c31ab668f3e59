// A mission held by a process (running or paused) whose process is gone reads, and is closed, as
// interrupted at the start of the next station; one whose process lives, or that has ended, is
// left as it is.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>

#include "app/mission_liveness.hpp"
#include "store/store.hpp"

namespace {

using namespace avk;
using store::MissionStatus;

// The pid of a process that has exited and been reaped: no process has it (until the kernel
// hands it out again, which takes a full cycle of pids).
std::int64_t a_dead_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

std::int64_t mission_held(store::Store& db, MissionStatus status, std::int64_t pid) {
  const auto id = db.missions().create("usim-1", "collection", R"({"speeds":[1.0]})");
  db.missions().set_status(id, MissionStatus::running, "", 1.0);
  if (status != MissionStatus::running) db.missions().set_status(id, status, "operator", 2.0);
  db.missions().set_runner(id, pid);
  return id;
}

TEST(MissionLiveness, RunningOrPausedWithoutTheirProcessAreInterrupted) {
  store::Store db(":memory:");
  db.vehicles().upsert({"usim-1", "usim", 2.0, 1.2});
  const std::int64_t dead = a_dead_pid();
  const std::int64_t alive = ::getpid();
  const auto running_dead = mission_held(db, MissionStatus::running, dead);
  const auto paused_dead = mission_held(db, MissionStatus::paused, dead);
  const auto running_alive = mission_held(db, MissionStatus::running, alive);
  const auto paused_alive = mission_held(db, MissionStatus::paused, alive);
  const auto done = mission_held(db, MissionStatus::done, dead);

  EXPECT_EQ(app::effective_status(*db.missions().get(paused_dead)), MissionStatus::interrupted);
  EXPECT_EQ(app::effective_status(*db.missions().get(paused_alive)), MissionStatus::paused);
  EXPECT_EQ(app::mark_orphaned_missions_interrupted(db), 2);
  for (const auto id : {running_dead, paused_dead}) {
    const auto m = db.missions().get(id);
    EXPECT_EQ(m->status, MissionStatus::interrupted) << id;
    EXPECT_FALSE(m->runner_pid) << id;
    // Nothing recorded: it ended where it started.
    ASSERT_TRUE(m->ended_s) << id;
    EXPECT_EQ(*m->ended_s, 1.0) << id;
  }
  EXPECT_EQ(db.missions().get(running_alive)->status, MissionStatus::running);
  EXPECT_EQ(db.missions().get(paused_alive)->status, MissionStatus::paused);
  EXPECT_EQ(db.missions().get(done)->status, MissionStatus::done);
  // Closed once: a second start finds nothing more to close.
  EXPECT_EQ(app::mark_orphaned_missions_interrupted(db), 0);
}

}  // namespace
