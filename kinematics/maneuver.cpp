#include "kinematics/maneuver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "kinematics/approach_risk.hpp"
#include "kinematics/water_frame.hpp"

namespace avk::kinematics {

Point contact_position(const Contact& c, double t_s) {
  const Point d = rotate_by_heading({0.0, c.speed_mps * t_s}, c.course_deg);
  return {c.x_m + d.x_m, c.y_m + d.y_m};
}

PredictedManeuver timed_maneuver(double dheading_deg, double speed_mps, const Polyline& trajectory,
                                 const std::optional<TurnTiming>& timing,
                                 std::vector<double> half_width_m) {
  if (trajectory.empty()) throw std::invalid_argument("a maneuver needs a trajectory");
  if (!(speed_mps > 0.0)) throw std::invalid_argument("a maneuver needs a positive speed");
  if (!half_width_m.empty() && half_width_m.size() != trajectory.size())
    throw std::invalid_argument("one corridor half width per trajectory point");
  PredictedManeuver m;
  m.dheading_deg = dheading_deg;
  m.speed_mps = speed_mps;
  m.half_width_m = std::move(half_width_m);
  m.timed_by_turns = timing.has_value() && timing->time_s.size() == kTimingStations;
  const std::vector<double> s = cumulative_arc_length_m(trajectory);
  const double length = s.back();
  // The timing spans the cell's own trajectory; a blended or re-simplified trajectory is a little
  // longer or shorter, so lengths map by fraction.
  const double to_timing = m.timed_by_turns && length > 0.0 ? timing->length_m / length : 1.0;
  m.path.reserve(trajectory.size());
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    const double t = m.timed_by_turns ? time_at_length_s(*timing, s[i] * to_timing, speed_mps)
                                      : s[i] / speed_mps;
    m.path.push_back({t, trajectory[i].x_m, trajectory[i].y_m});
  }
  return m;
}

namespace {

// Per-point values (corridor half widths, band spreads) follow the path's cut and run-on.
void cut_values(std::vector<double>& v, std::size_t i, double w) {
  if (v.empty()) return;
  v[i] = v[i - 1] + w * (v[i] - v[i - 1]);
  v.resize(i + 1);
}

void hold_last(std::vector<double>& v) {
  if (!v.empty()) v.push_back(v.back());
}

// The path cut at the horizon, with its per-point values; false when it ends before it.
bool cut_at(PredictedManeuver& m, double horizon_s) {
  for (std::size_t i = 1; i < m.path.size(); ++i) {
    if (m.path[i].t_s < horizon_s) continue;
    const TimedPoint a = m.path[i - 1], b = m.path[i];
    const double w = b.t_s > a.t_s ? (horizon_s - a.t_s) / (b.t_s - a.t_s) : 1.0;
    m.path[i] = {horizon_s, a.x_m + w * (b.x_m - a.x_m), a.y_m + w * (b.y_m - a.y_m)};
    m.path.resize(i + 1);
    cut_values(m.half_width_m, i, w);
    cut_values(m.along_sd_m, i, w);
    cut_values(m.cross_sd_m, i, w);
    m.turn_points = std::min(m.turn_points, m.path.size());
    return true;
  }
  return false;
}

}  // namespace

PredictedManeuver extended_to_horizon(PredictedManeuver m, double horizon_s) {
  if (m.path.empty()) throw std::invalid_argument("a maneuver needs a path");
  if (!(horizon_s > 0.0) || !std::isfinite(horizon_s))
    throw std::invalid_argument("the horizon must be a positive time");
  if (cut_at(m, horizon_s)) return m;
  const TimedPoint last = m.path.back();
  // A path that ends within rounding of the horizon needs no run-on of a nanometre.
  if (last.t_s >= horizon_s - 1e-9) return m;
  // Past the prediction the vehicle holds its new heading (the goal, as the CKT's trajectories
  // end on it) at the commanded speed.
  const double run = (horizon_s - last.t_s) * m.speed_mps;
  const Point d = rotate_by_heading({0.0, run}, m.dheading_deg);
  m.path.push_back({horizon_s, last.x_m + d.x_m, last.y_m + d.y_m});
  hold_last(m.half_width_m);
  hold_last(m.along_sd_m);
  hold_last(m.cross_sd_m);
  return m;
}

