// `raykernel triangle` (docs/contract.md §6, with §3's number syntax, invalid-line and exit-status rules): the
// output format, options, invalid lines, and two samples through the stream code and the real binary: the
// contract's (tests/data/contract-cases/triangle-sample.*) and the hand-derived one
// (tests/data/triangle-cases/hand.*), whose every expected line is also checked against an independent oracle.
#include "support/answer_lines.hpp"
#include "support/triangle_oracle.hpp"
#include "common/text_input.hpp"
#include "commands/triangle.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace raykernel::cli {
namespace {

const std::string cli = RAYKERNEL_CLI_PATH;
const std::string cases = RAYKERNEL_CASES_DIR;
const std::string triangle_cases = RAYKERNEL_TRIANGLE_CASES_DIR;

struct CliRun {
  int status;
  std::string out, err;
};

CliRun run(const std::string& args, const std::string& stdin_text = "") {
  const std::string dir = ::testing::TempDir();
  const std::string tag = std::to_string(getpid());
  const std::string in = dir + "/triangle_in_" + tag + ".txt", err = dir + "/triangle_err_" + tag + ".txt";
  {
    std::ofstream f(in, std::ios::binary);
    f << stdin_text;
  }
  CliRun r{};
  FILE* p = popen((cli + " " + args + " < " + in + " 2> " + err).c_str(), "r");
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) r.out.append(buf, n);
  const int status = pclose(p);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err);
  std::stringstream s;
  s << e.rdbuf();
  r.err = s.str();
  return r;
}

struct StreamRun {
  int status;
  std::string out, err;
  TriangleCounts counts;
};
StreamRun stream(const std::string& text, TriangleCommandOptions options = {}) {
  std::istringstream in(text);
  std::ostringstream out, err;
  StreamRun r{};
  r.status = triangle_stream(in, out, err, options, r.counts);
  r.out = out.str();
  r.err = err.str();
  return r;
}

// One output line of `raykernel triangle --exact` against the expected one: the words must match, except
// the reason after `invalid`; T, UA, UB, UC compare as the doubles they read back to (the sign of a zero
// matters unless the exact value is 0), the exact values as rationals.
bool same_triangle_line(const std::string& got_line, const std::string& want_line) {
  using test_support::words;
  const auto g = words(got_line), w = words(want_line);
  if (g.empty() || w.empty() || g[0] != w[0]) return false;
  if (w[0] == "invalid") return true;
  if (w.size() == 1) return g == w;
  if (w.size() != 10 || g.size() != 10 || g[1] != w[1]) return false;
  for (std::size_t k = 0; k < 4; ++k) {
    mpq_class exact_want, exact_got;
    if (!test_support::parse_rational(w[6 + k], exact_want) || !test_support::parse_rational(g[6 + k], exact_got))
      return false;
    if (exact_got != exact_want || !test_support::same_t(g[2 + k], w[2 + k], exact_want)) return false;
  }
  return true;
}

void expect_sample(const std::string& input, const std::string& expected, const std::string& rule) {
  const CliRun r = run("triangle --exact --rule=" + rule + " " + input);
  EXPECT_EQ(r.status, 1) << "the samples have invalid lines";
  const auto want = test_support::read_lines(expected);
  std::istringstream got(r.out);
  std::vector<std::string> lines;
  for (std::string l; std::getline(got, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), want.size()) << input;
  int wrong = 0;
  for (std::size_t i = 0; i < want.size(); ++i) {
    if (!same_triangle_line(lines[i], want[i])) {
      ++wrong;
      ADD_FAILURE() << input << " answer " << i + 1 << " (" << rule << ")\n  want: " << want[i]
                    << "\n  got:  " << lines[i];
    }
  }
  EXPECT_EQ(wrong, 0);
}

// ---- Format and options -----------------------------------------------------------------------------------

TEST(TriangleCli, OneAnswerPerQueryLine) {
  // The unit triangle (0,0,0), (1,0,0), (0,1,0) hit at (1/4, 1/4), t = 1 (tests/triangle_test.cpp); then a
  // parallel ray (d = (1,0,0)) and a degenerate triangle; comments and blank lines give nothing.
  const StreamRun r = stream(
      "# comment\n0.25 0.25 -1 0 0 1 0 0 0 1 0 0 0 1 0\n\n0 0 -1 1 0 0 0 0 0 1 0 0 0 1 0\n"
      "  1 1 0 0 0 1 0 0 0 1 1 1 2 2 2\n");
  EXPECT_EQ(r.status, exit_ok);
  EXPECT_EQ(r.out, "hit inside 1 0.5 0.25 0.25\nparallel\ndegenerate\n");
  EXPECT_EQ(r.err, "");
}

