#pragma once
// The names a client needs to interpret the station's messages: every event kind with its
// severity, the helm modes and the link states. Sent in the live stream's hello and by
// GET /api/v1/meta, so the dashboard takes them from the server instead of keeping copies.

#include <nlohmann/json.hpp>

namespace avk::server {

// {"event_kinds": [{"kind", "severity"}, ...], "helm_modes": [...], "link_states": [...]}
nlohmann::json vocabulary_json();

}  // namespace avk::server
