#pragma once
// Numbers in text meant for people and files (messages, CSV cells, tables): one way to write
// them for the whole station.

#include <string>

namespace avk::kinematics {

// The shortest text that reads back as the same double, as JSON writes it ("1.0", "0.25").
std::string number_text(double v);

// A fixed number of decimals ("1.50"), for tables and messages an operator reads.
std::string fixed_text(double v, int decimals);

}  // namespace avk::kinematics
