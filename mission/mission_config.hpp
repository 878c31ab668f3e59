#pragma once
// The mission file (docs/mission-format.md): what turns to collect, how to establish each turn's
// conditions, when a turn is complete, and where the vehicle may go. Validation collects every
// problem, each naming its field, so an operator fixes a file in one pass.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "kinematics/geometry.hpp"

namespace avk::mission {

enum class DirectionPolicy { right, left, alternate, automatic };
const char* to_string(DirectionPolicy p);

enum class MissionKind { turns, persistent_excitation };

// Size limits of a mission (docs/mission-format.md). A mission is a request from outside: without
// them a 13 KB file asks for 10^9 planned turns, and a 62,000-vertex region makes every
// containment check slow. Each is well past what a field day collects (the thesis' Figure 4-1
// mission plans 18 turns).
inline constexpr std::size_t kMaxMissionSpeeds = 20;
inline constexpr std::size_t kMaxMissionDheadings = 36;
inline constexpr int kMaxMissionRepeats = 100;
inline constexpr std::size_t kMaxMissionYawRates = 9;
inline constexpr std::size_t kMaxPlannedTurns = 2000;  // speeds x dheadings x yaw rates x repeats
inline constexpr std::size_t kMaxRegionVertices = 256;
inline constexpr double kMaxRegionExtentM = 10000.0;  // each side of the bounding box
// The name is listed with every mission (GET /missions, the dashboard's tables): at most this
// many bytes of UTF-8, which holds any file name (255) an import takes it from.
inline constexpr std::size_t kMaxMissionNameBytes = 256;
// Two speeds (heading changes) closer than this would fill the same table cell: a duplicate.
inline constexpr double kMinSpeedSpacingMps = 0.05;
inline constexpr double kMinDheadingSpacingDeg = 0.5;
inline constexpr double kMinYawRateSpacingDps = 0.5;
inline constexpr double kMaxInitialYawRateDps = 60.0;

// A turn that changes speed as it changes heading. The ConditionSet establishes
// from_mps (u0) on a steady course; the turn command sends the new heading with to_mps (u1).
inline constexpr std::size_t kMaxMissionSpeedChanges = 20;
struct SpeedChange {
  double from_mps = 0.0;
  double to_mps = 0.0;
  friend bool operator==(const SpeedChange&, const SpeedChange&) = default;
};

struct TurnArray {
  std::vector<double> speeds_mps;  // empty only when speed_changes is not
  // Each entry is flown for every heading change (x repeats), after the constant-speed turns.
  std::vector<SpeedChange> speed_changes;
  std::vector<double> dheadings_deg;  // magnitudes in (0, 180]
  DirectionPolicy direction = DirectionPolicy::alternate;
  int repeats = 1;
  // A turn aborted by containment or a link loss is re-queued; after this many attempts it is
  // given up (and reported) so that a region too small for a turn cannot loop forever.
  int max_attempts = 10;
  // Turns that start while the vehicle is already turning (thesis §6.2): signed target
  // yaw rates at the moment the turn is commanded, + into the coming turn, - against it, 0 the
  // ordinary steady start. Empty: only steady starts.
  std::vector<double> initial_yaw_rates_dps;
  double initial_yaw_rate_band_dps = 1.5;    // the turn starts when |rate - target| <= this
  double pre_turn_dheading_deg = 45.0;       // the heading change that builds up the yaw rate
  double initial_yaw_rate_timeout_s = 30.0;  // the band not entered in this long: aborted
};

// How the ConditionSet estimates the yaw rate from compass headings. least_squares: the slope of
// the heading over the last yaw_rate_window_s (kinematics/yaw_rate_estimator.hpp), fit for a real
// compass. moving_average: the thesis' eqs. 4.1-4.2, the mean of the last `window` differenced
// headings, which only the two end samples decide; kept to reproduce the thesis' figures.
enum class YawRateMethod { least_squares, moving_average };
const char* to_string(YawRateMethod m);

struct ConditionSetConfig {
  double speed_tolerance_mps = 0.1;
  double max_yaw_rate_dps = 1.0;
  int window = 5;  // moving-average window of differenced headings (thesis eq. 4.2)
  double timeout_s = 120.0;
  // The heading must also be within this of the course being held: at the far end of an
  // overshoot swing the yaw rate passes through zero while the vehicle is well off course.
  double max_heading_error_deg = 2.0;
  YawRateMethod yaw_rate_method = YawRateMethod::least_squares;
  // The least-squares window: with 1° compass noise at 10 Hz the slope over 2 s scatters by
  // 0.36 °/s, a third of the usual 1 °/s limit, and lags a changing rate by about 1 s.
  double yaw_rate_window_s = 2.0;
  // Room ahead to begin: conditions are established only on a course that stays clear of the
  // buffer for this long at the turn's speed, plus the turn's own room (kConditioningTurnRoomM).
  // A shorter run would end in containment before or during the turn, wasting the attempt; the
  // helm turns inward first instead (a turning_back event).
  double run_ahead_s = 30.0;
};
inline constexpr double kConditioningTurnRoomM = 10.0;

// ConstantHeading's completion (thesis §4.4.3), relative to the commanded change: a turn is
// complete within max(floor, min(threshold, fraction x |goal|)) of its goal heading. A fixed 5 deg
// recorded a 10 deg turn as complete after about 5 deg, slow and drifting; the
// fraction records a small turn to its end, the threshold still spares a large one the slow
// final approach, and the floor keeps a small turn above the heading noise.
// mission::completion_threshold_deg (turn_monitor.hpp) computes it for every user.
struct CompletionRule {
  double threshold_deg = 5.0;
  double fraction = 0.1;
  double floor_deg = 1.0;
};

struct OperatingRegion {
  kinematics::Polyline polygon;  // local grid, metres
  double buffer_m = 10.0;
  kinematics::Point return_point;
  std::optional<double> return_speed_mps;  // default: the mission's first speed
  double capture_radius_m = 3.0;           // the return point is reached within this
};

// Thesis §3.4.2: constant speed, random heading changes at random intervals (seeded).
struct ExcitationConfig {
  double speed_mps = 1.0;
  double duration_s = 600.0;
  double min_step_deg = 20.0;
  double max_step_deg = 120.0;
  double min_interval_s = 3.0;
  double max_interval_s = 10.0;
  std::uint64_t seed = 1;
};

struct MissionConfig {
  std::string name;
  MissionKind kind = MissionKind::turns;
  TurnArray turn_array;
  ConditionSetConfig condition_set;
  CompletionRule completion;  // constant_heading.completion_*
  // A turn that has not completed after this long is aborted (and re-queued).
  double turn_timeout_s = 120.0;
  OperatingRegion region;
  std::optional<ExcitationConfig> excitation;
};

struct FieldError {
  std::string field;  // JSON pointer
  std::string message;
};

class MissionConfigError : public std::runtime_error {
 public:
  explicit MissionConfigError(std::vector<FieldError> errors);
  const std::vector<FieldError>& errors() const { return errors_; }

 private:
  std::vector<FieldError> errors_;
};

// Speed for the run back to the return point.
double return_speed_mps(const MissionConfig& config);

// Parses and validates; max_speed_mps is the vehicle's. Throws MissionConfigError listing every
// problem.
MissionConfig parse_mission_config(std::string_view json_text, double max_speed_mps);

// Polygon helpers the validation and the container behaviour share.
double polygon_area_m2(const kinematics::Polyline& polygon);
bool polygon_is_simple(const kinematics::Polyline& polygon);
bool point_in_polygon(kinematics::Point p, const kinematics::Polyline& polygon);
double distance_to_boundary_m(kinematics::Point p, const kinematics::Polyline& polygon);

}  // namespace avk::mission
