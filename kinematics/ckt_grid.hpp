#pragma once
// How the CKT code compares grid values and writes them in messages, shared by building,
// querying and materialising a table.

#include <string>

namespace avk::kinematics {

// Two speeds or heading changes closer than this are the same grid line: values that went
// through text or arithmetic still find their own row and column.
inline constexpr double kCktGridEps = 1e-9;

// A grid value as the table's messages write it (six significant digits).
std::string ckt_value_text(double v);

}  // namespace avk::kinematics