TEST(TriangleCli, ExactAndHex) {
  // d = (0, 0, 3): t = 1/3 = RN 0x1.5555555555555p-2 (tests/triangle_test.cpp, ThirdsRoundToNearest).
  TriangleCommandOptions options;
  options.exact_t = true;
  options.hex = true;
  const StreamRun r = stream("0.25 0.25 -1 0 0 3 0 0 0 1 0 0 0 1 0\n", options);
  EXPECT_EQ(r.out, "hit inside 0x1.5555555555555p-2 0x1p-1 0x1p-2 0x1p-2 1/3 1/2 1/4 1/4\n");
}

TEST(TriangleCli, RulesDifferOnAGivenAwayEdge) {
  // Edge bc of the unit triangle at (1/2, 1/2): the owned rule gives it away, the closed rule hits.
  const std::string q = "0.5 0.5 -1 0 0 1 0 0 0 1 0 0 0 1 0\n";
  EXPECT_EQ(stream(q).out, "miss edge-bc 1 0 0.5 0.5\n");
  TriangleCommandOptions closed;
  closed.rule = TriangleRule::closed;
  EXPECT_EQ(stream(q, closed).out, "hit edge-bc 1 0 0.5 0.5\n");
  EXPECT_EQ(run("triangle --rule=closed", q).out, "hit edge-bc 1 0 0.5 0.5\n");
  EXPECT_EQ(run("triangle --rule closed", q).out, "hit edge-bc 1 0 0.5 0.5\n");
  EXPECT_EQ(run("triangle --rule=owned", q).out, "miss edge-bc 1 0 0.5 0.5\n");
}

TEST(TriangleCli, InvalidLinesAreReportedAndSkipped) {
  // Line 2: 14 numbers; line 3: NaN; line 4: zero direction; line 5 is still answered.
  const StreamRun r = stream(
      "0.25 0.25 -1 0 0 1 0 0 0 1 0 0 0 1 0\n0 0 -1 0 0 1 0 0 0 1 0 0 0 1\n"
      "0 0 -1 0 0 1 0 0 0 1 nan 0 0 1 0\n0 0 -1 0 0 0 0 0 0 1 0 0 0 1 0\n"
      "0.25 0.25 1 0 0 1 0 0 0 1 0 0 0 1 0\n");
  EXPECT_EQ(r.status, exit_invalid_line);
  EXPECT_EQ(r.out,
            "hit inside 1 0.5 0.25 0.25\ninvalid expected 15 numbers, found 14\n"
            "invalid field 11: 'nan' is not finite\ninvalid ray direction is the zero vector\n"
            "behind inside -1 0.5 0.25 0.25\n");
  EXPECT_EQ(r.err,
            "raykernel: line 2: expected 15 numbers, found 14\n"
            "raykernel: line 3: field 11: 'nan' is not finite\n"
            "raykernel: line 4: ray direction is the zero vector\n");
}

TEST(TriangleCli, UsageErrors) {
  EXPECT_EQ(run("triangle --rule=sideways").status, exit_usage);
  EXPECT_EQ(run("triangle --bogus").status, exit_usage);
  EXPECT_EQ(run("triangle /nonexistent/file").status, exit_usage);
  EXPECT_EQ(run("triangle a b").status, exit_usage);
  const CliRun help = run("triangle --help");
  EXPECT_EQ(help.status, exit_ok);
  EXPECT_NE(help.out.find("--rule=owned|closed"), std::string::npos);
}

TEST(TriangleCli, PathsAndStats) {
  // Through vertex a of the unit triangle: the certified path needs exact signs (two π are 0). The naive path
  // (Möller–Trumbore) computes det = e1·(d × e2) = (1,0,0)·(−1,0,0) = −1 and u = T·P/det = 0/−1 = −0,
  // v = d·(T × e1)/det = 0/−1 = −0: the weights of b and c come out as −0. --stats counts the stages.
  const std::string q = "0 0 -1 0 0 1 0 0 0 1 0 0 0 1 0\n";
  for (const char* path : {"certified", "exact", "naive"}) {
    const CliRun r = run(std::string("triangle --stats --path=") + path, q);
    EXPECT_EQ(r.out, std::string(path) == "naive" ? "hit vertex-a 1 1 -0 -0\n" : "hit vertex-a 1 1 0 0\n") << path;
    EXPECT_NE(r.err.find("raykernel: stats: 1 queries: 1 hit"), std::string::npos) << r.err;
  }
  const CliRun r = run("triangle --stats", q);
  EXPECT_NE(r.err.find("relation decided by: filter 0, compensated 0, expansion 1, exact 0"), std::string::npos)
      << r.err;
}

