// Writes a gpsfake log of a traffic scenario's AIVDM to stdout (docs/ais.md): the static data once,
// then every contact's position report every interval_s seconds over duration_s.
//   make_ais_log examples/traffic-charles.json 600 2 > traffic.aivdm
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "sim/ais_traffic.hpp"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: make_ais_log <scenario.json> <duration_s> <interval_s>\n";
    return 2;
  }
  try {
    std::ifstream f(argv[1]);
    if (!f) throw std::runtime_error(std::string("cannot read ") + argv[1]);
    std::stringstream text;
    text << f.rdbuf();
    const auto traffic = avk::sim::AisTraffic::parse(text.str());
    const double duration_s = std::stod(argv[2]);
    const double interval_s = std::stod(argv[3]);
    if (!(interval_s > 0.0)) throw std::runtime_error("interval_s must be > 0");
    std::cout << "# " << argv[1] << ": every " << interval_s << " s over " << duration_s << " s\n";
    for (const auto& line : traffic.static_sentences())
      std::cout << line;
    for (double t = 0.0; t <= duration_s; t += interval_s)
      for (const auto& line : traffic.position_sentences(t))
        std::cout << line;
  } catch (const std::exception& e) {
    std::cerr << "make_ais_log: " << e.what() << "\n";
    return 1;
  }
}
