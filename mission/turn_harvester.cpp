#include "mission/turn_harvester.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "mission/turn_monitor.hpp"

namespace avk::mission {

std::size_t HarvestResult::rejected_total() const {
  return std::accumulate(rejected.begin(), rejected.end(), std::size_t{0});
}

double turn_quality(const StepStart& start, const kinematics::TurnSequence& turn,
                    const ConditionSetConfig& condition_set, const CompletionRule& completion) {
  const auto ratio = [](double value, double limit) {
    return limit > 0.0 ? std::min(1.0, std::abs(value) / limit) : (value == 0.0 ? 0.0 : 1.0);
  };
  const double steady = 1.0 - 0.5 * ratio(start.yaw_rate_dps, condition_set.max_yaw_rate_dps) -
                        0.5 * ratio(start.speed_error_mps, condition_set.speed_tolerance_mps);
  const double goal = turn.meta().goal_dheading_deg;
  const double miss = std::abs(turn.heading_change_deg()) - std::abs(goal);
  const double complete = 1.0 - 0.5 * ratio(miss, completion_threshold_deg(completion, goal));
  return std::clamp(steady * complete, 0.0, 1.0);
}

namespace {

class Harvest {
 public:
  Harvest(std::span<const double> collected, const HarvestOptions& options)
      : collected_(collected), options_(options) {}

  bool collected(double t_s) const {
    return std::any_of(collected_.begin(), collected_.end(), [&](double c) {
      return std::abs(c - t_s) <= options_.same_start_tolerance_s;
    });
  }

  void count_skipped(TurnExtractor& x) {
    for (const auto& step : x.take_skipped_steps()) {
      ++out.steps;
      if (collected(step.t_s)) {
        ++out.already_recorded;
      } else {
        ++out.rejected[static_cast<std::size_t>(step.reason)];
      }
    }
  }

  void take(const TurnExtractor& x, kinematics::TurnSequence turn) {
    ++out.steps;
    if (collected(turn.meta().start_time_s)) {
      ++out.already_recorded;
      return;
    }
    if (const auto why = x.last_turn_rejection()) {
      ++out.rejected[static_cast<std::size_t>(*why)];
      return;
    }
    const auto& o = options_.extraction;
    turn.meta().source = kinematics::TurnSource::harvested;
    turn.meta().quality = turn_quality(x.last_turn_start(), turn, o.condition_set, o.completion);
    out.turns.push_back({std::move(turn), x.last_turn_start()});
  }

  HarvestResult out;

 private:
  std::span<const double> collected_;
  const HarvestOptions& options_;
};

}  // namespace

HarvestResult harvest_turns(std::span<const vehicle::GuidedNav> log,
                            std::span<const double> recorded_start_times_s,
                            const HarvestOptions& options, const std::string& vehicle_id,
                            const std::string& mission_id) {
  TurnExtractor extractor(options.extraction, vehicle_id, mission_id);
  Harvest h(recorded_start_times_s, options);
  for (const auto& s : log) {
    auto turn = extractor.feed(s);
    // A sample may end a turn and be a step of its own: the turn came first.
    if (turn) h.take(extractor, std::move(*turn));
    h.count_skipped(extractor);
  }
  if (auto turn = extractor.finish()) h.take(extractor, std::move(*turn));
  return std::move(h.out);
}

}  // namespace avk::mission
