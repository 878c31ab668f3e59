#pragma once
// The position band's coverage on missions the table never saw as a document
// (`avk band coverage --format json`).

#include <nlohmann/json.hpp>

#include "app/band_coverage.hpp"

namespace avk::server {

// The missions compared, the share asked, the coverage during and after the turns and overall,
// the along- and cross-track errors, and the coverage by speed.
nlohmann::json band_coverage_json(const app::BandCoverage& c);

}  // namespace avk::server