TimedPath placed(const TimedPath& normalized, const Pose& pose) {
  // rotate_by_heading's rotation, with its sine and cosine taken once for the whole path.
  const Point ex = rotate_by_heading({1.0, 0.0}, pose.heading_deg);
  const Point ey = rotate_by_heading({0.0, 1.0}, pose.heading_deg);
  TimedPath out;
  out.reserve(normalized.size());
  for (const TimedPoint& p : normalized)
    out.push_back({p.t_s, pose.x_m + p.x_m * ex.x_m + p.y_m * ey.x_m,
                   pose.y_m + p.x_m * ex.y_m + p.y_m * ey.y_m});
  return out;
}

namespace {

// A contact's motion with its velocity resolved once: the CPA loops below run over every segment
// of every candidate, and a sine and cosine per evaluation were most of their time.
struct Motion {
  double x0, y0, vx, vy;
  explicit Motion(const Contact& c) {
    const Point v = rotate_by_heading({0.0, c.speed_mps}, c.course_deg);
    x0 = c.x_m, y0 = c.y_m, vx = v.x_m, vy = v.y_m;
  }
};

struct SegmentApproach {
  double distance2_m2;  // squared
  double time_s;
  double weight;  // where along the segment, 0..1
};

// The closest approach on one segment of own path: the relative position is linear in time.
SegmentApproach segment_approach(const TimedPoint& a, const TimedPoint& b, const Motion& c) {
  const double rx = a.x_m - (c.x0 + c.vx * a.t_s), ry = a.y_m - (c.y0 + c.vy * a.t_s);
  const double dt = b.t_s - a.t_s;
  if (!(dt > 0.0)) return {rx * rx + ry * ry, a.t_s, 0.0};
  const double dx = (b.x_m - a.x_m) - c.vx * dt, dy = (b.y_m - a.y_m) - c.vy * dt;
  const double dd = dx * dx + dy * dy;
  const double w = dd > 0.0 ? std::clamp(-(rx * dx + ry * dy) / dd, 0.0, 1.0) : 0.0;
  const double ex = rx + w * dx, ey = ry + w * dy;
  return {ex * ex + ey * ey, a.t_s + w * dt, w};
}

double distance2_at(const TimedPoint& p, const Motion& c) {
  const double rx = p.x_m - (c.x0 + c.vx * p.t_s), ry = p.y_m - (c.y0 + c.vy * p.t_s);
  return rx * rx + ry * ry;
}

// One pass over the path for the CPA and, with half widths, the corridor's nearer edge.
std::pair<Approach, std::optional<Approach>> approaches(const TimedPath& own,
                                                        const std::vector<double>* half_width_m,
                                                        const Contact& contact) {
  if (own.empty()) throw std::invalid_argument("a closest approach needs a path");
  if (half_width_m && half_width_m->size() != own.size())
    throw std::invalid_argument("one corridor half width per path point");
  const Motion c(contact);
  double best2 = distance2_at(own.front(), c);
  double best_t = own.front().t_s;
  std::optional<Approach> edge;
  const auto edge_of = [](double d2, double w) { return std::max(0.0, std::sqrt(d2) - w); };
  if (half_width_m) edge = Approach{edge_of(best2, half_width_m->front()), own.front().t_s};
  for (std::size_t i = 1; i < own.size(); ++i) {
    const SegmentApproach s = segment_approach(own[i - 1], own[i], c);
    if (s.distance2_m2 < best2) best2 = s.distance2_m2, best_t = s.time_s;
    if (!half_width_m) continue;
    const double w0 = (*half_width_m)[i - 1], w1 = (*half_width_m)[i];
    // On this segment the edge comes no nearer than the path does less the widest half width.
    const double reach = edge->distance_m + std::max(w0, w1);
    if (s.distance2_m2 >= reach * reach) continue;
    // The half width changes by centimetres along a segment, so the smallest distance less width
    // is at an end or at the segment's closest approach.
    const double at_end = edge_of(distance2_at(own[i], c), w1);
    if (at_end < edge->distance_m) edge = Approach{at_end, own[i].t_s};
    const double at_cpa = edge_of(s.distance2_m2, w0 + s.weight * (w1 - w0));
    if (at_cpa < edge->distance_m) edge = Approach{at_cpa, s.time_s};
  }
  return {Approach{std::sqrt(best2), best_t}, edge};
}

}  // namespace

