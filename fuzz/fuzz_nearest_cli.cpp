// fuzz_nearest_cli: arbitrary text as the planes file and the rays file of `raykernel nearest` (docs/contract.md §4),
// through the functions the command runs — cli::read_planes, cli::nearest_stream — and through the command
// itself, cli::run_nearest, with the planes in a file and the rays on standard input.
//
// Input: the planes text, a line "%%", the rays text. Without a "%%" line the whole input is both files
// (a planes line is also a valid rays line). Checked, against the harness's own reading of the text:
//   - both files are read as fuzz_text.hpp's input_lines reads them (a byte-order mark at the start skipped);
//   - read_planes: the planes are the non-skipped lines, in order, read as 6 numbers by strtod (bit for
//     bit; a number that overflows or underflows to zero is invalid); the first line that is not 6 finite numbers with a nonzero normal stops it, with its number
//     (counting every line from 1), no planes, and parse_number_line's or validate_plane's reason;
//   - nearest_stream, three times (default; --path=exact --exact-t --hex --stats; --path=naive --exact-t):
//     every rays line that is not skipped gets exactly one output line, in order: `hit K T [P/Q]` with K and
//     the bits of T those of nearest_hit (the exact path must give the certified answer too), P/Q the
//     winner's exact t, or `miss`; an invalid line gets `invalid REASON` and `raykernel: line N: REASON` on
//     stderr, nothing else; exit status 0, or 1 when a line was invalid; the counts (what --stats prints)
//     equal what nearest_hit_traced reports, ray by ray;
//   - run_nearest --planes FILE -: exit 2, nothing on stdout and exactly `raykernel: FILE:N: REASON` on
//     stderr when a plane line is invalid; otherwise nearest_stream's output, errors and status, byte for byte.
#include "fuzz_support.hpp"
#include "fuzz_text.hpp"

#include "commands/commands.hpp"
#include "commands/plane_nearest.hpp"
#include "common/text_input.hpp"

#include <raykernel/nearest_hit.hpp>
#include <raykernel/raykernel.hpp>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <unistd.h>

