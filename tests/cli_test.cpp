// The CLI (docs/contract.md §3): the number syntax, the output format, invalid lines, exit statuses, and the
// contract's sample cases run through the real binary.
#include "commands.hpp"
#include "support/answer_lines.hpp"
#include "text_input.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <fstream>
#include <limits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace raykernel::cli {
namespace {

const std::string cli = RAYKERNEL_CLI_PATH;
const std::string cases = RAYKERNEL_CASES_DIR;

struct CliRun {
  int status;
  std::string out, err;
};

// Runs the binary with a shell command line; stdout and stderr captured separately.
CliRun run(const std::string& args, const std::string& stdin_text = "") {
  const std::string dir = ::testing::TempDir();
  // Per process: ctest runs each test case as its own process, in parallel.
  const std::string tag = std::to_string(getpid());
  const std::string in = dir + "/cli_in_" + tag + ".txt", err = dir + "/cli_err_" + tag + ".txt";
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

// ---- Number syntax -----------------------------------------------------------------------------------

TEST(NumberLine, AcceptsEveryStrtodSyntax) {
  const NumberLine l = parse_number_line(" 1 -2.5 3e2\t0x1.8p1 .5 5. +7 -0 1e-400 0X10 0x1p-1074 4.9e-324 ", 12);
  ASSERT_EQ(l.status, LineStatus::numbers) << l.reason;
  const double want[12] = {1, -2.5, 300, 3, 0.5, 5, 7, -0.0, 0, 16, 0x1p-1074, 0x1p-1074};
  for (int i = 0; i < 12; ++i) EXPECT_EQ(l.value[static_cast<std::size_t>(i)], want[i]) << i;
  EXPECT_TRUE(std::signbit(l.value[7]));
}

TEST(NumberLine, SkipsBlankAndCommentLines) {
  EXPECT_EQ(parse_number_line("", 12).status, LineStatus::skip);
  EXPECT_EQ(parse_number_line(" \t\r", 12).status, LineStatus::skip);
  EXPECT_EQ(parse_number_line("# 1 2 3", 12).status, LineStatus::skip);
  EXPECT_EQ(parse_number_line("   #", 12).status, LineStatus::skip);
}

TEST(NumberLine, NamesWhatIsWrong) {
  auto reason = [](const std::string& line) {
    const NumberLine l = parse_number_line(line, 12);
    EXPECT_EQ(l.status, LineStatus::invalid) << line;
    return l.reason;
  };
  EXPECT_EQ(reason("0 0 0 1 0 0 1 0 0 1 0"), "expected 12 numbers, found 11");
  EXPECT_EQ(reason("0 0 0 1 0 0 1 0 0 1 0 0 7"), "expected 12 numbers, found 13");
  EXPECT_EQ(reason("0 0 0 1 0 0 1 0 0 1 abc 0"), "field 11: 'abc' is not a number");
  EXPECT_EQ(reason("0 0 0 1 0 0 1 0 0 1 1.0x 0"), "field 11: '1.0x' is not a number");
  EXPECT_EQ(reason("nan 0 0 1 0 0 0 0 0 1 0 0"), "field 1: 'nan' is not finite (non-finite)");
  EXPECT_EQ(reason("0 0 0 -inf 0 0 1 0 0 1 0 0"), "field 4: '-inf' is not finite (non-finite)");
  EXPECT_EQ(reason("0 0 0 1 0 0 1e400 0 0 1 0 0"), "field 7: '1e400' overflows the double range (non-finite)");
  EXPECT_EQ(reason("0 0 0 1 0 0 1 0 0 1 0 0 # trailing comment"), "expected 12 numbers, found 15");
  EXPECT_EQ(reason(std::string("0 0 0 1 0 0 1 0 0 1 0 0\0x", 25)), "field 12: '0\\x00x' is not a number");
}

TEST(Format, ShortestRoundTripsEveryDouble) {
  for (double x : {0.1, -0.0, 1e-320, 0x1p-1074, 1.7976931348623157e308, 1.0 / 3, 123456789.0,
                   std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()}) {
    const std::string s = format_shortest(x);
    const double back = std::strtod(s.c_str(), nullptr);
    EXPECT_EQ(std::memcmp(&back, &x, sizeof x), 0) << s;
    const std::string h = format_hex(x);
    const double back_hex = std::strtod(h.c_str(), nullptr);
    EXPECT_EQ(std::memcmp(&back_hex, &x, sizeof x), 0) << h;
  }
  EXPECT_EQ(format_shortest(-0.0), "-0");
  EXPECT_EQ(format_shortest(0.1), "0.1");
  EXPECT_EQ(format_hex(1.5), "0x1.8p+0");
  EXPECT_EQ(format_hex(-std::numeric_limits<double>::infinity()), "-inf");
}

// ---- classify on streams -------------------------------------------------------------------------------

std::string classify(const std::string& input, const ClassifyOptions& options, int* status = nullptr,
                     std::string* errors = nullptr) {
  std::istringstream in(input);
  std::ostringstream out, err;
  ClassifyCounts counts;
  const int s = classify_stream(in, out, err, options, counts);
  if (status) *status = s;
  if (errors) *errors = err.str();
  return out.str();
}

TEST(Classify, OneOutputLinePerQueryLine) {
  // Hand-derived: line 2 → hit 5 (seed example), line 4 → behind −5, line 5 → parallel, line 6 → in-plane.
  const std::string input =
      "# comment\n"
      "0 0 0  0 0 1  0 0 5  0 0 1\n"
      "\n"
      "0 0 10  0 0 1  0 0 5  0 0 1\n"
      "0 0 0  1 0 0  0 0 5  0 0 1\n"
      "1 2 5  1 -1 0  0 0 5  0 0 1\n";
  int status = -1;
  EXPECT_EQ(classify(input, {}, &status), "hit 5\nbehind -5\nparallel\nin-plane\n");
  EXPECT_EQ(status, exit_ok);
}

TEST(Classify, InvalidLinesAreAnsweredAndReportedWithTheirLineNumber) {
  const std::string input = "0 0 0 0 0 0 1 0 0 1 0 0\n\n0 0 0 1 0 0 1 0 0 0 -0 0\n0 0 0 1 0 0 1 0 0 1\n0 0 0  0 0 1  0 0 5  0 0 1\n";
  int status = -1;
  std::string err;
  const std::string out = classify(input, {}, &status, &err);
  EXPECT_EQ(out,
            "invalid ray direction is the zero vector\n"
            "invalid plane normal is the zero vector\n"
            "invalid expected 12 numbers, found 10\n"
            "hit 5\n");
  EXPECT_EQ(err,
            "raykernel: line 1: ray direction is the zero vector\n"
            "raykernel: line 3: plane normal is the zero vector\n"
            "raykernel: line 4: expected 12 numbers, found 10\n");
  EXPECT_EQ(status, exit_invalid_line);
}

TEST(Classify, ExactTAndHex) {
  // num = 1, den = 10: t = 0.1 rounded; exact 1/10.
  ClassifyOptions o;
  o.exact_t = true;
  EXPECT_EQ(classify("0 0 0 10 0 0 1 0 0 1 0 0\n", o), "hit 0.1 1/10\n");
  o.hex = true;
  EXPECT_EQ(classify("0 0 0 10 0 0 1 0 0 1 0 0\n", o), "hit 0x1.999999999999ap-4 1/10\n");
  // Signed zero: t = −2^-1174 → behind -0 (hand-derived in contract_test.cpp).
  EXPECT_EQ(classify("0x1p-1074 0 0 0x1p100 0 0 0 0 0 1 0 0\n", {}), "behind -0\n");
}

TEST(Classify, NaivePathShowsTheLecturesMistakes) {
  // Products that underflow: the exact answer is hit 1; in plain doubles both d·n and (p − o)·n underflow
  // to 0, so the naive path calls the ray in-plane.
  const std::string line = "0 0 0 0x1p-600 0 0 0x1p-600 0 0 0x1p-600 0 0\n";
  ClassifyOptions naive;
  naive.path = Path::naive;
  EXPECT_EQ(classify(line, {}), "hit 1\n");
  EXPECT_EQ(classify(line, naive), "in-plane\n");
  ClassifyOptions exact;
  exact.path = Path::exact;
  EXPECT_EQ(classify(line, exact), "hit 1\n");
}

TEST(Classify, ContractSampleOnEveryPathThatGuarantees) {
  const auto input_lines = test_support::read_lines(cases + "/classify-sample.txt");
  const auto expected = test_support::read_lines(cases + "/classify-sample.expected");
  std::string input;
  for (const auto& l : input_lines) input += l + "\n";
  for (Path path : {Path::certified, Path::exact}) {
    ClassifyOptions o;
    o.exact_t = true;
    o.path = path;
    int status = -1;
    std::istringstream out(classify(input, o, &status));
    std::vector<std::string> got;
    for (std::string l; std::getline(out, l);) got.push_back(l);
    ASSERT_EQ(got.size(), expected.size());
    for (std::size_t i = 0; i < got.size(); ++i)
      EXPECT_TRUE(test_support::same_classify_answer(got[i], expected[i])) << "answer " << i + 1 << "\n  got:  " << got[i]
                                                                   << "\n  want: " << expected[i];
    EXPECT_EQ(status, exit_invalid_line);
  }
}

// ---- The binary ----------------------------------------------------------------------------------------

TEST(Binary, ContractSampleEndToEnd) {
  const CliRun r = run("classify --exact-t " + cases + "/classify-sample.txt");
  EXPECT_EQ(r.status, 1) << "the sample has invalid lines";
  const auto expected = test_support::read_lines(cases + "/classify-sample.expected");
  std::istringstream out(r.out);
  std::size_t i = 0, wrong = 0;
  for (std::string l; std::getline(out, l); ++i)
    if (i >= expected.size() || !test_support::same_classify_answer(l, expected[i])) ++wrong;
  EXPECT_EQ(i, expected.size());
  EXPECT_EQ(wrong, 0u);
}

TEST(Binary, ExitStatuses) {
  EXPECT_EQ(run("classify", "0 0 0 0 0 1 0 0 5 0 0 1\n").status, 0);
  EXPECT_EQ(run("classify -", "0 0 0 0 0 0 0 0 5 0 0 1\n").status, 1);
  EXPECT_EQ(run("classify --bogus").status, 2);
  EXPECT_EQ(run("classify --path=fast").status, 2);
  EXPECT_EQ(run("classify /nonexistent/file").status, 2);
  EXPECT_EQ(run("classify a b").status, 2);
  EXPECT_EQ(run("nonsense").status, 2);
  const CliRun version_run = run("--version");
  EXPECT_EQ(version_run.status, 0);
  EXPECT_EQ(version_run.out, "raykernel 0.1.0\n");
  const CliRun overview = run("");
  EXPECT_EQ(overview.status, 0);
  EXPECT_NE(overview.out.find("classify"), std::string::npos);
  for (const char* sub : {"classify --help", "demo --help"}) {
    const CliRun help = run(sub);
    EXPECT_EQ(help.status, 0) << sub;
    EXPECT_NE(help.out.find("usage: raykernel"), std::string::npos) << sub;
  }
}

TEST(Binary, StatsNameEveryStage) {
  const CliRun r = run("classify --stats", "0 0 0 0 0 1 0 0 5 0 0 1\n1 -2 1 1 1 -2 0 0 0 1 1 1\n");
  EXPECT_EQ(r.out, "hit 5\nin-plane\n");
  for (const char* word : {"filter", "compensated", "expansion", "exact", "2 queries"})
    EXPECT_NE(r.err.find(word), std::string::npos) << word << " in: " << r.err;
}

TEST(Binary, ADirectoryIsAnIoError) { EXPECT_EQ(run("classify " + cases).status, 2); }

}  // namespace
}  // namespace raykernel::cli
