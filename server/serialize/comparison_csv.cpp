#include "server/serialize/comparison.hpp"

#include <algorithm>

#include "server/serialize/csv.hpp"
#include "server/serialize/values.hpp"

namespace avk::server {

namespace kin = avk::kinematics;

std::string predictive_csv(const app::Comparison& c) {
  std::string out =
      "speed_mps,dheading_deg,n_turns,span_m,avk_path_m,avk_path_sd_m,model_path_m,"
      "model_path_sd_m,instantaneous_path_m,instantaneous_path_sd_m,avk_yx_mse_m2,"
      "model_yx_mse_m2,instantaneous_yx_mse_m2,corridor_inside,corridor_total\n";
  const auto path = [](const kin::HeldOutScores* s) {
    if (!s) return std::string(",");
    const kin::MeanSd m = s->path();
    return num(m.mean) + ',' + num(m.sd);
  };
  const auto mse = [](const kin::HeldOutScores* s) {
    return s ? num(s->yx_mse().mean) : std::string();
  };
  for (const auto& cell : c.predictive) {
    const kin::HeldOutScores* m = cell.model ? &*cell.model : nullptr;
    out += num(cell.speed_mps) + ',' + num(cell.dheading_deg) + ',' + std::to_string(cell.n_turns) +
           ',' + num(cell.span_m) + ',' + path(&cell.avk) + ',' + path(m) + ',' +
           path(&cell.instantaneous) + ',' + mse(&cell.avk) + ',' + mse(m) + ',' +
           mse(&cell.instantaneous) + ',' +
           (cell.coverage ? std::to_string(cell.coverage->inside) : std::string()) + ',' +
           (cell.coverage ? std::to_string(cell.coverage->total) : std::string()) + '\n';
  }
  return out;
}

std::string comparison_csv(const app::Comparison& c) {
  const auto mse = [](const kin::MethodError* e) { return e ? num(e->mse_m2) : std::string(); };
  const auto pct = [](const kin::MethodError* e) {
    return e && e->improvement_pct ? num(*e->improvement_pct) : std::string();
  };
  const auto advance = [](const kin::MethodError* e) {
    return e ? num(e->advance_error_m) : std::string();
  };
  const auto transfer = [](const kin::MethodError* e) {
    return e ? num(e->transfer_error_m) : std::string();
  };
  std::string out =
      "speed_mps,dheading_deg,n_turns,outliers,avk_mse_m2,model_mse_m2,"
      "instantaneous_mse_m2,avk_improvement_pct,model_improvement_pct,"
      "avk_advance_error_m,model_advance_error_m,instantaneous_advance_error_m,"
      "avk_transfer_error_m,model_transfer_error_m,instantaneous_transfer_error_m\n";
  for (const auto& cell : c.cells) {
    const kin::MethodError* m = cell.model ? &*cell.model : nullptr;
    const kin::MethodError* a = &cell.avk;
    const kin::MethodError* i = &cell.instantaneous;
    out += num(cell.speed_mps) + ',' + num(cell.dheading_deg) + ',' + std::to_string(cell.n_turns) +
           ',' + std::to_string(std::count(cell.outlier.begin(), cell.outlier.end(), true)) + ',' +
           mse(a) + ',' + mse(m) + ',' + mse(i) + ',' + pct(a) + ',' + pct(m) + ',' + advance(a) +
           ',' + advance(m) + ',' + advance(i) + ',' + transfer(a) + ',' + transfer(m) + ',' +
           transfer(i) + '\n';
  }
  return out;
}

}  // namespace avk::server