namespace {

using raykernel::NearestHit;
using raykernel::Plane;
using raykernel::Ray;
using raykernel::fuzz::check;
using raykernel::fuzz::getline_lines;
using raykernel::fuzz::tokens_of;
namespace cli = raykernel::cli;

std::string_view current_planes, current_rays;
bool current_split = false;

std::string describe_current() {
  std::string s = current_split ? "planes file and rays file, separated by a line %%"
                                : "no %% line: the same text is the planes file and the rays file";
  s += "\nplanes text (" + std::to_string(current_planes.size()) + " bytes, C-escaped):\n" +
       raykernel::fuzz::c_escaped(current_planes);
  if (current_split)
    s += "\nrays text (" + std::to_string(current_rays.size()) + " bytes, C-escaped):\n" +
         raykernel::fuzz::c_escaped(current_rays);
  return s;
}

// Splits the input at its first line "%%" (at the start, or after a '\n'; ended by '\n' or the end).
bool split_input(std::string_view text, std::string_view& planes, std::string_view& rays) {
  for (std::size_t start = 0; start <= text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    if (text.substr(start, end - start) == "%%") {
      planes = text.substr(0, start);
      rays = end < text.size() ? text.substr(end + 1) : std::string_view();
      return true;
    }
    if (end >= text.size()) break;
    start = end + 1;
  }
  planes = rays = text;
  return false;
}

// ---- The planes file -------------------------------------------------------------------------------------

struct ExpectedPlanes {
  std::vector<Plane> planes;
  std::uint64_t error_line = 0;
  std::string error;  // parse_number_line's or validate_plane's reason for the error line
};

ExpectedPlanes expected_planes(std::string_view text) {
  ExpectedPlanes e;
  const std::vector<std::string_view> lines = raykernel::fuzz::input_lines(text);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const raykernel::fuzz::ExpectedNumbers numbers = raykernel::fuzz::expected_numbers(lines[i], 6);
    if (numbers.skipped) continue;
    const auto& v = numbers.value;
    const Plane plane{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
    if (numbers.numbers && !raykernel::fuzz::zero_vector_by_bits(plane.normal)) {
      e.planes.push_back(plane);
      continue;
    }
    e.error_line = i + 1;
    e.error = numbers.numbers ? raykernel::validate(plane).value_or("")
                              : cli::parse_number_line(lines[i], 6).reason;
    check(!e.error.empty(), [&] {
      return "line " + std::to_string(i + 1) + " of the planes: an invalid line has a reason (parse_number_line, "
             "validate_plane)";
    });
    e.planes.clear();
    return e;
  }
  return e;
}

bool same_plane(const Plane& a, const Plane& b) {
  using raykernel::fuzz::bits;
  return bits(a.point.x) == bits(b.point.x) && bits(a.point.y) == bits(b.point.y) && bits(a.point.z) == bits(b.point.z) &&
         bits(a.normal.x) == bits(b.normal.x) && bits(a.normal.y) == bits(b.normal.y) &&
         bits(a.normal.z) == bits(b.normal.z);
}

ExpectedPlanes check_read_planes(std::string_view text) {
  const ExpectedPlanes want = expected_planes(text);
  std::istringstream in{std::string(text)};
  const cli::PlanesFile got = cli::read_planes(in);
  check(got.ok() == (want.error_line == 0) && got.error_line == want.error_line, [&] {
    return "read_planes stops at line " + std::to_string(want.error_line) + " (0: every line valid), got line " +
           std::to_string(got.error_line) + " ('" + got.error + "')";
  });
  if (!got.ok()) {
    check(got.error == want.error && got.items.empty(), [&] {
      return "read_planes reports line " + std::to_string(want.error_line) + " with reason '" + want.error +
             "' and no planes, got '" + got.error + "' and " + std::to_string(got.items.size()) + " planes";
    });
    return want;
  }
  check(got.items.size() == want.planes.size(), [&] {
    return "read_planes reads " + std::to_string(want.planes.size()) + " planes, got " + std::to_string(got.items.size());
  });
  for (std::size_t k = 0; k < want.planes.size(); ++k) {
    check(same_plane(got.items[k], want.planes[k]),
          [&] { return "plane " + std::to_string(k) + " has the doubles strtod reads"; });
  }
  return want;
}

// ---- The rays file ---------------------------------------------------------------------------------------

// What nearest_hit_traced says about each valid rays line, computed once for the three runs.
struct ExpectedRay {
  bool skipped = false;
  bool valid = false;
  Ray ray{};
  raykernel::TracedNearestHit traced;
};

std::vector<ExpectedRay> expected_rays(const std::vector<std::string_view>& lines, const std::vector<Plane>& planes) {
  std::vector<ExpectedRay> out(lines.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const raykernel::fuzz::ExpectedNumbers numbers = raykernel::fuzz::expected_numbers(lines[i], 6);
    out[i].skipped = numbers.skipped;
    const auto& v = numbers.value;
    out[i].ray = {{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
    out[i].valid = numbers.numbers && !raykernel::fuzz::zero_vector_by_bits(out[i].ray.direction);
    if (out[i].valid) out[i].traced = raykernel::nearest_hit_traced(out[i].ray, planes);
  }
  return out;
}

std::string answer_text(const std::optional<NearestHit>& h) {
  return h ? "hit " + std::to_string(h->plane) + " " + raykernel::fuzz::hex(h->t) : std::string("miss");
}

struct Run {
  cli::NearestOptions options;
  const char* name;
};

struct StreamOutput {
  int status;
  std::string out, err;
};

StreamOutput check_stream(std::string_view text, const std::vector<std::string_view>& lines,
                          const std::vector<ExpectedRay>& expected, const std::vector<Plane>& planes, const Run& run) {
  std::istringstream in{std::string(text)};
  std::ostringstream out, err;
  cli::NearestCounts counts;
  int status = -1;
  try {
    status = cli::nearest_stream(in, out, err, planes, run.options, counts);
  } catch (const std::exception& e) {
    check(false, [&] { return std::string("[") + run.name + "] nearest_stream throws: " + e.what(); });
  }
  (void)cli::describe(counts, run.options.method);
  auto run_label = [&] { return std::string("[") + run.name + "] "; };
  std::size_t i = 0;
  auto at = [&](std::string_view what) {
    return run_label() + "rays line " + std::to_string(i + 1) + ": " + std::string(what);
  };

  // str(), not view(): ostringstream::view() needs libc++ 17 (ClusterFuzzLite's is newer; clang-14's is not).
  const std::string out_text = out.str(), err_text = err.str();
  const std::vector<std::string_view> out_lines = getline_lines(out_text);
  const std::vector<std::string_view> err_lines = getline_lines(err_text);
  check(out_text.empty() || out_text.back() == '\n', [&] { return run_label() + "stdout ends with a newline"; });
  check(err_text.empty() || err_text.back() == '\n', [&] { return run_label() + "stderr ends with a newline"; });

  std::size_t next_out = 0, next_err = 0;
  std::uint64_t answered = 0, invalid = 0, hits = 0, misses = 0;
  std::array<std::uint64_t, 4> relation_stage{}, comparison_stage{}, t_stage{};
  for (i = 0; i < lines.size(); ++i) {
    const ExpectedRay& e = expected[i];
    const cli::NumberLine parsed = cli::parse_number_line(lines[i], 6);
    check((parsed.status == cli::LineStatus::skip) == e.skipped,
          [&] { return at("skipped exactly when blank or starting with '#'"); });
    if (e.skipped) continue;
    ++answered;
    check(next_out < out_lines.size(), [&] { return at("has an output line"); });
    const std::string_view answer = out_lines[next_out++];

    if (!e.valid) {
      ++invalid;
      check(answer.starts_with("invalid ") && answer.size() > 8,
            [&] { return at("answered 'invalid REASON', got '" + std::string(answer) + "'"); });
      check(next_err < err_lines.size(), [&] { return at("reported on stderr"); });
      const std::string_view got = err_lines[next_err++];
      const std::string want = "raykernel: line " + std::to_string(i + 1) + ": " + std::string(answer.substr(8));
      check(got == want, [&] { return at("stderr says '" + want + "', got '" + std::string(got) + "'"); });
      continue;
    }
    check(parsed.status == cli::LineStatus::numbers, [&] { return at("a valid line parses as numbers"); });
    const std::vector<std::string_view> words = tokens_of(answer);
    check(!words.empty() && (words[0] == "hit" || words[0] == "miss"),
          [&] { return at("answered 'hit K T' or 'miss', got '" + std::string(answer) + "'"); });
    if (words[0] == "miss") ++misses;
    else ++hits;
    if (run.options.method == cli::Method::naive) {  // no guarantee beyond answering with a plane that exists
      if (words[0] == "hit") {
        check(words.size() == (run.options.exact_t ? 4u : 3u) && std::stoull(std::string(words[1])) < planes.size(),
              [&] { return at("the naive path answers 'hit K T P/Q' with a plane K, got '" + std::string(answer) + "'"); });
      }
      continue;
    }
    const raykernel::TracedNearestHit& want = e.traced;
    ++relation_stage[static_cast<std::size_t>(want.relation_stage)];
    for (std::size_t k = 0; k < 4; ++k) comparison_stage[k] += want.comparisons[k];
    if (!want.hit) {
      check(answer == "miss", [&] { return at("answers 'miss' (nearest_hit finds no plane), got '" + std::string(answer) + "'"); });
      continue;
    }
    ++t_stage[static_cast<std::size_t>(want.t_stage)];
    const std::size_t want_words = run.options.exact_t ? 4 : 3;
    check(words.size() == want_words && words[0] == "hit" && words[1] == std::to_string(want.hit->plane), [&] {
      return at("answers nearest_hit's " + answer_text(want.hit) + " in " + std::to_string(want_words) + " words, got '" +
                std::string(answer) + "'");
    });
    const std::string t_text(words[2]);
    char* end = nullptr;
    const double t = std::strtod(t_text.c_str(), &end);
    check(end == t_text.c_str() + t_text.size() && raykernel::fuzz::bits(t) == raykernel::fuzz::bits(want.hit->t),
          [&] { return at("T '" + t_text + "' reads back as t = " + raykernel::fuzz::hex(want.hit->t)); });
    if (run.options.hex) {
      check(t_text.find("0x") != std::string::npos || std::isinf(t), [&] { return at("--hex prints a hex float"); });
    }
    if (run.options.exact_t) {
      const raykernel::ExactIntersection exact = raykernel::intersect_exact_rational(e.ray, planes[want.hit->plane]);
      check(exact.t && words[3] == exact.t->str(), [&] { return at("P/Q is the winner's exact t"); });
    }
  }
  check(next_out == out_lines.size(), [&] { return run_label() + "no extra output lines"; });
  check(next_err == err_lines.size(), [&] { return run_label() + "no extra error lines"; });
  check(status == (invalid == 0 ? cli::exit_ok : cli::exit_invalid_line),
        [&] { return run_label() + "exit status 0 when every rays line is valid, else 1"; });
  check(counts.lines_answered == answered && counts.invalid == invalid && counts.hits == hits && counts.misses == misses,
        [&] { return run_label() + "counts of answered, invalid, hit and miss lines"; });
  if (run.options.method == cli::Method::certified) {
    for (std::size_t k = 0; k < 4; ++k) {
      check(counts.relation_stage[k] == relation_stage[k] && counts.comparison_stage[k] == comparison_stage[k] &&
                counts.t_stage[k] == t_stage[k],
            [&] { return run_label() + "stage counts are nearest_hit_traced's, summed over the rays"; });
    }
  }
  return {status, out.str(), err.str()};
}

// ---- The command -----------------------------------------------------------------------------------------

// A directory of this process for the planes file, removed at exit (never destroyed itself, so that the
// atexit handler can still read it).
const std::string* scratch = nullptr;
const std::string& scratch_directory() {
  if (scratch == nullptr) {
    std::string pattern = (std::filesystem::temp_directory_path() / "raykernel-fuzz-nearest-cli.XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) raykernel::fuzz::fail("cannot create a temporary directory for the planes file");
    scratch = new std::string(pattern);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(*scratch, ec);
    });
  }
  return *scratch;
}

// std::cin, std::cout and std::cerr on strings for the lifetime of the object.
class StandardStreams {
 public:
  explicit StandardStreams(std::string input) : in_(std::move(input)) {
    old_in_ = std::cin.rdbuf(in_.rdbuf());
    old_out_ = std::cout.rdbuf(out_.rdbuf());
    old_err_ = std::cerr.rdbuf(err_.rdbuf());
  }
  ~StandardStreams() {
    std::cin.rdbuf(old_in_);
    std::cout.rdbuf(old_out_);
    std::cerr.rdbuf(old_err_);
    std::cin.clear();
    std::cout.clear();
    std::cerr.clear();
  }
  StandardStreams(const StandardStreams&) = delete;
  StandardStreams& operator=(const StandardStreams&) = delete;
  [[nodiscard]] std::string out() const { return out_.str(); }
  [[nodiscard]] std::string err() const { return err_.str(); }

 private:
  std::istringstream in_;
  std::ostringstream out_, err_;
  std::streambuf *old_in_, *old_out_, *old_err_;
};

void check_command(std::string_view planes_text, std::string_view rays_text, const ExpectedPlanes& planes,
                   const std::optional<StreamOutput>& stream) {
  const std::string path = scratch_directory() + "/planes.txt";
  {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file.write(planes_text.data(), static_cast<std::streamsize>(planes_text.size()));
    if (!file) raykernel::fuzz::fail("cannot write the planes file " + path);
  }
  int status = -1;
  std::string out, err;
  {
    const StandardStreams streams{std::string(rays_text)};
    try {
      status = cli::run_nearest({"--planes", path, "-"});
    } catch (const std::exception& e) {
      out = streams.out(), err = streams.err();
      status = -2;
      err += std::string("(threw: ") + e.what() + ")";
    }
    if (status != -2) out = streams.out(), err = streams.err();
  }
  check(status != -2, [&] { return "run_nearest throws: " + err; });
  if (planes.error_line != 0) {
    const std::string want = "raykernel: " + path + ":" + std::to_string(planes.error_line) + ": " + planes.error + "\n";
    check(status == cli::exit_usage && out.empty() && err == want, [&] {
      return "an invalid plane line: exit status 2, nothing on stdout and '" + want + "' on stderr; got status " +
             std::to_string(status) + ", stdout " + std::to_string(out.size()) + " bytes, stderr '" + err + "'";
    });
    return;
  }
  check(stream.has_value() && status == stream->status && out == stream->out && err == stream->err, [&] {
    return "run_nearest --planes FILE - prints what nearest_stream prints (status " + std::to_string(status) + ", " +
           std::to_string(out.size()) + " bytes on stdout, " + std::to_string(err.size()) + " on stderr)";
  });
}

std::uint64_t executions = 0, split_inputs = 0, planes_invalid = 0, planes_read = 0, rays_lines = 0, rays_valid = 0,
              rays_hit = 0;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool initialized = [] {
    raykernel::fuzz::set_harness_name("nearest_cli");
    raykernel::fuzz::set_input_describer(describe_current);
    raykernel::fuzz::print_at_exit([] {
      auto u = [](std::uint64_t x) { return static_cast<unsigned long long>(x); };
      std::fprintf(stderr,
                   "==== raykernel fuzz stats: nearest_cli: %llu executions (%llu with a %%%% line), %llu with an "
                   "invalid planes file; %llu planes read, %llu rays lines, %llu valid rays, %llu hits\n",
                   u(executions), u(split_inputs), u(planes_invalid), u(planes_read), u(rays_lines), u(rays_valid),
                   u(rays_hit));
    });
    return true;
  }();
  (void)initialized;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  current_split = split_input(text, current_planes, current_rays);

  const ExpectedPlanes planes = check_read_planes(current_planes);
  std::optional<StreamOutput> default_run;
  ++executions;
  split_inputs += current_split ? 1 : 0;
  if (planes.error_line == 0) {
    const std::vector<std::string_view> lines = raykernel::fuzz::input_lines(current_rays);
    const std::vector<ExpectedRay> expected = expected_rays(lines, planes.planes);
    static const Run runs[] = {
        {{cli::Method::certified, false, false, false}, "default"},
        {{cli::Method::exact, true, true, true}, "--path=exact --exact-t --hex --stats"},
        {{cli::Method::naive, true, false, false}, "--path=naive --exact-t"},
    };
    for (const Run& run : runs) {
      StreamOutput o = check_stream(current_rays, lines, expected, planes.planes, run);
      if (!default_run) default_run = std::move(o);
    }
    planes_read += planes.planes.size();
    rays_lines += lines.size();
    for (const ExpectedRay& e : expected) {
      rays_valid += e.valid ? 1 : 0;
      rays_hit += e.valid && e.traced.hit ? 1 : 0;
    }
  } else {
    ++planes_invalid;
  }
  check_command(current_planes, current_rays, planes, default_run);
  return 0;
}
