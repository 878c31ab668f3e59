#include "kinematics/current_estimate.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "kinematics/angles.hpp"

namespace avk::kinematics {

std::array<double, 2> ground_velocity_mps(const SteadyLeg& leg) {
  const std::size_t n = leg.t_s.size();
  if (n < 3 || leg.x_m.size() != n || leg.y_m.size() != n)
    throw std::invalid_argument("a steady leg needs 3 or more samples of t, x and y");
  double tm = 0.0, xm = 0.0, ym = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    tm += leg.t_s[i], xm += leg.x_m[i], ym += leg.y_m[i];
  tm /= static_cast<double>(n), xm /= static_cast<double>(n), ym /= static_cast<double>(n);
  double stt = 0.0, stx = 0.0, sty = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double dt = leg.t_s[i] - tm;
    stt += dt * dt;
    stx += dt * (leg.x_m[i] - xm);
    sty += dt * (leg.y_m[i] - ym);
  }
  if (!(stt > 0.0)) throw std::invalid_argument("a steady leg needs a time span");
  return {stx / stt, sty / stt};
}

double CurrentEstimate::speed_mps() const {
  return std::hypot(east_mps, north_mps);
}

double CurrentEstimate::toward_deg() const {
  return heading_of_deg(east_mps, north_mps);
}

double CurrentEstimate::speed_sd_mps() const {
  const double s = speed_mps();
  if (!(s > 0.0)) return std::sqrt(std::max(0.0, 0.5 * (covariance[0] + covariance[2])));
  // Along the current's direction.
  const double ue = east_mps / s, un = north_mps / s;
  return std::sqrt(std::max(
      0.0, ue * ue * covariance[0] + 2.0 * ue * un * covariance[1] + un * un * covariance[2]));
}

double CurrentEstimate::toward_sd_deg() const {
  const double s = speed_mps();
  if (!(s > 0.0)) return 180.0;
  // Across the current's direction, as an angle.
  const double pe = north_mps / s, pn = -east_mps / s;
  const double across = std::sqrt(std::max(
      0.0, pe * pe * covariance[0] + 2.0 * pe * pn * covariance[1] + pn * pn * covariance[2]));
  return std::min(180.0, rad_to_deg(std::atan2(across, s)));
}

CurrentEstimateResult estimate_current(const std::vector<SteadyLeg>& legs) {
  CurrentEstimateResult r;
  if (legs.size() < 2) {
    r.why_not = "a current needs steady legs on at least 2 headings; " +
                std::to_string(legs.size()) + " given";
    return r;
  }
  // The headings must spread: on one heading a current along it is a speed error.
  double spread = 0.0;
  for (std::size_t i = 0; i < legs.size(); ++i)
    for (std::size_t j = i + 1; j < legs.size(); ++j)
      spread = std::max(spread, std::abs(angle180_deg(legs[i].heading_deg - legs[j].heading_deg)));
  if (spread < kMinHeadingSpreadDeg) {
    r.why_not = "the steady legs' headings are within " + std::to_string(spread) +
                " deg of each other; a current needs them " + std::to_string(kMinHeadingSpreadDeg) +
                " deg apart or more";
    return r;
  }
  const auto m = static_cast<Eigen::Index>(legs.size());
  Eigen::MatrixXd a(m, 2);
  Eigen::VectorXd b(m);
  std::vector<std::array<double, 2>> v(legs.size());
  for (std::size_t i = 0; i < legs.size(); ++i) {
    v[i] = ground_velocity_mps(legs[i]);
    const double h = deg_to_rad(legs[i].heading_deg);
    // The heading's normal (to starboard): the speed through the water has no part along it.
    const double ne = std::cos(h), nn = -std::sin(h);
    const auto row = static_cast<Eigen::Index>(i);
    a.row(row) << ne, nn;
    b(row) = v[i][0] * ne + v[i][1] * nn;
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  if (qr.rank() < 2) {
    r.why_not = "the steady legs' headings do not determine both components of the current";
    return r;
  }
  const Eigen::Vector2d x = qr.solve(b);
  const Eigen::VectorXd res = a * x - b;
  const double dof = static_cast<double>(m - 2);
  // With 2 legs the fit is exact: no spread to report then.
  const double sigma2 = dof > 0.0 ? res.squaredNorm() / dof : 0.0;
  const Eigen::Matrix2d cov = sigma2 * (a.transpose() * a).inverse();
  double scale = 0.0;
  std::size_t scaled = 0;
  for (std::size_t i = 0; i < legs.size(); ++i) {
    if (!(legs[i].water_speed_mps > 0.0)) continue;
    const double h = deg_to_rad(legs[i].heading_deg);
    const double along = (v[i][0] - x(0)) * std::sin(h) + (v[i][1] - x(1)) * std::cos(h);
    scale += along / legs[i].water_speed_mps;
    ++scaled;
  }
  CurrentEstimate e;
  e.east_mps = x(0);
  e.north_mps = x(1);
  e.speed_scale = scaled ? scale / static_cast<double>(scaled) : 1.0;
  e.covariance = {cov(0, 0), cov(0, 1), cov(1, 1)};
  e.residual_rms_mps = std::sqrt(res.squaredNorm() / static_cast<double>(m));
  e.legs = legs.size();
  r.estimate = e;
  return r;
}

CurrentEstimateResult estimate_current_from_turns(const std::vector<TurnResidual>& turns) {
  CurrentEstimateResult r;
  std::vector<Eigen::Vector2d> per_turn;
  for (const TurnResidual& t : turns) {
    if (t.t_s.size() != t.residual_m.size())
      throw std::invalid_argument("a turn residual needs one time per point");
    double tt = 0.0;
    Eigen::Vector2d tr = Eigen::Vector2d::Zero();
    for (std::size_t i = 0; i < t.t_s.size(); ++i) {
      tt += t.t_s[i] * t.t_s[i];
      tr += t.t_s[i] * Eigen::Vector2d(t.residual_m[i].x_m, t.residual_m[i].y_m);
    }
    if (tt > 0.0) per_turn.push_back(tr / tt);
  }
  if (per_turn.size() < 2) {
    r.why_not = "a current from turns needs at least 2 turns with a time span; " +
                std::to_string(per_turn.size()) + " given";
    return r;
  }
  const auto n = static_cast<double>(per_turn.size());
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& c : per_turn)
    mean += c;
  mean /= n;
  Eigen::Matrix2d spread = Eigen::Matrix2d::Zero();
  for (const auto& c : per_turn)
    spread += (c - mean) * (c - mean).transpose();
  const Eigen::Matrix2d cov = spread / (n - 1.0) / n;
  CurrentEstimate e;
  e.east_mps = mean.x();
  e.north_mps = mean.y();
  e.covariance = {cov(0, 0), cov(0, 1), cov(1, 1)};
  e.residual_rms_mps = std::sqrt(spread.trace() / n);
  e.legs = per_turn.size();
  r.estimate = e;
  return r;
}

}  // namespace avk::kinematics
