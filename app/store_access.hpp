#pragma once
// The station's database as the use cases reach it, and its rows as they answer them. Only app/
// includes this: front ends call the use cases, which answer in view types, so no front end holds a
// store (the layer rules forbid it).

#include "app/store_access.hpp"
#include "app/store_views.hpp"
#include "store/store.hpp"

namespace avk::app {

class Context;

// This thread's connection to the context's database: SQLite connections are not shared between
// threads, and each thread opens its own on first use.
store::Store& store_of(Context& ctx);

}  // namespace avk::app
