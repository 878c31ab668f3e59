#include "app/vehicle_loop.hpp"

#include <unistd.h>

#include <condition_variable>
#include <map>

#include "app/mission_recorder.hpp"
#include "app/station_identity.hpp"
#include "app/store_access.hpp"
#include "kinematics/number_text.hpp"
#include "mission/command_helm.hpp"
#include "sim/scheduler.hpp"
#include "store/store.hpp"

namespace avk::app {

struct VehicleLoop::Impl {
  VehicleLoopOptions options;
  std::string db_path;
  LiveFeed& feed;
  sim::Scheduler scheduler;
  std::unique_ptr<VehicleSource> source;
  std::thread thread;
  std::atomic<bool> stop_requested{false};
  std::string stop_reason;

  mutable std::mutex mutex;
  std::condition_variable ticked;
  std::uint64_t ticks = 0;
  std::deque<std::function<void(double)>> pending;
  std::optional<std::int64_t> attached;  // set when a mission is accepted, before it runs
  bool present = false;  // reporting navigation over a link (announced when it changes)
  std::optional<kinematics::Point> return_point;  // the last mission's
  VehicleSnapshot snapshot;
  std::map<std::int64_t, MissionLive> live;

  // Loop thread only.
  std::unique_ptr<store::Store> store;
  // The helm while no mission runs: the operator's commands, the hold after a mission's end.
  std::unique_ptr<mission::CommandHelm> helm;
  struct Running {
    std::int64_t id;
    mission::MissionConfig config;
    std::unique_ptr<mission::MissionRunner> runner;
    std::unique_ptr<MissionRecorder> recorder;
    std::unique_ptr<mission::MissionObserver> follower;
  };
  std::optional<Running> running;
  bool idle_stopped = false;

  // Publishes the runner's mode and state to live() and the snapshot's helm fields the moment
  // they change, inside the runner's own call. It is the runner's first observer, so a reader
  // that sees a status in the store (written by the recorder after it) sees the helm that goes
  // with it: a mission is never `paused` while the vehicle still shows CONDITIONING.
  struct HelmSync final : mission::MissionObserver {
    explicit HelmSync(Impl& i) : impl(i) {}
    void on_mode(mission::HelmMode, mission::HelmMode, double) override { impl.update_live(); }
    void on_state(mission::MissionState, const std::string&, double) override {
      impl.update_live();
    }
    Impl& impl;
  };
  HelmSync helm_sync{*this};

  Impl(VehicleLoopOptions o, std::string path, LiveFeed& f)
      : options(std::move(o)),
        db_path(std::move(path)),
        feed(f),
        scheduler(scheduler_options(options)) {
    options.realtime = true;  // the station's vehicle lives on the wall clock
    source = make_vehicle_source(options, scheduler);
    helm = std::make_unique<mission::CommandHelm>(source->vehicle());
  }

  vehicle::Vehicle& vehicle() { return source->vehicle(); }

  void helm_tick(double now) {
    std::deque<std::function<void(double)>> todo;
    {
      std::lock_guard lock(mutex);
      todo.swap(pending);
    }
    for (auto& f : todo)
      f(now);
    if (stop_requested.load()) {
      if (running) {
        running->runner->interrupt(now, stop_reason);
        finish_running(now);
      }
      scheduler.request_stop();
    } else if (running) {
      running->runner->tick(now);
      update_live();
      if (running->runner->finished()) finish_running(now);
    } else if (helm->mode()) {
      helm->tick(now);
      if (helm->take_arrival())
        feed.station_event(now, mission::EventKind::arrived, arrival_text());
      update_command();
    } else {
      vehicle().take_nav();  // no mission: nothing records it, but the mailbox must not grow
      if (!idle_stopped) vehicle().all_stop(now);
      idle_stopped = true;
    }
    {
      std::lock_guard lock(mutex);
      ++ticks;
    }
    ticked.notify_all();
  }

  void start_running(MissionPlan plan, double now) {
    mission::RunnerOptions ro;
    ro.vehicle_id = vehicle().info().id;
    ro.mission_label = std::to_string(plan.mission_id);
    Running r;
    r.id = plan.mission_id;
    r.config = plan.config;
    helm->mission_started(plan.config);
    helm->clear();  // the mission drives the vehicle now
    r.runner = std::make_unique<mission::MissionRunner>(plan.config, vehicle(), plan.tasks, ro);
    r.runner->add_observer(helm_sync);  // first: see HelmSync
    r.recorder = std::make_unique<MissionRecorder>(
        *store, plan.mission_id, 1.0,
        [this, vid = vehicle().info().id](const CurrentView& c) { feed.current(vid, c); });
    r.follower = feed.follow(plan.mission_id, *r.runner);
    r.runner->add_observer(*r.recorder);
    r.runner->add_observer(*r.follower);
    r.recorder->set_runner(static_cast<std::int64_t>(::getpid()));
    idle_stopped = false;
    running = std::move(r);
    {
      std::lock_guard lock(mutex);
      return_point = running->config.region.return_point;
      snapshot.command.reset();
    }
    feed.station_event(now, mission::EventKind::mission_attached,
                       "mission " + std::to_string(plan.mission_id) + " started with " +
                           std::to_string(plan.tasks.size()) + " turns to do");
  }