Approach closest_approach(const TimedPath& own, const Contact& contact) {
  return approaches(own, nullptr, contact).first;
}

Approach closest_approach_of_corridor(const TimedPath& own, const std::vector<double>& half_width_m,
                                      const Contact& contact) {
  return *approaches(own, &half_width_m, contact).second;
}

PredictedManeuver placed_over_ground(const PredictedManeuver& normalized, const Pose& pose,
                                     const std::optional<WaterCurrent>& current,
                                     bool speed_over_ground, double horizon_s) {
  const bool retime =
      current && speed_over_ground && (current->east_mps != 0.0 || current->north_mps != 0.0);
  // Re-timing stretches or shrinks time by at most the over-ground scale's bounds, so a water
  // path that long reaches the horizon over ground too.
  PredictedManeuver m =
      extended_to_horizon(normalized, retime ? horizon_s * kMaxOverGroundScale : horizon_s);
  m.path = placed(m.path, pose);
  if (!current) return m;
  const Point c{current->east_mps, current->north_mps};
  if (!retime) {
    m.path = drifted(std::move(m.path), c);
    return m;
  }
  m.path = retimed_over_ground(m.path, c);
  cut_at(m, horizon_s);
  return m;
}

CandidateEvaluation evaluate_candidate(const ManeuverProblem& problem,
                                       const PredictedManeuver& normalized) {
  const PredictedManeuver m = placed_over_ground(normalized, problem.own, problem.current,
                                                 problem.speed_over_ground, problem.horizon_s);
  CandidateEvaluation e;
  e.dheading_deg = m.dheading_deg;
  e.speed_mps = m.speed_mps;
  e.path = m.path;
  e.half_width_m = m.half_width_m;
  e.covariance_m2 = position_band(e.path, m.along_sd_m, m.cross_sd_m, m.turn_points, problem.band);
  e.min_cpa_m = std::numeric_limits<double>::infinity();
  const bool corridor = !e.half_width_m.empty();
  if (corridor) e.min_edge_cpa_m = std::numeric_limits<double>::infinity();
  e.clears = true;
  e.contacts.reserve(problem.contacts.size());
  double safe = 1.0;
  for (const Contact& c : problem.contacts) {
    ContactApproach a;
    std::tie(a.cpa, a.edge_cpa) = approaches(e.path, corridor ? &e.half_width_m : nullptr, c);
    a.risk = approach_risk(e.path, e.covariance_m2, c, problem.standoff_m);
    safe *= 1.0 - a.risk;
    e.min_cpa_m = std::min(e.min_cpa_m, a.cpa.distance_m);
    if (corridor) e.min_edge_cpa_m = std::min(*e.min_edge_cpa_m, a.edge_cpa->distance_m);
    const double judged =
        problem.use_corridor && a.edge_cpa ? a.edge_cpa->distance_m : a.cpa.distance_m;
    if (judged < problem.standoff_m) e.clears = false;
    e.contacts.push_back(a);
  }
  e.risk = 1.0 - safe;
  return e;
}

std::optional<std::size_t> choose_maneuver(const std::vector<CandidateEvaluation>& candidates) {
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const CandidateEvaluation& c = candidates[i];
    if (!c.clears) continue;
    if (!best) {
      best = i;
      continue;
    }
    const CandidateEvaluation& b = candidates[*best];
    const double ab = std::abs(b.dheading_deg), ac = std::abs(c.dheading_deg);
    if (ac < ab - 1e-9 || (std::abs(ac - ab) <= 1e-9 && c.dheading_deg > b.dheading_deg)) best = i;
  }
  return best;
}

