#pragma once
// MCAP files built byte by byte, for what the station's writer never writes: damaged files for
// the reader's tests, and zstd bombs for those tests and bench_exhaustion.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

#include "app/mcap/records.hpp"

namespace avk::testing::mcap_bytes {

using app::mcap::kMagic;
using app::mcap::Opcode;

// Little-endian fields.
template <class T>
std::string le(T v) {
  std::string out;
  for (std::size_t i = 0; i < sizeof(T); ++i)
    out.push_back(static_cast<char>(v >> (8 * i)));
  return out;
}
inline std::string str(const std::string& s) {
  return le<std::uint32_t>(static_cast<std::uint32_t>(s.size())) + s;
}
inline std::string record(Opcode op, const std::string& content) {
  return std::string(1, static_cast<char>(op)) + le<std::uint64_t>(content.size()) + content;
}

// Magic, Header, `data`, a Data End and Footer without CRCs or summary, Magic.
inline std::string hand_built_file(const std::string& data) {
  return std::string(kMagic) + record(Opcode::header, str("") + str("hand")) + data +
         record(Opcode::data_end, le<std::uint32_t>(0)) +
         record(Opcode::footer,
                le<std::uint64_t>(0) + le<std::uint64_t>(0) + le<std::uint32_t>(0)) +
         std::string(kMagic);
}

// A zstd frame of `size` zero bytes that declares its size, made of RLE blocks by hand: 4 bytes
// per 128 KiB, so 1 GiB takes 32 KiB, as a bomb packs it.
inline std::string zero_frame(std::uint64_t size) {
  // Magic, then a frame header descriptor of 0xE0: an 8-byte content size, a single segment.
  std::string f = le<std::uint32_t>(0xFD2FB528u) + "\xE0" + le<std::uint64_t>(size);
  constexpr std::uint64_t kBlock = 128 * 1024;  // the largest block zstd allows
  for (std::uint64_t left = size; left > 0;) {
    const std::uint64_t n = std::min(left, kBlock);
    left -= n;
    // Block header: last-block bit, block type 1 (RLE), then the size; the byte to repeat.
    const auto header = static_cast<std::uint32_t>(n << 3 | 1u << 1 | (left == 0 ? 1u : 0u));
    f += le<std::uint32_t>(header).substr(0, 3) + std::string(1, '\0');
  }
  return f;
}

// A chunk whose records are `size` zero bytes, honestly declared (no CRC: 0 is "not checked").
// Zeros read as records of opcode 0 and length 0, which a reader skips, so a size that is a
// multiple of 9 makes a chunk a reader without limits takes whole.
inline std::string zero_chunk(std::uint64_t size) {
  const std::string frame = zero_frame(size);
  return record(Opcode::chunk, le<std::uint64_t>(0) + le<std::uint64_t>(0) +
                                   le<std::uint64_t>(size) + le<std::uint32_t>(0) + str("zstd") +
                                   le<std::uint64_t>(frame.size()) + frame);
}

}  // namespace avk::testing::mcap_bytes
