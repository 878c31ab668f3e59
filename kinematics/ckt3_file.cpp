#include "kinematics/ckt3_file.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "kinematics/ckt_file.hpp"
#include "kinematics/parse_error.hpp"

namespace avk::kinematics {

using nlohmann::json;

namespace {

// The measured cells of a slice: what a 2-D table of its turns would hold.
Ckt measured_part(const YawRateSlice& s) {
  std::vector<CktCell> cells;
  for (std::size_t i = 0; i < s.table.cells().size(); ++i)
    if (s.sources[i] == CellSource::measured) cells.push_back(s.table.cells()[i]);
  Ckt t = Ckt::from_cells(s.table.grid(), std::move(cells), s.table.options());
  t.vehicle_id = s.table.vehicle_id;
  t.vehicle_length_m = s.table.vehicle_length_m;
  t.created_utc = s.table.created_utc;
  return t;
}

[[noreturn]] void fail(const std::string& field, const std::string& message) {
  throw ParseError(field, 0, message);
}

}  // namespace

json yaw_rate_ckt_to_json(const YawRateCkt& table) {
  if (table.slices().empty()) throw std::invalid_argument("the table has no slices");
  const YawRateSlice* steady = table.steady();
  json doc = ckt_to_json(measured_part(steady ? *steady : table.slices().front()));
  json slices = json::array();
  for (const YawRateSlice& s : table.slices()) {
    json cells = ckt_to_json(s.table)["cells"];
    // ckt_to_json writes the cells with data in table order; their sources in the same order.
    std::size_t k = 0;
    for (std::size_t i = 0; i < s.table.cells().size(); ++i)
      if (s.table.cells()[i].has_data()) cells[k++]["source"] = to_string(s.sources[i]);
    slices.push_back(
        {{"initial_yaw_rate_dps", s.initial_yaw_rate_dps}, {"cells", std::move(cells)}});
  }
  doc["yaw_rate_slices"] = std::move(slices);
  return doc;
}

std::string yaw_rate_ckt_to_json_string(const YawRateCkt& table) {
  return yaw_rate_ckt_to_json(table).dump() + "\n";
}

YawRateCkt yaw_rate_ckt_from_json(const json& doc) {
  Ckt base = ckt_from_json(doc);  // checks everything but the slices
  const auto it = doc.find("yaw_rate_slices");
  if (it == doc.end()) return YawRateCkt::from_table(std::move(base));
  const json& slices_json = *it;
  if (!slices_json.is_array() || slices_json.empty())
    fail("/yaw_rate_slices", "expected a non-empty array of slices");
  if (slices_json.size() > kCktMaxYawRateSlices)
    fail("/yaw_rate_slices", "at most " + std::to_string(kCktMaxYawRateSlices) + " slices");
  std::vector<YawRateSlice> slices;
  for (std::size_t k = 0; k < slices_json.size(); ++k) {
    const std::string path = "/yaw_rate_slices/" + std::to_string(k);
    const json& sj = slices_json[k];
    if (!sj.is_object()) fail(path, "expected an object");
    for (const auto& item : sj.items())
      if (item.key() != "initial_yaw_rate_dps" && item.key() != "cells")
        fail(path + "/" + item.key(), "unknown field '" + item.key() + "'");
    const auto rate = sj.find("initial_yaw_rate_dps");
    if (rate == sj.end() || !rate->is_number() || !std::isfinite(rate->get<double>()) ||
        std::abs(rate->get<double>()) > 90.0)
      fail(path + "/initial_yaw_rate_dps", "expected a yaw rate within [-90, 90] deg/s");
    const auto cells = sj.find("cells");
    if (cells == sj.end() || !cells->is_array()) fail(path + "/cells", "expected an array");
    // Each slice is read as the document with its own cells, so a cell is checked as in `cells`.
    json sub = doc;
    sub.erase("yaw_rate_slices");
    sub["cells"] = json::array();
    std::vector<std::pair<std::size_t, CellSource>> given;  // cell index in sub -> source
    for (std::size_t i = 0; i < cells->size(); ++i) {
      json cell = (*cells)[i];
      CellSource src = CellSource::measured;
      if (cell.is_object() && cell.contains("source")) {
        const json& sv = cell["source"];
        const auto parsed =
            sv.is_string() ? cell_source_from_string(sv.get<std::string>()) : std::nullopt;
        if (!parsed || *parsed == CellSource::interpolated)
          fail(path + "/cells/" + std::to_string(i) + "/source", "expected measured or model");
        src = *parsed;
        cell.erase("source");
      }
      given.push_back({i, src});
      sub["cells"].push_back(std::move(cell));
    }
    Ckt table;
    try {
      table = ckt_from_json(sub);
    } catch (const ParseError& e) {
      const std::string field = e.field().starts_with("/cells") ? path + e.field() : e.field();
      throw ParseError(field, e.position(), e.message());
    }
    std::vector<CellSource> sources(table.cells().size(), CellSource::interpolated);
    const std::size_t nd = table.grid().dheadings_deg.size();
    for (const auto& [i, src] : given) {
      const json& cj = (*cells)[i];
      const auto si = table.speed_index(cj["speed_mps"].get<double>());
      const auto di = table.dheading_index(cj["dheading_deg"].get<double>());
      if (si && di) sources[*si * nd + *di] = src;
    }
    slices.push_back({rate->get<double>(), std::move(table), std::move(sources)});
  }
  try {
    return YawRateCkt::from_slices(std::move(slices));
  } catch (const std::invalid_argument& e) {
    fail("/yaw_rate_slices", e.what());
  }
}

YawRateCkt parse_yaw_rate_ckt_json(std::string_view text) {
  return yaw_rate_ckt_from_json(parse_ckt_document(text));
}

}  // namespace avk::kinematics
