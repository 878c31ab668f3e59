// Writes examples/sample-turns.txt: synthetic turns (straight lead-in + constant-radius arc,
// 5 cm position noise, 0.5 deg compass noise) over the thesis' Figure 4-1 grid, three a cell,
// alternating sides, started from scattered poses. Stands in for mission data in the examples.
#include <iostream>

#include "kinematics/turn_text.hpp"
#include "support/synthetic_turns.hpp"

int main() {
  std::cout << "# synthetic turns: lead-in 0.5+u m, radius 1+2u m, noise 0.05 m / 0.5 deg\n";
  for (const auto& t : avk::testing::thesis_grid_turns(3, 0.25, 0.05, 0.5)) {
    std::cout << avk::kinematics::to_text_record(t) << "\n";
  }
}
