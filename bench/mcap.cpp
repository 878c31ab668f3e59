// MCAP export and import throughput: N JSON messages of about 300 bytes (a pose and a navigation
// message per sample, as a mission export writes them) in 1 MiB chunks, zstd and uncompressed.
// bytes_per_second counts message payload bytes; file_bytes is the size of the written file.

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "app/mcap/reader.hpp"
#include "app/mcap/writer.hpp"

namespace {

using namespace avk::app::mcap;

const std::vector<std::string>& payloads(std::size_t n) {
  static std::vector<std::string> v;
  for (std::size_t i = v.size(); i < n; ++i) {
    const double x = 0.37 * static_cast<double>(i);
    std::string s =
        R"({"timestamp":{"sec":)" + std::to_string(1700000000 + i / 5) + R"(,"nsec":)" +
        std::to_string((i % 5) * 200000000) + R"(},"frame_id":"grid","pose":{"position":{"x":)" +
        std::to_string(x) + R"(,"y":)" + std::to_string(-x * 0.5) +
        R"(,"z":0},"orientation":{"x":0,"y":0,"z":)" + std::to_string(x / 1000.0) +
        R"(,"w":0.99}},"heading_deg":)" + std::to_string(i % 360) +
        R"(,"speed_mps":1.25,"desired_speed_mps":1.5,"yaw_rate_dps":0.25,"desired_heading_deg":90,"helm_mode":"survey"})";
    v.push_back(std::move(s));
  }
  return v;
}

std::string write_file(Compression compression, std::size_t n) {
  Writer w(WriterOptions{compression, std::size_t{1} << 20, "", "avk-station"});
  const std::uint16_t schema = w.add_schema("foxglove.PoseInFrame", "jsonschema", "{}");
  const std::uint16_t pose = w.add_channel(schema, "/vehicle/pose", "json");
  const std::uint16_t nav = w.add_channel(0, "/vehicle/navigation", "json");
  const std::vector<std::string>& data = payloads(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t t = 1'700'000'000'000'000'000ull + i * 100'000'000ull;
    w.add_message(i % 2 == 0 ? pose : nav, t, t, data[i]);
  }
  return w.finish();
}

std::size_t payload_bytes(std::size_t n) {
  std::size_t total = 0;
  for (std::size_t i = 0; i < n; ++i)
    total += payloads(n)[i].size();
  return total;
}

void BM_McapWrite(benchmark::State& state) {
  const auto compression = static_cast<Compression>(state.range(0));
  const auto n = static_cast<std::size_t>(state.range(1));
  payloads(n);
  std::size_t file_bytes = 0;
  for (auto _ : state) {
    const std::string file = write_file(compression, n);
    file_bytes = file.size();
    benchmark::DoNotOptimize(file.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * payload_bytes(n)));
  state.counters["file_bytes"] = static_cast<double>(file_bytes);
  state.counters["payload_bytes"] = static_cast<double>(payload_bytes(n));
  state.SetLabel(compression == Compression::zstd ? "zstd" : "none");
}
BENCHMARK(BM_McapWrite)
    ->Args({static_cast<int>(Compression::none), 100000})
    ->Args({static_cast<int>(Compression::zstd), 100000})
    ->Unit(benchmark::kMillisecond);

void BM_McapRead(benchmark::State& state) {
  const auto compression = static_cast<Compression>(state.range(0));
  const auto n = static_cast<std::size_t>(state.range(1));
  const std::string file = write_file(compression, n);
  for (auto _ : state) {
    const McapContents c = read_mcap(file);
    benchmark::DoNotOptimize(c.messages.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * payload_bytes(n)));
  state.counters["file_bytes"] = static_cast<double>(file.size());
  state.SetLabel(compression == Compression::zstd ? "zstd" : "none");
}
BENCHMARK(BM_McapRead)
    ->Args({static_cast<int>(Compression::none), 100000})
    ->Args({static_cast<int>(Compression::zstd), 100000})
    ->Unit(benchmark::kMillisecond);

}  // namespace
