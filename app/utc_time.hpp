#pragma once
// The wall clock as records carry it: ISO 8601 UTC to the second ("2026-12-01T20:06:16Z").

#include <string>

namespace avk::app {

std::string utc_now_iso8601();

}  // namespace avk::app
