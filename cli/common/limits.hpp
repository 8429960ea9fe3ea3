// The CLI's limits, in one place: what the options and scene files accept, and how much of a bad token a
// message quotes. (The library has no such limits; these keep a command's memory and time bounded.)
#pragma once

#include <cstddef>
#include <cstdint>

#include <raykernel/parallel.hpp>

namespace raykernel::cli::limits {

// A render: image side and samples per pixel (scene files and --width, --height, --samples), worker threads.
inline constexpr std::uint32_t max_image_side = 16384;
inline constexpr std::uint32_t max_samples_per_pixel = 4096;
inline constexpr std::uint32_t max_threads = raykernel::max_threads;  // <raykernel/parallel.hpp>

// Scene files: how deeply arrays and objects may nest (a scene needs 4 levels; the parser's memory and stack
// grow with the nesting).
inline constexpr std::size_t max_json_depth = 64;

// The largest scene file `render` reads (a scene of a million planes takes about 100 MB).
inline constexpr std::size_t max_scene_bytes = std::size_t{1} << 28;

// `raykernel demo --per-kind N`.
inline constexpr std::uint64_t max_demo_queries_per_kind = 100'000'000;

// The longest line of a text input (queries, rays, points, planes): far above any line of numbers (18
// numbers of 800 digits), small enough that memory stays bounded.
inline constexpr std::size_t max_line_bytes = std::size_t{1} << 20;

// The most numbers a query line holds (spawn's 18), and the bytes of a bad token a message quotes.
inline constexpr int max_numbers_per_line = 18;  // a spawn line (docs/contract.md §9)
inline constexpr std::size_t quoted_token_bytes = 40;

}  // namespace raykernel::cli::limits