std::vector<double> candidate_dheadings_deg(double step_deg) {
  if (!(step_deg > 0.0 && step_deg <= 180.0))
    throw std::invalid_argument("the candidate step must be within (0, 180] degrees");
  // Symmetric about 0 so that keeping course is always a candidate and each starboard turn has
  // its port twin; +-180 close the set even when the step does not divide 180.
  std::vector<double> out{0.0};
  for (int k = 1; static_cast<double>(k) * step_deg < 180.0 - 1e-9; ++k) {
    out.push_back(static_cast<double>(k) * step_deg);
    out.push_back(-static_cast<double>(k) * step_deg);
  }
  out.push_back(180.0);
  out.push_back(-180.0);
  std::sort(out.begin(), out.end());
  return out;
}

OngoingEvaluation evaluate_ongoing(const TimedPath& path, const std::vector<double>& half_width_m,
                                   double elapsed_s, std::optional<Point> measured,
                                   const std::optional<OngoingBand>& band) {
  if (path.empty()) throw std::invalid_argument("an ongoing maneuver needs its prediction");
  if (!half_width_m.empty() && half_width_m.size() != path.size())
    throw std::invalid_argument("one corridor half width per path point");
  if (band && band->covariance_m2.size() != path.size())
    throw std::invalid_argument("one band covariance per path point");
  const double band_k = band ? band_radius_factor(band->share) : 0.0;
  if (!(elapsed_s >= 0.0) || !std::isfinite(elapsed_s))
    throw std::invalid_argument("the elapsed time must be a non-negative number of seconds");
  if (measured && !(std::isfinite(measured->x_m) && std::isfinite(measured->y_m)))
    throw std::invalid_argument("the measured position must be finite");
  OngoingEvaluation e;
  e.elapsed_s = elapsed_s;
  // The first segment that ends at or after elapsed_s.
  std::size_t i = 1;
  while (i < path.size() && path[i].t_s < elapsed_s)
    ++i;
  std::size_t next = i;  // first point strictly ahead of expected
  if (i >= path.size()) {
    e.expected = {path.back().x_m, path.back().y_m};
    if (!half_width_m.empty()) e.half_width_m = half_width_m.back();
    if (band) e.band_m2 = band->covariance_m2.back();
    next = path.size();
  } else {
    const TimedPoint& a = path[i - 1];
    const TimedPoint& b = path[i];
    const double w =
        b.t_s > a.t_s ? std::clamp((elapsed_s - a.t_s) / (b.t_s - a.t_s), 0.0, 1.0) : 1.0;
    e.expected = {a.x_m + w * (b.x_m - a.x_m), a.y_m + w * (b.y_m - a.y_m)};
    if (!half_width_m.empty())
      e.half_width_m = half_width_m[i - 1] + w * (half_width_m[i] - half_width_m[i - 1]);
    if (band) {
      Covariance2 c{};
      for (std::size_t k = 0; k < c.size(); ++k)
        c[k] = band->covariance_m2[i - 1][k] +
               w * (band->covariance_m2[i][k] - band->covariance_m2[i - 1][k]);
      e.band_m2 = c;
    }
  }
  if (e.band_m2) e.band_ellipse = kinematics::band_ellipse(*e.band_m2, band->share);
  e.remaining.push_back({std::max(elapsed_s, path.front().t_s), e.expected.x_m, e.expected.y_m});
  for (std::size_t k = next; k < path.size(); ++k)
    if (path[k].t_s > elapsed_s) e.remaining.push_back(path[k]);
  if (measured) {
    e.deviation_m = distance_m(*measured, e.expected);
    Polyline line;
    line.reserve(path.size());
    for (const TimedPoint& p : path)
      line.push_back({p.x_m, p.y_m});
    e.cross_track_m = distance_to_polyline_m(*measured, line);
    if (e.band_m2) {
      const Point d{measured->x_m - e.expected.x_m, measured->y_m - e.expected.y_m};
      e.inside_band = mahalanobis2(*e.band_m2, d) <= band_k * band_k;
      e.inside_corridor = e.inside_band;
    } else if (e.half_width_m) {
      e.inside_corridor = *e.cross_track_m <= *e.half_width_m;
    }
  }
  return e;
}

}  // namespace avk::kinematics
