#include "kinematics/turn_sequence.hpp"

#include <algorithm>
#include <cmath>

#include "kinematics/angles.hpp"

namespace avk::kinematics {

const char* to_string(TurnStatus s) {
  switch (s) {
    case TurnStatus::ok:
      return "ok";
    case TurnStatus::aborted:
      return "aborted";
    case TurnStatus::rejected:
      return "rejected";
  }
  return "?";
}

std::optional<TurnStatus> turn_status_from_string(const std::string& s) {
  if (s == "ok") return TurnStatus::ok;
  if (s == "aborted") return TurnStatus::aborted;
  if (s == "rejected") return TurnStatus::rejected;
  return std::nullopt;
}

const char* to_string(TurnSource s) {
  return s == TurnSource::harvested ? "harvested" : "collection";
}

std::optional<TurnSource> turn_source_from_string(const std::string& s) {
  if (s == "collection") return TurnSource::collection;
  if (s == "harvested") return TurnSource::harvested;
  return std::nullopt;
}

const char* to_string(TurnErrorCode c) {
  switch (c) {
    case TurnErrorCode::too_few_samples:
      return "too_few_samples";
    case TurnErrorCode::non_finite:
      return "non_finite";
    case TurnErrorCode::time_not_increasing:
      return "time_not_increasing";
    case TurnErrorCode::instantaneous_turn:
      return "instantaneous_turn";
    case TurnErrorCode::bad_metadata:
      return "bad_metadata";
  }
  return "?";
}

TurnSequence TurnSequence::from_streams(TurnMeta meta, const std::vector<double>& t_s,
                                        const std::vector<double>& x_m,
                                        const std::vector<double>& y_m,
                                        const std::vector<double>& heading_deg,
                                        const std::vector<double>& speed_mps) {
  const std::size_t n =
      std::min({t_s.size(), x_m.size(), y_m.size(), heading_deg.size(), speed_mps.size()});
  TurnSequence turn(std::move(meta), {});
  const auto note = [&](const char* name, std::size_t size) {
    if (size > n) {
      turn.add_warning(std::string("dropped ") + std::to_string(size - n) + " trailing " + name +
                       " value(s): streams had unequal lengths");
    }
  };
  note("t", t_s.size());
  note("x", x_m.size());
  note("y", y_m.size());
  note("heading", heading_deg.size());
  note("speed", speed_mps.size());
  turn.samples_.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    turn.samples_.push_back({t_s[i], x_m[i], y_m[i], heading_deg[i], speed_mps[i]});
  }
  turn.fill_derived_metadata();
  return turn;
}

Polyline TurnSequence::points() const {
  Polyline p;
  p.reserve(samples_.size());
  for (const auto& s : samples_)
    p.push_back({s.x_m, s.y_m});
  return p;
}

double TurnSequence::heading_change_deg() const {
  if (samples_.size() < 2) return 0.0;
  double total = 0.0;
  for (std::size_t i = 1; i < samples_.size(); ++i) {
    total += angle180_deg(samples_[i].heading_deg - samples_[i - 1].heading_deg);
  }
  return total;
}

void TurnSequence::fill_derived_metadata() {
  if (samples_.empty()) return;
  meta_.initial_heading_deg = samples_.front().heading_deg;
  meta_.initial_speed_mps = samples_.front().speed_mps;
  meta_.start_time_s = samples_.front().t_s;
  meta_.end_time_s = samples_.back().t_s;
  meta_.observed_dheading_deg = heading_change_deg();
}

void TurnSequence::validate(const TurnValidationOptions& options) const {
  if (samples_.size() < options.min_samples) {
    throw TurnError(TurnErrorCode::too_few_samples,
                    "turn has " + std::to_string(samples_.size()) + " samples; at least " +
                        std::to_string(options.min_samples) + " are needed");
  }
  const auto finite_meta = {
      meta_.commanded_speed_mps, meta_.goal_dheading_deg, meta_.observed_dheading_deg,
      meta_.initial_heading_deg, meta_.initial_speed_mps, meta_.start_time_s,
      meta_.end_time_s};
  for (double v : finite_meta) {
    if (!std::isfinite(v)) {
      throw TurnError(TurnErrorCode::non_finite, "turn metadata holds a NaN or infinite value");
    }
  }
  for (std::size_t i = 0; i < samples_.size(); ++i) {
    const auto& s = samples_[i];
    if (!std::isfinite(s.t_s) || !std::isfinite(s.x_m) || !std::isfinite(s.y_m) ||
        !std::isfinite(s.heading_deg) || !std::isfinite(s.speed_mps)) {
      throw TurnError(TurnErrorCode::non_finite,
                      "sample " + std::to_string(i) + " holds a NaN or infinite value", i);
    }
    if (i > 0 && !(s.t_s > samples_[i - 1].t_s)) {
      throw TurnError(TurnErrorCode::time_not_increasing,
                      "sample " + std::to_string(i) + " time does not increase", i);
    }
  }
  if (std::abs(heading_change_deg()) < options.instantaneous_tolerance_deg) {
    throw TurnError(TurnErrorCode::instantaneous_turn,
                    "initial and final headings are equal: an instantaneous turn");
  }
}

TurnSequence TurnSequence::normalized() const {
  if (meta_.normalized) return *this;
  TurnSequence out = *this;
  out.meta_.normalized = true;
  if (samples_.empty()) return out;
  const Pose start{samples_.front().x_m, samples_.front().y_m, meta_.initial_heading_deg};
  const TurnSide s = side();
  const double mirror = s == TurnSide::left ? -1.0 : 1.0;
  if (out.meta_.initial_yaw_rate_dps) *out.meta_.initial_yaw_rate_dps *= mirror;
  double unwrapped = angle180_deg(samples_.front().heading_deg - meta_.initial_heading_deg);
  for (std::size_t i = 0; i < samples_.size(); ++i) {
    if (i > 0) unwrapped += angle180_deg(samples_[i].heading_deg - samples_[i - 1].heading_deg);
    const Point p = normalize_point({samples_[i].x_m, samples_[i].y_m}, start, s);
    out.samples_[i].x_m = p.x_m;
    out.samples_[i].y_m = p.y_m;
    out.samples_[i].heading_deg = mirror * unwrapped;
  }
  return out;
}

}  // namespace avk::kinematics
