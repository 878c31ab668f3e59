#pragma once
// A turn's forms as the turns table holds them: the JSON documents, and the packed samples with the
// samples-free metadata that let the CKT load thousands of turns without parsing their JSON.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "kinematics/turn_sequence.hpp"

namespace avk::store::sql {

// A sample is 5 doubles (t_s, x_m, y_m, heading_deg, speed_mps), each 8 bytes little-endian
// whatever the host, so a database file moves between machines.
std::vector<unsigned char> pack_samples(const std::vector<kinematics::TurnSample>& samples);
// Throws StoreError naming the turn for bytes that are not whole samples.
std::vector<kinematics::TurnSample> unpack_samples(std::int64_t turn_id,
                                                   std::span<const unsigned char> bytes);

// The turn without its samples: metadata and warnings through the same serialiser as the full
// document, so whatever TurnMeta holds survives the packed path too.
std::string meta_json(const kinematics::TurnSequence& turn);
// The turn back from its metadata document and packed samples.
kinematics::TurnSequence unpack_turn(std::int64_t turn_id, const std::string& meta_json,
                                     std::span<const unsigned char> samples);

// Throws StoreError naming the turn and the column when the stored JSON is corrupt.
kinematics::TurnSequence parse_stored_turn(std::int64_t id, const std::string& column,
                                           const std::string& text);

// A turn's documents as stored: the raw JSON and, when it has one, the normalised JSON with its
// packed samples (the CKT's fast path).
struct TurnDocuments {
  std::string raw_json;
  std::optional<std::string> normalized_json, normalized_meta;
  std::vector<unsigned char> normalized_samples;
};
TurnDocuments normalized_documents(std::string raw_json, const kinematics::TurnSequence& norm);

// The water-frame form of one turn (by turn id), packed like the normalised form.
using PackedWaterTurn = std::tuple<std::int64_t, std::string, std::vector<unsigned char>>;
PackedWaterTurn pack_water_turn(std::int64_t id, const kinematics::TurnSequence& turn);

}  // namespace avk::store::sql
