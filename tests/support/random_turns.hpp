#pragma once
// Helpers shared by the turn serialisation tests (text record and JSON): random turns drawn from
// a per-format alphabet of awkward doubles and string pieces, bit-exact comparison, the
// documented example turn, parse-error checks and the mutation-robustness loop.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <limits>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "kinematics/parse_error.hpp"
#include "kinematics/turn_sequence.hpp"

namespace avk::testing {

// What a format's writer finds hard: special doubles and string pieces to build values from.
struct RandomTurnAlphabet {
  std::span<const double> special_doubles;
  std::span<const std::string> string_pieces;
};

inline double random_double(std::mt19937_64& rng, std::span<const double> specials) {
  switch (rng() % 6) {
    case 0: {  // any finite bit pattern: every exponent, subnormals, both signs
      double d = 0.0;
      do {
        d = std::bit_cast<double>(static_cast<std::uint64_t>(rng()));
      } while (!std::isfinite(d));
      return d;
    }
    case 1:  // subnormal
      return std::bit_cast<double>(static_cast<std::uint64_t>(rng()) & 0x800FFFFFFFFFFFFFull);
    case 2:
      return specials[rng() % specials.size()];
    case 3:  // integral values, which writers are tempted to print as integers
      return static_cast<double>(static_cast<int>(rng() % 2001) - 1000);
    default:
      return std::uniform_real_distribution<double>(-400.0, 400.0)(rng);
  }
}

inline std::string random_string(std::mt19937_64& rng, std::span<const std::string> pieces) {
  std::string s;
  const std::size_t n = rng() % 10;
  for (std::size_t i = 0; i < n; ++i)
    s += pieces[rng() % pieces.size()];
  return s;
}

inline kinematics::TurnSequence random_turn(std::mt19937_64& rng,
                                            const RandomTurnAlphabet& alphabet) {
  const auto number = [&] { return random_double(rng, alphabet.special_doubles); };
  const auto text = [&] { return random_string(rng, alphabet.string_pieces); };
  kinematics::TurnMeta m;
  m.vehicle_id = text();
  m.mission_id = text();
  for (double* d : {&m.commanded_speed_mps, &m.goal_dheading_deg, &m.observed_dheading_deg,
                    &m.initial_heading_deg, &m.initial_speed_mps, &m.start_time_s, &m.end_time_s})
    *d = number();
  m.status = static_cast<kinematics::TurnStatus>(rng() % 3);
  m.status_reason = text();
  m.normalized = rng() % 2 == 1;
  std::vector<kinematics::TurnSample> samples(rng() % 12);
  for (auto& s : samples)
    s = {number(), number(), number(), number(), number()};  // braced: evaluated left to right
  kinematics::TurnSequence turn(m, samples);
  const std::size_t warnings = rng() % 4;
  for (std::size_t i = 0; i < warnings; ++i)
    turn.add_warning(text());
  return turn;
}

// Calls check(turn) on `count` random turns drawn with `seed`, stopping at the first failure.
template <class Check>
void for_random_turns(std::uint64_t seed, int count, const RandomTurnAlphabet& alphabet,
                      Check check) {
  std::mt19937_64 rng(seed);
  for (int i = 0; i < count; ++i) {
    check(random_turn(rng, alphabet));
    if (::testing::Test::HasFailure()) break;
  }
}

// operator== treats -0.0 == 0.0; a record must keep the sign as well, so compare the bits.
inline std::vector<std::uint64_t> all_bits(const kinematics::TurnSequence& t) {
  std::vector<std::uint64_t> out;
  const auto& m = t.meta();
  for (double d : {m.commanded_speed_mps, m.goal_dheading_deg, m.observed_dheading_deg,
                   m.initial_heading_deg, m.initial_speed_mps, m.start_time_s, m.end_time_s})
    out.push_back(std::bit_cast<std::uint64_t>(d));
  for (const auto& s : t.samples()) {
    for (double d : {s.t_s, s.x_m, s.y_m, s.heading_deg, s.speed_mps})
      out.push_back(std::bit_cast<std::uint64_t>(d));
  }
  return out;
}

// write(turn) must be one line that parses back to the same turn, bit for bit, and writes again
// to the same bytes.
template <class Parse, class Write>
void expect_exact_round_trip(const kinematics::TurnSequence& turn, Parse parse, Write write) {
  const std::string written = write(turn);
  EXPECT_EQ(written.find('\n'), std::string::npos);
  const kinematics::TurnSequence back = parse(written);
  EXPECT_EQ(back, turn) << written;
  EXPECT_EQ(all_bits(back), all_bits(turn)) << written;
  EXPECT_EQ(back.warnings(), turn.warnings()) << written;
  EXPECT_EQ(write(back), written);
}

// The turn both formats document as their example.
inline kinematics::TurnSequence example_turn() {
  kinematics::TurnMeta m;
  m.vehicle_id = "m200 alpha";
  m.mission_id = "charles;2024";
  m.commanded_speed_mps = 1.5;
  m.goal_dheading_deg = 90.0;
  m.observed_dheading_deg = 88.5;
  m.initial_heading_deg = 45.0;
  m.initial_speed_mps = 1.5;
  m.start_time_s = 100.0;
  m.end_time_s = 101.0;
  kinematics::TurnSequence turn(m, {{100.0, 0.0, 0.0, 45.0, 1.5},
                                    {100.5, 0.53, 0.53, 60.25, 1.49},
                                    {101.0, 1.1, 0.9, 133.5, 1.5}});
  turn.add_warning("dropped 1 x");
  return turn;
}

// The example turn with the given status, and `reason` as its status_reason unless it is ok.
inline kinematics::TurnSequence example_turn_with_status(kinematics::TurnStatus status,
                                                         const std::string& reason) {
  kinematics::TurnSequence turn = example_turn();
  turn.meta().status = status;
  turn.meta().status_reason = status == kinematics::TurnStatus::ok ? "" : reason;
  return turn;
}

// The example turn with awkward doubles in all its metadata but end_time_s, which each format's
// test picks: negative zero, the smallest and largest, and ones needing many digits.
inline kinematics::TurnSequence example_turn_with_special_doubles() {
  kinematics::TurnSequence turn = example_turn();
  turn.meta().commanded_speed_mps = -0.0;
  turn.meta().goal_dheading_deg = 1e-300;
  turn.meta().observed_dheading_deg = 0.1;
  turn.meta().initial_heading_deg = std::numeric_limits<double>::max();
  turn.meta().initial_speed_mps = std::numeric_limits<double>::denorm_min();
  turn.meta().start_time_s = 1.7e9 + 0.123456789;
  return turn;
}

// Replaces the first occurrence of `from` (which must exist) in `s`.
inline std::string replace_first(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

inline std::size_t offset_of(const std::string& haystack, const std::string& needle) {
  const auto at = haystack.find(needle);
  EXPECT_NE(at, std::string::npos) << needle;
  return at;
}

// parse(input) must throw a ParseError naming `field` at byte `position`.
template <class Parse>
void expect_parse_error_from(Parse parse, const std::string& input, const std::string& field,
                             std::size_t position) {
  try {
    parse(input);
    ADD_FAILURE() << "accepted: " << input;
  } catch (const kinematics::ParseError& e) {
    EXPECT_EQ(e.field(), field) << e.what() << "\n  in: " << input;
    EXPECT_EQ(e.position(), position) << e.what() << "\n  in: " << input;
  }
}

// ---- mutation robustness: a cheap stand-in for the libFuzzer target in tests/fuzz ----

// Applies 1 to 4 random edits; `inserts` are the separators and nasty tokens of the format.
inline std::string mutate(std::string s, std::mt19937_64& rng,
                          std::span<const std::string> inserts) {
  const int edits = 1 + static_cast<int>(rng() % 4);
  for (int e = 0; e < edits; ++e) {
    const std::size_t at = s.empty() ? 0 : rng() % (s.size() + 1);
    const std::size_t len = 1 + rng() % 16;
    switch (rng() % 6) {
      case 0:  // flip a byte or a bit
        if (at < s.size()) {
          s[at] =
              rng() % 2 ? static_cast<char>(rng()) : static_cast<char>(s[at] ^ (1 << (rng() % 8)));
        }
        break;
      case 1:  // delete a range
        if (at < s.size()) s.erase(at, len);
        break;
      case 2:  // duplicate a range
        if (at < s.size()) s.insert(rng() % (s.size() + 1), s.substr(at, len));
        break;
      case 3:  // insert a separator or a nasty token
        s.insert(at, inserts[rng() % inserts.size()]);
        break;
      case 4:  // truncate
        s.resize(at);
        break;
      default:  // change a digit, which often keeps the input valid
        for (std::size_t k = at; k < s.size(); ++k) {
          if (s[k] >= '0' && s[k] <= '9') {
            s[k] = static_cast<char>('0' + rng() % 10);
            break;
          }
        }
        break;
    }
  }
  return s;
}

inline std::string printable(const std::string& s) {
  std::string out;
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u > 0x7E) {
      static constexpr char kHex[] = "0123456789ABCDEF";
      out += "\\x";
      out += kHex[u >> 4];
      out += kHex[u & 0x0F];
    } else {
      out += c;
    }
  }
  return out;
}

