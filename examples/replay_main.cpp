// The fuzz harness without libFuzzer: replays saved inputs (files, or every file in a directory), or feeds
// it N pseudo-random inputs from a seed — a smoke test that needs no clang.
//
//   fuzz_my_intersect_replay [FILE|DIR]...
//   fuzz_my_intersect_replay --random N [--seed S]
//
// Prints the report of the first failing input and a summary; exit status 1 when an input failed, 2 on a
// usage or I/O error.
#include <raykernel/testkit/plane_queries.hpp>  // SplitMix64

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <span>
#include <string>
#include <vector>

bool my_intersect_matches_raykernel(std::span<const std::uint8_t> bytes, std::string& report);

namespace {

struct Tally {
  long inputs = 0;
  long failures = 0;
  void run(const std::vector<std::uint8_t>& bytes, const std::string& name) {
    ++inputs;
    std::string report;
    if (my_intersect_matches_raykernel(bytes, report)) return;
    if (failures++ == 0) std::printf("FAILED on %s\n%s", name.c_str(), report.c_str());
  }
};

bool read_file(const std::filesystem::path& path, std::vector<std::uint8_t>& bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Tally tally;
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (!args.empty() && args[0] == "--random") {
    if (args.size() != 2 && !(args.size() == 4 && args[2] == "--seed")) {
      std::fprintf(stderr, "usage: %s --random N [--seed S]\n", argv[0]);
      return 2;
    }
    const long count = std::stol(args[1]);
    const std::uint64_t seed = args.size() == 4 ? std::stoull(args[3]) : 1;
    raykernel::testkit::SplitMix64 rng(seed);
    for (long i = 0; i < count; ++i) {
      // Half raw doubles, half hard queries (first byte ≥ 0x80); 0 to 128 further bytes.
      std::vector<std::uint8_t> bytes(1 + rng() % 129);
      for (auto& b : bytes) b = static_cast<std::uint8_t>(rng());
      tally.run(bytes, "random input #" + std::to_string(i) + " (seed " + std::to_string(seed) + ")");
    }
  } else {
    for (const std::string& arg : args) {
      std::vector<std::filesystem::path> files;
      if (std::filesystem::is_directory(arg)) {
        for (const auto& entry : std::filesystem::directory_iterator(arg))
          if (entry.is_regular_file()) files.push_back(entry.path());
      } else {
        files.emplace_back(arg);
      }
      for (const auto& file : files) {
        std::vector<std::uint8_t> bytes;
        if (!read_file(file, bytes)) {
          std::fprintf(stderr, "fuzz_my_intersect_replay: cannot read %s\n", file.c_str());
          return 2;
        }
        tally.run(bytes, file.string());
      }
    }
  }
  std::printf("%ld inputs, %ld failed\n", tally.inputs, tally.failures);
  return tally.failures == 0 ? 0 : 1;
}
