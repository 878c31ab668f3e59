#pragma once
// A MOOS-IvP .alog as a mission of the station: its navigation (helm state unknown, stored as
// IMPORTED) and its turns, from the log's turn records or, when it has none, extracted from the
// steps of DESIRED_HEADING. Malformed lines are counted and named, never fatal.

#include <cstdint>
#include <istream>
#include <optional>
#include <string>

#include "app/harvest.hpp"
#include "app/mission_views.hpp"
#include "app/result.hpp"
#include "kinematics/turn_sequence.hpp"
#include "mission/turn_extractor.hpp"
#include "vehicle/alog.hpp"

namespace avk::app {

class Context;

struct AlogImportRequest {
  std::string source;        // the log's name, for the mission's record and its status reason
  std::string mission_name;  // the mission's name (the file's name)
  std::string vehicle_id;
  vehicle::AlogNames names;
  mission::TurnExtractorOptions extraction;
  // Harvest the log's navigation (app/harvest.hpp) instead of storing the extracted turns as
  // collection turns: its turns are stored as harvested, with their quality and the counts.
  bool harvest = false;
};

struct AlogImportReport {
  std::int64_t mission_id = 0;
  vehicle::AlogStats reader;
  vehicle::AlogNavStats nav;
  vehicle::AlogProblems malformed;
  std::size_t nav_stored = 0;
  TurnCounts from_records, from_extraction;
  std::optional<HarvestReport> harvest;  // with request.harvest
};

// Stores the log as a mission of the vehicle (running while it imports, so an import that dies
// midway is listed as interrupted, then done). invalid_argument for an empty vehicle id.
Result<AlogImportReport> import_alog(Context& ctx, std::istream& log,
                                     const AlogImportRequest& request);

}  // namespace avk::app