  void finish_running(double now) {
    running->recorder->flush();
    running->recorder->set_runner(std::nullopt);
    running->recorder->replay_spool();
    update_live();
    feed.station_event(
        now, mission::EventKind::mission_detached,
        "mission " + std::to_string(running->id) + " " +
            (running->runner->state() ? mission::to_string(*running->runner->state()) : "ended"));
    const std::optional<mission::MissionState> state = running->runner->state();
    if (state && helm->mission_ended(running->config, *state, now))
      feed.station_event(now, mission::EventKind::vehicle_command,
                         "mission " + std::to_string(running->id) + " " +
                             mission::to_string(*state) + ": " +
                             mission::describe(*helm->active()));
    running.reset();
    update_command();
    std::lock_guard lock(mutex);
    attached.reset();
  }

  // The operator's command, on the loop's thread: an attached mission is aborted first.
  void apply_command(mission::VehicleCommand c, double now) {
    if (running) {
      running->runner->abort(now, "aborted by the operator's command: " + mission::describe(c));
      update_live();
      finish_running(now);
    }
    helm->command(c, now);
    feed.station_event(now, mission::EventKind::vehicle_command,
                       mission::describe(*helm->active()));
    update_command();
  }

  // "arrived at (12.0, -3.5), 2.1 m away: holding within 5.0 m".
  std::string arrival_text() const {
    using kinematics::fixed_text;
    const mission::VehicleCommand& c = *helm->active();
    std::string out = "arrived";
    if (c.point)
      out += " at (" + fixed_text(c.point->x_m, 1) + ", " + fixed_text(c.point->y_m, 1) + ")";
    if (const auto d = helm->distance_m()) out += ", " + fixed_text(*d, 1) + " m away";
    return out + ": holding within " + fixed_text(c.radius_m, 1) + " m";
  }

  // The helm's command in the snapshot, the moment it changes (like update_live for a mission).
  void update_command() {
    if (running) return;
    std::lock_guard lock(mutex);
    fill_command(snapshot);
  }
  void fill_command(VehicleSnapshot& s) const {
    s.helm_mode = helm->mode();
    s.desired_heading_deg = helm->desired_heading_deg();
    s.desired_speed_mps = helm->desired_speed_mps();
    s.mission_id.reset();
    s.command.reset();
    if (helm->active()) s.command = VehicleCommandState{*helm->active(), helm->distance_m()};
  }

  // The mission's live view and the vehicle's helm fields in one step (one lock), so that
  // GET /missions/{id} and GET /vehicles/{vid} never disagree about the helm.
  void update_live() {
    if (!running) return;  // observers are added before `running` is set
    const mission::MissionRunner& r = *running->runner;
    MissionLive l;
    l.mission_id = running->id;
    l.state = r.state();
    l.helm_mode = r.mode();
    l.cells = r.cells();
    l.turn = r.running_turn();
    std::lock_guard lock(mutex);
    snapshot.helm_mode = l.helm_mode;
    snapshot.desired_heading_deg = r.desired_heading_deg();
    snapshot.desired_speed_mps = r.desired_speed_mps();
    snapshot.mission_id = running->id;
    live[l.mission_id] = std::move(l);
  }

  // A vehicle joins when its navigation first arrives and leaves when its link is lost, so an
  // operator of a fleet learns of a boat that went silent without watching each one.
  void announce_presence(const VehicleSnapshot& s) {
    const bool now_present = s.link != vehicle::LinkState::disconnected && s.nav.has_value();
    if (now_present == present) return;
    present = now_present;
    const std::string& id = s.info.id;
    if (present) {
      std::string kind = s.info.kind.empty() ? "" : " (" + s.info.kind + ")";
      feed.station_event(s.t_s, mission::EventKind::vehicle_joined,
                         "vehicle " + id + kind + " joined" +
                             (source->link_name().empty() ? "" : " over " + source->link_name()));
    } else {
      feed.station_event(s.t_s, mission::EventKind::vehicle_left,
                         "vehicle " + id + " left: its link is lost");
    }
  }