// Each parser must either give a turn that writes and reads back identically, or throw ParseError.
// Returns true when the input was accepted.
template <class Parse, class Write>
bool check_parser(const std::string& input, Parse parse, Write write) {
  try {
    const kinematics::TurnSequence turn = parse(input);
    const std::string again = write(turn);
    const kinematics::TurnSequence back = parse(again);
    EXPECT_EQ(back, turn) << printable(input);
    EXPECT_EQ(back.warnings(), turn.warnings()) << printable(input);
    EXPECT_EQ(write(back), again) << printable(input);
    return true;
  } catch (const kinematics::ParseError&) {
    return false;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "escaped: " << e.what() << "\n  input: " << printable(input);
  } catch (...) {
    ADD_FAILURE() << "escaped a non-std exception\n  input: " << printable(input);
  }
  return false;
}

struct MutationOutcome {
  int accepted = 0;  // by the format under test
  int rejected = 0;
};

// Mutates `rounds` inputs drawn from `seeds` plus eight random turns written by `write`. Checks
// each with the format under test (parse, write), counting its outcomes, and with the other format
// (other_parse, other_write), which must also either accept or throw ParseError. Stops at the first
// failure.
template <class Parse, class Write, class OtherParse, class OtherWrite>
MutationOutcome run_mutations(std::uint64_t rng_seed, std::vector<std::string> seeds,
                              const RandomTurnAlphabet& alphabet,
                              std::span<const std::string> inserts, int rounds, Parse parse,
                              Write write, OtherParse other_parse, OtherWrite other_write) {
  std::mt19937_64 rng(rng_seed);
  for (int i = 0; i < 8; ++i)
    seeds.push_back(write(random_turn(rng, alphabet)));
  MutationOutcome outcome;
  for (int i = 0; i < rounds; ++i) {
    const std::string input = mutate(seeds[rng() % seeds.size()], rng, inserts);
    if (check_parser(input, parse, write)) {
      ++outcome.accepted;
    } else {
      ++outcome.rejected;
    }
    check_parser(input, other_parse, other_write);
    if (::testing::Test::HasFailure()) break;
  }
  return outcome;
}

}  // namespace avk::testing
