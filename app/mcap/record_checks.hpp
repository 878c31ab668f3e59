#pragma once
// What every read of an MCAP file shares: how a record and a chunk are named in an McapError, the
// size check of a chunk before anything of it is allocated, and which opcodes are known.

#include <cstdint>
#include <string>

#include "app/mcap/reader.hpp"

namespace avk::app::mcap {

// "Channel record at offset 123".
std::string where(const RecordView& r);

// "chunk at offset 123: ", the start of a chunk's errors.
std::string chunk_at(std::uint64_t offset);

// Refuses a chunk declaring more than max_bytes uncompressed, before anything of the chunk is
// allocated or inflated.
void check_chunk_size(const ChunkRecord& chunk, std::uint64_t chunk_offset,
                      std::uint64_t max_bytes);

// An opcode this reader knows; others are skipped as the format allows.
bool is_known(std::uint8_t op);

}  // namespace avk::app::mcap