// ---- Samples -------------------------------------------------------------------------------------------------

TEST(TriangleCli, ContractSampleThroughTheStream) {
  for (const auto& [rule, expected] : {std::pair{TriangleRule::owned, "/triangle-sample.expected"},
                                       std::pair{TriangleRule::closed, "/triangle-sample.closed.expected"}}) {
    std::ifstream in(cases + "/triangle-sample.txt");
    std::ostringstream out, err;
    TriangleCommandOptions options;
    options.exact_t = true;
    options.rule = rule;
    TriangleCounts counts;
    EXPECT_EQ(triangle_stream(in, out, err, options, counts), exit_invalid_line);
    const auto want = test_support::read_lines(cases + expected);
    std::istringstream got(out.str());
    std::size_t i = 0;
    for (std::string l; std::getline(got, l); ++i) {
      ASSERT_LT(i, want.size());
      EXPECT_TRUE(same_triangle_line(l, want[i])) << "answer " << i + 1 << "\n  want: " << want[i] << "\n  got:  " << l;
    }
    EXPECT_EQ(i, want.size());
  }
}

TEST(TriangleCli, ContractSampleThroughTheBinary) {
  expect_sample(cases + "/triangle-sample.txt", cases + "/triangle-sample.expected", "owned");
  expect_sample(cases + "/triangle-sample.txt", cases + "/triangle-sample.closed.expected", "closed");
}

TEST(TriangleCli, HandSampleThroughTheBinary) {
  expect_sample(triangle_cases + "/hand.txt", triangle_cases + "/hand.expected", "owned");
  expect_sample(triangle_cases + "/hand.txt", triangle_cases + "/hand.closed.expected", "closed");
}

TEST(TriangleCli, HandSampleAgreesWithTheIndependentOracle) {
  // Every expected line of the hand sample, against the oracle of tests/support/triangle_oracle.hpp.
  const auto input = test_support::read_lines(triangle_cases + "/hand.txt");
  for (const auto& [rule, file] : {std::pair{TriangleRule::owned, "/hand.expected"},
                                   std::pair{TriangleRule::closed, "/hand.closed.expected"}}) {
    const auto want = test_support::read_lines(triangle_cases + file);
    std::size_t k = 0;
    for (const std::string& line : input) {
      const NumberLine parsed = parse_number_line(line, 15);
      if (parsed.status == LineStatus::skip) continue;
      ASSERT_LT(k, want.size());
      const std::string& expected = want[k++];
      if (parsed.status == LineStatus::invalid) {
        EXPECT_EQ(test_support::words(expected)[0], "invalid");
        continue;
      }
      const auto& v = parsed.value;
      const Ray ray{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
      const Triangle tri{{v[6], v[7], v[8]}, {v[9], v[10], v[11]}, {v[12], v[13], v[14]}};
      if (validate(ray, tri)) {
        EXPECT_EQ(test_support::words(expected)[0], "invalid") << line;
        continue;
      }
      const test_support::TriangleOracle o = test_support::triangle_oracle(ray, tri, rule);
      std::string oracle_line(to_string(o.answer.relation));
      if (o.answer.location != TriangleLocation::none) {
        oracle_line += " " + std::string(to_string(o.answer.location));
        for (double x : {o.answer.t, o.answer.barycentric[0], o.answer.barycentric[1], o.answer.barycentric[2]})
          oracle_line += " " + format_shortest(x);
        for (const mpq_class& q : {mpq_class(o.num / o.den), mpq_class(o.pi_a / o.den), mpq_class(o.pi_b / o.den),
                                   mpq_class(o.pi_c / o.den)})
          oracle_line += " " + q.get_num().get_str() + "/" + q.get_den().get_str();
      }
      EXPECT_TRUE(same_triangle_line(oracle_line, expected)) << line << "\n  oracle: " << oracle_line
                                                             << "\n  expected: " << expected;
    }
    EXPECT_EQ(k, want.size());
  }
}

}  // namespace
}  // namespace raykernel::cli
