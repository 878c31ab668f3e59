#pragma once
// Recorded turns as documents: a row of the listing, a turn with its trajectories, a harvest's
// report.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/harvest.hpp"
#include "app/missions.hpp"
#include "app/turn_views.hpp"

namespace avk::server {

nlohmann::json turn_row_json(const app::TurnView& t);
nlohmann::json harvest_report_json(const app::HarvestReport& r);
// A vehicle's missions harvested: {missions: [harvest_report_json, ...]}.
nlohmann::json harvest_reports_json(const std::vector<app::HarvestReport>& reports);
// A page of the turn listing: {items: [turn_row_json, ...], next}.
nlohmann::json turns_page_json(const app::Page<app::TurnView>& page);
nlohmann::json turn_json(const app::TurnDetail& t);  // with raw and normalised trajectories
std::string turns_csv(const std::vector<app::TurnView>& rows);

}  // namespace avk::server
