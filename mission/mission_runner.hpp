#pragma once
// The collection mission (thesis §4.3–4.5): pDynamicsMonitor and the helm's behaviours in one
// state machine. It talks to the vehicle only through vehicle::Vehicle and reports everything it
// records to its observers; whoever owns the clock calls tick() at the helm's AppTick.
//
// Modes: (TRANSITING, when it starts outside the region ->) CONTAINING -> CONDITIONING -> TURNING
// -> CONDITIONING -> ... -> RETURNING -> DONE, and EXCITING for a persistent-excitation mission.
// Entering the buffer aborts a turn in progress (stored as aborted, re-queued) and contains;
// leaving the region after having reached its interior halts (all stop).

#include <deque>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "kinematics/ckt.hpp"
#include "mission/condition_set.hpp"
#include "mission/container.hpp"
#include "mission/direction_chooser.hpp"
#include "mission/helm_mode.hpp"
#include "mission/mission_config.hpp"
#include "mission/mission_observer.hpp"
#include "mission/station_keeping.hpp"
#include "mission/turn_monitor.hpp"
#include "mission/turn_plan.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::mission {

struct RunnerOptions {
  std::string vehicle_id;
  std::string mission_label;  // written into each TurnSequence's mission_id
  // A table from earlier missions for direction auto until this mission has its own; not owned.
  const kinematics::Ckt* prior_table = nullptr;
  DirectionOptions direction{};
  double max_sample_gap_s = 2.0;  // a turn with a longer navigation gap is rejected
};

// Progress of one turn-array cell.
struct CellProgress {
  double speed_mps = 0.0;
  double dheading_deg = 0.0;
  int planned = 0;
  int ok = 0;  // including turns done before a resume
  int rejected = 0;
  int aborted = 0;
  int given_up = 0;
  bool running = false;
  std::optional<double> speed_after_mps;  // a speed-change cell (speed_mps -> this)
};

class MissionRunner {
 public:
  // tasks: the turns still to do (plan_turns, or remaining_turns when resuming).
  MissionRunner(MissionConfig config, vehicle::Vehicle& vehicle, std::vector<TurnTask> tasks,
                RunnerOptions options);

  void add_observer(MissionObserver& observer) { observers_.push_back(&observer); }

  // The helm's AppTick: takes the navigation that arrived, advances the modes, commands.
  void tick(double now_s);

  // Operator commands. A turn in progress is aborted and re-queued (not counted as an attempt).
  // Paused, the vehicle keeps station where it was paused until resumed.
  // Each returns false when it does not apply (resume of a mission that is not paused, ...).
  bool pause(double now_s, const std::string& reason = "paused by operator");
  bool resume(double now_s);
  bool abort(double now_s, const std::string& reason = "aborted by operator");
  // The process is going away: like pause, but the mission ends here as interrupted.
  void interrupt(double now_s, const std::string& reason);

  HelmMode mode() const { return mode_; }
  std::optional<MissionState> state() const { return state_; }
  bool finished() const;
  std::optional<double> desired_heading_deg() const { return desired_heading_deg_; }
  std::optional<double> desired_speed_mps() const { return desired_speed_mps_; }
  const std::deque<TurnTask>& queue() const { return queue_; }
  const std::vector<CellProgress>& cells() const { return cells_; }
  const Container& container() const { return container_; }
  std::size_t turns_given_up() const { return given_up_; }
  // Set from the moment a turn is commanded until it ends (finished, aborted or paused).
  const std::optional<RunningTurn>& running_turn() const { return running_turn_; }

 private:
  void process(const vehicle::NavSample& s);
  void set_mode(HelmMode m, double t_s);
  void set_state(MissionState s, const std::string& reason, double t_s);
  void event(double t_s, EventKind kind, const std::string& message);
  void contain(const vehicle::NavSample& s, const std::string& why);
  void leave_containment(const vehicle::NavSample& s);
  // Holds course_deg (the heading now when not given) unless the run along it is too short to
  // set conditions and turn; then turns inward first (containing, towards turn_back_course_deg_).
  // A course reached by turning back is held as it is (may_turn_back false), so a region too
  // small for the run never turns the boat back and forth.
  void start_conditioning(const vehicle::NavSample& s,
                          std::optional<double> course_deg = std::nullopt,
                          bool may_turn_back = true);

  void end_condition_set(double t_s, ConditionSetEpisode::Outcome outcome);
  // A turn with a nonzero target yaw rate: once the conditions are set, a heading change that
  // builds up the yaw rate; the turn starts when it enters the target band.
  void start_pre_turn(const vehicle::NavSample& s);
  bool pre_turn_in_band() const;
  kinematics::TurnSide side_for(const TurnTask& task, const vehicle::NavSample& s);
  void start_turn(const vehicle::NavSample& s);
  void finish_turn(const vehicle::NavSample& s, Completion how);
  // count_attempt: containment, timeouts and link loss count towards max_attempts; an
  // operator's pause does not.
  void abort_turn(double t_s, const std::string& reason, bool count_attempt);
  // After a failed attempt: back to the front of the queue, or given up at max_attempts.
  void give_up_or_requeue(double t_s, TurnOutcome& out);
  void start_exciting(const vehicle::NavSample& s, double now_s);
  void start_returning(double t_s);
  void stop_all(double t_s, HelmMode mode, MissionState state, const std::string& reason);
  void check_return(const vehicle::NavSample& s);
  void update_desired(double now_s);
  CellProgress* cell_of(const TurnTask& t);
  const kinematics::Ckt* table_for_auto();

  MissionConfig config_;
  vehicle::Vehicle& vehicle_;
  RunnerOptions options_;
  Container container_;
  std::vector<MissionObserver*> observers_;
  std::deque<TurnTask> queue_;
  std::vector<CellProgress> cells_;

  HelmMode mode_ = HelmMode::containing;
  HelmMode paused_from_ = HelmMode::containing;
  std::optional<MissionState> state_;
  std::optional<double> desired_heading_deg_;
  std::optional<double> desired_speed_mps_;
  std::optional<vehicle::NavSample> last_nav_;
  bool been_inside_ = false;
  bool holding_ = false;  // navigation is not live: all stop until it is
  // Paused: the vehicle keeps station where it was paused (against current and wind) rather than
  // drifting, as long as navigation is live; all stop without it.
  std::optional<StationKeeping> pause_keeper_;
  bool pause_stopped_ = true;
  void keep_station_while_paused(double now_s);

  std::optional<ConditionSetMonitor> condition_set_;
  double condition_set_start_s_ = 0.0;
  double held_course_deg_ = 0.0;
  std::optional<double> turn_back_course_deg_;  // containing early, not in the buffer
  std::optional<TurnMonitor> turn_;
  std::optional<RunningTurn> running_turn_;  // with turn_
  double turn_start_s_ = 0.0;
  std::optional<double> turn_condition_set_time_s_;
  std::optional<double> turn_start_heading_error_deg_;
  std::optional<double> turn_start_yaw_rate_dps_;
  std::optional<kinematics::TurnSide> pre_turn_side_;  // set while a pre-turn is under way
  double pre_turn_start_s_ = 0.0;
  std::size_t given_up_ = 0;
  kinematics::TurnSide next_auto_preference_ = kinematics::TurnSide::right;

  std::vector<kinematics::TurnSequence> ok_turns_;  // this mission's, for direction auto
  std::optional<kinematics::Ckt> own_table_;
  std::size_t own_table_turns_ = 0;

  std::mt19937_64 rng_;
  std::optional<double> excite_start_s_;
  double next_step_s_ = 0.0;

  double return_best_m_ = 0.0;
};

}  // namespace avk::mission
