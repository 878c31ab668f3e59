#pragma once
// The attacks bench_exhaustion runs against a spawned `avk serve`, one a phase: slow bodies, slow
// connections, oversized bodies, MCAP bombs and heavy reads. Each runs until its time is up and
// returns notes on how the server answered.

#include <chrono>
#include <filesystem>
#include <set>
#include <string>

namespace avk::bench {

inline constexpr const char* kToken = "bench-exhaustion-token-0123456789-abcdefghijKLMN";
inline constexpr const char* kImport = "/api/v1/vehicles/sim-usim/ckt/import";

// 25 POSTs to the CKT import without a token and 25 with it, each body sent at one byte per 10 s.
std::string slow_bodies(unsigned short port, std::chrono::seconds length);
// `count` connections, each with a partial request header and one more byte per 10 s.
std::string slow_connections(unsigned short port, int count, std::chrono::seconds length);
// 8 parallel unauthenticated 62 MB bodies to the CKT import, sent as fast as the server takes
// them.
std::string oversized_bodies(unsigned short port);

// Rounds of four `avk import mcap` at once of each bomb into the server's database, until
// `length` has passed; the notes say how the imports were answered. `refused_small` is cleared
// unless every import failed naming a chunk and stayed under 100 MB.
std::string mcap_bombs(const std::filesystem::path& dir, std::chrono::seconds length,
                       bool& refused_small);

// n clients send heavy reads back to back until the time is up, each from its own address when
// `spread` (127.0.0.2, .3, ...), else all from 127.0.0.1. `without` names kinds left out.
std::string heavy_reads(unsigned short port, int n, bool spread, std::chrono::seconds length,
                        const std::set<std::string>& without);

}  // namespace avk::bench