  void telemetry_tick(double now) {
    VehicleSnapshot s;
    s.info = vehicle().info();
    s.link = vehicle().link_state(now);
    s.nav = vehicle().last_nav();
    s.frontseat = source->frontseat_status();
    s.t_s = now;
    if (running) {
      s.helm_mode = running->runner->mode();
      s.desired_heading_deg = running->runner->desired_heading_deg();
      s.desired_speed_mps = running->runner->desired_speed_mps();
      s.mission_id = running->id;
    } else {
      fill_command(s);
    }
    feed.telemetry(s);
    announce_presence(s);
    std::lock_guard lock(mutex);
    snapshot = std::move(s);
  }

  void run() {
    store = open_station_store(db_path);
    const std::unique_ptr<sim::Pacer> pacer = source->pacer();
    while (!stop_requested.load() || running) {
      if (!scheduler.run_until(scheduler.now_s() + 1.0, *pacer)) break;
    }
    source->park();
    store.reset();
  }
};

VehicleLoop::VehicleLoop(VehicleLoopOptions options, std::string db_path, LiveFeed& feed)
    : impl_(std::make_unique<Impl>(std::move(options), std::move(db_path), feed)),
      info_(impl_->vehicle().info()) {
  Impl& i = *impl_;
  i.scheduler.add("helm", i.options.setup.helm_hz, [&i](double now) { i.helm_tick(now); });
  i.scheduler.add("telemetry", i.options.telemetry_hz, [&i](double now) { i.telemetry_tick(now); });
  i.snapshot.info = info_;
}

VehicleLoop::~VehicleLoop() {
  stop();
}

void VehicleLoop::start() {
  if (impl_->thread.joinable()) return;
  impl_->thread = std::thread([this] { impl_->run(); });
}

void VehicleLoop::request_stop(const std::string& reason) {
  if (!impl_->thread.joinable() || impl_->stop_requested.load()) return;
  {
    std::lock_guard lock(impl_->mutex);
    impl_->stop_reason = reason;
  }
  impl_->stop_requested.store(true);
}

void VehicleLoop::stop(const std::string& reason) {
  if (!impl_->thread.joinable()) return;
  request_stop(reason);
  impl_->thread.join();
}

const VehicleLoopOptions& VehicleLoop::options() const {
  return impl_->options;
}

VehicleSnapshot VehicleLoop::snapshot() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->snapshot;
}

std::optional<MissionLive> VehicleLoop::live(std::int64_t mission_id) const {
  std::lock_guard lock(impl_->mutex);
  const auto it = impl_->live.find(mission_id);
  if (it == impl_->live.end()) return std::nullopt;
  return it->second;
}

std::optional<std::int64_t> VehicleLoop::attached_mission() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->attached;
}

bool VehicleLoop::attach(MissionPlan plan) {
  std::lock_guard lock(impl_->mutex);
  if (impl_->attached || impl_->stop_requested.load()) return false;
  impl_->attached = plan.mission_id;
  Impl* i = impl_.get();
  impl_->pending.push_back(
      [i, p = std::move(plan)](double now) mutable { i->start_running(std::move(p), now); });
  return true;
}

bool VehicleLoop::command(std::int64_t mission_id, Command c) {
  std::lock_guard lock(impl_->mutex);
  if (impl_->attached != mission_id) return false;
  Impl* i = impl_.get();
  impl_->pending.push_back([i, mission_id, c](double now) {
    if (!i->running || i->running->id != mission_id) return;
    auto& r = *i->running->runner;
    switch (c) {
      case Command::pause:
        r.pause(now);
        break;
      case Command::resume:
        r.resume(now);
        break;
      case Command::abort:
        r.abort(now);
        break;
    }
    i->update_live();
    if (r.finished()) i->finish_running(now);
  });
  return true;
}

bool VehicleLoop::command_vehicle(mission::VehicleCommand c) {
  std::lock_guard lock(impl_->mutex);
  if (impl_->stop_requested.load()) return false;
  Impl* i = impl_.get();
  impl_->pending.push_back([i, c](double now) { i->apply_command(c, now); });
  return true;
}

void VehicleLoop::announce(double t_s, mission::EventKind kind, const std::string& message) {
  impl_->feed.station_event(t_s, kind, message);
}

std::optional<kinematics::Point> VehicleLoop::last_return_point() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->return_point;
}

bool VehicleLoop::wait_for_tick(std::chrono::milliseconds timeout) {
  std::unique_lock lock(impl_->mutex);
  const std::uint64_t target = impl_->ticks + 2;  // one tick may be halfway through
  return impl_->ticked.wait_for(lock, timeout, [&] { return impl_->ticks >= target; });
}

}  // namespace avk::app
