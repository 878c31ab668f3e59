#pragma once
// The cells every CSV document is made of, written once so that a table quotes text and leaves
// a missing value empty the same way in every export.

#include <optional>
#include <string>

#include "kinematics/ckt.hpp"

namespace avk::server {

// RFC 4180: a cell with a comma, quote or line break is quoted, its quotes doubled.
std::string csv_cell(const std::string& s);
// A number as num() writes it; empty when there is none.
std::string optional_csv(const std::optional<double>& v);
// The mean, or the spread, of a mean with its spread; empty when there is none.
std::string mean_csv(const std::optional<kinematics::MeanSd>& v);
std::string sd_csv(const std::optional<kinematics::MeanSd>& v);

}  // namespace avk::server
