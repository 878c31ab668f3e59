#pragma once
// The station's database as the use cases reach it, and its rows as they answer them. Only app/
// includes this: front ends call the use cases, which answer in view types, so no front end holds a
// store (the layer rules forbid it).

#include <memory>
#include <string>

#include "app/store_views.hpp"
#include "store/store.hpp"

namespace avk::app {

class Context;

// This thread's connection to the context's database: SQLite connections are not shared between
// threads, and each thread opens its own on first use.
store::Store& store_of(Context& ctx);

// Opens the database as this station: the missions it creates record station_id()
// (app/station_identity.hpp).
std::unique_ptr<store::Store> open_station_store(const std::string& db);

}  // namespace avk::app
