#pragma once
// The store's rows as the use cases answer them (app/*_view(s).hpp) and read them: the one place
// a row becomes a view or a domain value, used by app/ only, so that front ends never see a store
// type.

#include <vector>

#include "app/current_view.hpp"
#include "app/mission_views.hpp"
#include "app/model_view.hpp"
#include "app/turn_views.hpp"
#include "store/store.hpp"
#include "vehicle/alog.hpp"

namespace avk::app {

MissionStatus view_of(store::MissionStatus s);
store::MissionStatus to_store(MissionStatus s);
MissionView view_of(const store::Mission& m);
TurnCounts view_of(const store::TurnCounts& c);
MissionEventView view_of(const store::MissionEvent& e);
TrackPoint view_of(const store::NavPageRow& r);
TurnView view_of(const store::TurnRow& t);
TurnDetail view_of(store::StoredTurn t);
CurrentView view_of(const store::StoredCurrent& c);
ModelView view_of(const store::StoredModel& m);

// Stored navigation rows as the guided log the harvester reads (navigation with the desired
// heading and speed in force).
std::vector<vehicle::GuidedNav> guided_log(const std::vector<store::NavRow>& rows);

store::TurnFilter to_store(const TurnQuery& q);
store::StoredModel to_store(const ModelView& m);

template <class Row>
auto views_of(const std::vector<Row>& rows) {
  std::vector<decltype(view_of(rows.front()))> out;
  out.reserve(rows.size());
  for (const auto& r : rows)
    out.push_back(view_of(r));
  return out;
}

}  // namespace avk::app
