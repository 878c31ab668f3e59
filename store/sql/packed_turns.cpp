#include "store/sql/packed_turns.hpp"

#include <bit>
#include <exception>
#include <limits>
#include <utility>

#include "kinematics/turn_json.hpp"
#include "store/database.hpp"

namespace avk::store::sql {

namespace {

constexpr std::size_t kPackedSampleBytes = 5 * sizeof(std::uint64_t);
static_assert(sizeof(double) == sizeof(std::uint64_t) && std::numeric_limits<double>::is_iec559);

}  // namespace

std::vector<unsigned char> pack_samples(const std::vector<kinematics::TurnSample>& samples) {
  std::vector<unsigned char> out(samples.size() * kPackedSampleBytes);
  unsigned char* p = out.data();
  const auto put = [&p](double v) {
    const auto bits = std::bit_cast<std::uint64_t>(v);
    for (int b = 0; b < 8; ++b)
      *p++ = static_cast<unsigned char>(bits >> (8 * b));
  };
  for (const auto& s : samples) {
    put(s.t_s);
    put(s.x_m);
    put(s.y_m);
    put(s.heading_deg);
    put(s.speed_mps);
  }
  return out;
}

std::vector<kinematics::TurnSample> unpack_samples(std::int64_t turn_id,
                                                   std::span<const unsigned char> bytes) {
  if (bytes.size() % kPackedSampleBytes != 0)
    throw StoreError("turn " + std::to_string(turn_id) +
                     ": stored normalized_samples is corrupt (" + std::to_string(bytes.size()) +
                     " bytes, not whole samples)");
  const unsigned char* p = bytes.data();
  const auto get = [&p] {
    std::uint64_t bits = 0;
    for (int b = 0; b < 8; ++b)
      bits |= static_cast<std::uint64_t>(*p++) << (8 * b);
    return std::bit_cast<double>(bits);
  };
  std::vector<kinematics::TurnSample> out(bytes.size() / kPackedSampleBytes);
  for (auto& s : out) {
    s.t_s = get();
    s.x_m = get();
    s.y_m = get();
    s.heading_deg = get();
    s.speed_mps = get();
  }
  return out;
}

std::string meta_json(const kinematics::TurnSequence& turn) {
  kinematics::TurnSequence head(turn.meta(), {});
  for (const auto& w : turn.warnings())
    head.add_warning(w);
  return kinematics::to_json_string(head);
}

kinematics::TurnSequence unpack_turn(std::int64_t turn_id, const std::string& meta_json,
                                     std::span<const unsigned char> samples) {
  kinematics::TurnSequence head = parse_stored_turn(turn_id, "normalized_meta_json", meta_json);
  kinematics::TurnSequence turn(head.meta(), unpack_samples(turn_id, samples));
  for (const auto& w : head.warnings())
    turn.add_warning(w);
  return turn;
}

kinematics::TurnSequence parse_stored_turn(std::int64_t id, const std::string& column,
                                           const std::string& text) {
  try {
    return kinematics::parse_turn_json(text);
  } catch (const std::exception& e) {
    throw StoreError("turn " + std::to_string(id) + ": stored " + column +
                     " is corrupt: " + e.what());
  }
}

TurnDocuments normalized_documents(std::string raw_json, const kinematics::TurnSequence& norm) {
  return {std::move(raw_json), kinematics::to_json_string(norm), meta_json(norm),
          pack_samples(norm.samples())};
}

PackedWaterTurn pack_water_turn(std::int64_t id, const kinematics::TurnSequence& turn) {
  return {id, meta_json(turn), pack_samples(turn.samples())};
}

}  // namespace avk::store::sql
