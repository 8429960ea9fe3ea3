// The CLI (docs/contract.md §3): the number syntax, the output format, invalid lines, exit statuses, and the
// contract's sample cases run through the real binary.
#include "commands/plane_classify.hpp"
#include "commands/plane_nearest.hpp"
#include "support/answer_lines.hpp"
#include "common/text_input.hpp"

#include "common/text_format.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>

#include <array>
#include <csignal>
#include <filesystem>
#include <thread>
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
  const NumberLine l = parse_number_line(" 1 -2.5 3e2\t0x1.8p1 .5 5. +7 -0 0e-400 0X10 0x1p-1074 4.9e-324 ", 12);
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
  EXPECT_EQ(reason("0 0 0 1 0 0 1 0 0 1 abc 0"), "field 11: 'abc' is not a number");
  EXPECT_EQ(reason("0 0 0 1 0 0 1 0 0 1 1.0x 0"), "field 11: '1.0x' is not a number");
  // Said once, not "not finite (non-finite)".
  EXPECT_EQ(reason("nan 0 0 1 0 0 0 0 0 1 0 0"), "field 1: 'nan' is not finite");
  EXPECT_EQ(reason("0 0 0 -inf 0 0 1 0 0 1 0 0"), "field 4: '-inf' is not finite");
  EXPECT_EQ(reason("0 0 0 1 0 0 1e400 0 0 1 0 0"), "field 7: '1e400' overflows the double range");
  EXPECT_EQ(reason(std::string("0 0 0 1 0 0 1 0 0 1 0 0\0x", 25)), "field 12: '0\\x00x' is not a number");
}

TEST(NumberLine, SaysWhereExtraTokensStart) {
  // Tokens 13 and 14 ("#" at column 25, "x"): a comment after the numbers is not a comment line.
  const NumberLine comment = parse_number_line("0 0 0 1 0 0 1 0 0 1 0 0 # x", 12);
  ASSERT_EQ(comment.status, LineStatus::invalid);
  EXPECT_EQ(comment.reason,
            "expected 12 numbers, found 14; the extra ones start at token 13, column 25: '# x' (a # comment must be on "
            "a line of its own)");
  EXPECT_EQ(parse_number_line("1 2 3 4 5 6   7\r", 6).reason,
            "expected 6 numbers, found 7; the extra ones start at token 7, column 15: '7'");
}

TEST(NumberLine, NamesTheBadTokenOfACommaSeparatedLine) {
  // Four tokens, but the count is not the problem: the first token is.
  EXPECT_EQ(parse_number_line("0,0,0 0,0,1 0,0,5 0,0,1", 12).reason,
            "field 1: '0,0,0' is not a number (separate numbers with blanks, not commas)");
  EXPECT_EQ(parse_number_line("0, 0, 0, 0, 0, 1", 6).reason,
            "field 1: '0,' is not a number (separate numbers with blanks, not commas)");
}

TEST(NumberLine, ANonzeroNumberThatRoundsToZeroIsInvalid) {
  // 2^-1075 is half the smallest subnormal 2^-1074: every magnitude up to it rounds to zero (2^-1075 itself
  // is a tie, to the even 0); 4e-324 and 2.4703282292062328e-324 are above it and round to 2^-1074.
  const std::string why = " is nonzero but rounds to zero when read (its magnitude is at most 2^-1075, half the "
                          "smallest subnormal)";
  EXPECT_EQ(parse_number_line("0 0 0 1e-400 0 0", 6).reason, "field 4: '1e-400'" + why);
  EXPECT_EQ(parse_number_line("-2e-324 0 0 1 0 0", 6).reason, "field 1: '-2e-324'" + why);
  EXPECT_EQ(parse_number_line("0 0x1p-1075 0 1 0 0", 6).reason, "field 2: '0x1p-1075'" + why);
  EXPECT_EQ(parse_number_line("0 0 2.4703282292062327e-324 1 0 0", 6).reason, "field 3: '2.4703282292062327e-324'" + why);
  for (const char* subnormal : {"4e-324", "2.4703282292062328e-324", "0x1p-1074", "-0x0.0000000000001p-1022"}) {
    const NumberLine l = parse_number_line(std::string("0 0 0 ") + subnormal + " 0 0", 6);
    ASSERT_EQ(l.status, LineStatus::numbers) << subnormal << ": " << l.reason;
    EXPECT_EQ(std::fabs(l.value[3]), 0x1p-1074) << subnormal;
  }
  for (const char* zero : {"0e-400", "-0.000e-999", "0x0p-2000", "0x0.000p+5"}) {
    const NumberLine l = parse_number_line(std::string("0 0 0 1 0 0 ") + zero, 7);
    EXPECT_EQ(l.status, LineStatus::numbers) << zero << ": " << l.reason;
  }
}

TEST(NumberLine, EscapesBytesThatAreNotPrintable) {
  // A control byte, DEL, a byte that is not UTF-8, and a right-to-left override (U+202E), each as \xNN;
  // ordinary UTF-8 (é) passes.
  EXPECT_EQ(parse_number_line("\x01\x7f\xff\xe2\x80\xae\xc3\xa9 0 0 1 0 0", 6).reason,
            "field 1: '\\x01\\x7f\\xff\\xe2\\x80\\xae\xc3\xa9' is not a number");
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

// ---- Text shown to people (text_format.hpp) --------------------------------------------------------------

TEST(TextFormat, CountsPluralsAndPercentages) {
  EXPECT_EQ(with_thousands(0), "0");
  EXPECT_EQ(with_thousands(999), "999");
  EXPECT_EQ(with_thousands(1000), "1,000");
  EXPECT_EQ(with_thousands(2073600), "2,073,600");
  EXPECT_EQ(with_thousands(18446744073709551615u), "18,446,744,073,709,551,615");
  EXPECT_EQ(count_of(1, "plane"), "1 plane");
  EXPECT_EQ(count_of(0, "plane"), "0 planes");
  EXPECT_EQ(count_of(1234, "query", "queries"), "1,234 queries");
  EXPECT_EQ(percent(1, 3), "33.33%");
  EXPECT_EQ(percent(137478, 518400), "26.52%");
  EXPECT_EQ(percent(1, 3, 1), "33.3%");
  EXPECT_EQ(percent(5, 0), "0.00%");
}

TEST(TextFormat, RatesNeverShowZeroPointZeroZero) {
  // Three significant digits in the unit where the value is at least 1 (k from 999.5, M from 999,500).
  EXPECT_EQ(rate(4.31e6, "rays/s"), "4.31 M rays/s");
  EXPECT_EQ(rate(812.4e3, "rays/s"), "812 k rays/s");
  EXPECT_EQ(rate(1234, "rays/s"), "1.23 k rays/s");
  EXPECT_EQ(rate(999.4, "rays/s"), "999 rays/s");
  EXPECT_EQ(rate(999.6, "rays/s"), "1.00 k rays/s");
  EXPECT_EQ(rate(999.6e3, "rays/s"), "1.00 M rays/s");
  EXPECT_EQ(rate(35.2, "rays/s"), "35.2 rays/s");
  EXPECT_EQ(rate(0.004, "rays/s"), "0.004 rays/s");
  EXPECT_EQ(rate(0, "rays/s"), "0 rays/s");
  EXPECT_EQ(duration(0.481), "0.481 s");
  EXPECT_EQ(duration(2.345), "2.35 s");
  EXPECT_EQ(duration(0.0123), "12.3 ms");
  EXPECT_EQ(duration(0.0000851), "85.1 \u00b5s");
}

TEST(TextFormat, PrintableEscapesWhatATerminalWouldNotShow) {
  EXPECT_EQ(printable("plain text, UTF-8 \xc3\xa9 \xe2\x82\xac"), "plain text, UTF-8 \xc3\xa9 \xe2\x82\xac");
  EXPECT_EQ(printable(std::string("a\0b\n\t\x1b[0m\x7f", 10)), "a\\x00b\\x0a\\x09\\x1b[0m\\x7f");
  // Not UTF-8: a lone continuation byte, a truncated sequence, an overlong form, a surrogate.
  EXPECT_EQ(printable("\x80 \xc3 \xc0\xaf \xed\xa0\x80"), "\\x80 \\xc3 \\xc0\\xaf \\xed\\xa0\\x80");
  // Characters that print as nothing or reorder text: a C1 control, a zero-width space, a right-to-left
  // override, the byte-order mark.
  EXPECT_EQ(printable("\xc2\x85|\xe2\x80\x8b|\xe2\x80\xae|\xef\xbb\xbf"),
            "\\xc2\\x85|\\xe2\\x80\\x8b|\\xe2\\x80\\xae|\\xef\\xbb\\xbf");
  // A hostile-input probe's finds: a no-break space, a soft hyphen, the Arabic letter mark, a Hangul filler, a tag.
  EXPECT_EQ(printable("\xc2\xa0|\xc2\xad|\xd8\x9c|\xe1\x85\x9f|\xf3\xa0\x80\x81"),
            "\\xc2\\xa0|\\xc2\\xad|\\xd8\\x9c|\\xe1\\x85\\x9f|\\xf3\\xa0\\x80\\x81");
  // The ends of the ranges, and their neighbours that print: U+00A1 ¡, U+2010 ‐, U+3001 、, U+FFFD �.
  EXPECT_EQ(printable("\xc2\xa1\xe2\x80\x90\xe3\x80\x81\xef\xbf\xbd"), "\xc2\xa1\xe2\x80\x90\xe3\x80\x81\xef\xbf\xbd");
  // An ideographic space, a variation selector, a private-use character, the noncharacters U+FFFE and U+1FFFF.
  EXPECT_EQ(printable("\xe3\x80\x80\xef\xb8\x8f\xee\x80\x80\xef\xbf\xbe\xf0\x9f\xbf\xbf"),
            "\\xe3\\x80\\x80\\xef\\xb8\\x8f\\xee\\x80\\x80\\xef\\xbf\\xbe\\xf0\\x9f\\xbf\\xbf");
  EXPECT_EQ(quote("abc"), "'abc'");
  EXPECT_EQ(quote(std::string(50, 'x')), "'" + std::string(40, 'x') + "...'");
  // Cut before a character, not inside it: 39 ASCII bytes and a 2-byte é straddling byte 40.
  EXPECT_EQ(quote(std::string(39, 'x') + "\xc3\xa9yz"), "'" + std::string(39, 'x') + "...'");
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
  // Hand-derived: line 2 → hit 5 (the example of docs/ray-casting.md §2), line 4 → behind −5, line 5 → parallel, line 6 → in-plane.
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

TEST(Classify, SkipsAByteOrderMarkAtTheStartOnly) {
  // The UTF-8 byte-order mark some editors write: ignored at the start of the input (even before a comment
  // or a blank line), an invalid byte sequence anywhere else (escaped in the message).
  EXPECT_EQ(classify("\xEF\xBB\xBF" "0 0 0  0 0 1  0 0 5  0 0 1\n", {}), "hit 5\n");
  EXPECT_EQ(classify("\xEF\xBB\xBF" "# comment\n0 0 0  0 0 1  0 0 5  0 0 1\n", {}), "hit 5\n");
  EXPECT_EQ(classify("\xEF\xBB\xBF\n0 0 0  0 0 1  0 0 5  0 0 1\n", {}), "hit 5\n");
  std::string err;
  EXPECT_EQ(classify("0 0 0  0 0 1  0 0 5  0 0 1\n\xEF\xBB\xBF" "0 0 0  0 0 1  0 0 5  0 0 1\n", {}, nullptr, &err),
            "hit 5\ninvalid field 1: '\\xef\\xbb\\xbf0' is not a number\n");
  EXPECT_EQ(err, "raykernel: line 2: field 1: '\\xef\\xbb\\xbf0' is not a number\n");
}

TEST(Classify, ADirectionThatRoundsToZeroIsNotCalledTheZeroVector) {
  // 1e-400 read as a double is 0; the line is invalid for that reason, not for a zero direction. 4e-324
  // reads as 2^-1074: a valid direction, and t = 1/2^-1074 overflows to inf (hand-derived: num = 1·1,
  // den = 2^-1074·1).
  int status = -1;
  EXPECT_EQ(classify("0 0 0  1e-400 0 0  1 0 0  1 0 0\n0 0 0  4e-324 0 0  1 0 0  1 0 0\n", {}, &status),
            "invalid field 4: '1e-400' is nonzero but rounds to zero when read (its magnitude is at most 2^-1075, half "
            "the smallest subnormal)\nhit inf\n");
  EXPECT_EQ(status, exit_invalid_line);
}

// An output stream buffer that accepts `capacity` bytes and then fails, like a pipe whose reader left.
class FailingAfter : public std::streambuf {
 public:
  explicit FailingAfter(std::size_t capacity) : capacity_(capacity) {}

 protected:
  int_type overflow(int_type c) override {
    if (written_ >= capacity_) return traits_type::eof();
    ++written_;
    return c;
  }

 private:
  std::size_t capacity_, written_ = 0;
};

TEST(Classify, StopsReadingWhenItsOutputFails) {
  // classify: 10,000 queries answered "hit 5"; nearest: 10,000 rays answered "hit 0 5". The output takes 60
  // bytes (a few answers) and then fails: the streams must stop at once, not read and compute the rest.
  for (bool nearest : {false, true}) {
    const std::string line = nearest ? "0 0 0  0 0 1\n" : "0 0 0  0 0 1  0 0 5  0 0 1\n";
    std::string input;
    for (int k = 0; k < 10000; ++k) input += line;
    std::istringstream in(input);
    FailingAfter sink(60);
    std::ostream out(&sink);
    std::ostringstream err;
    std::uint64_t answered = 0;
    if (nearest) {
      const std::vector<Plane> planes = {{{0, 0, 5}, {0, 0, 1}}};
      NearestCounts counts;
      (void)nearest_stream(in, out, err, planes, {}, counts);
      answered = counts.lines_answered;
    } else {
      ClassifyCounts counts;
      (void)classify_stream(in, out, err, {}, counts);
      answered = counts.lines_answered;
    }
    EXPECT_FALSE(out);
    EXPECT_LE(answered, 11u) << (nearest ? "nearest" : "classify");
    EXPECT_LT(static_cast<std::size_t>(in.tellg()), 12 * line.size()) << (nearest ? "nearest" : "classify");
  }
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
  // Signed zero: t = −2^-1174 → behind -0 (hand-derived in plane_contract_test.cpp).
  EXPECT_EQ(classify("0x1p-1074 0 0 0x1p100 0 0 0 0 0 1 0 0\n", {}), "behind -0\n");
}

TEST(Classify, NaivePathShowsTheLecturesMistakes) {
  // Products that underflow: the exact answer is hit 1; in plain doubles both d·n and (p − o)·n underflow
  // to 0, so the naive path calls the ray in-plane.
  const std::string line = "0 0 0 0x1p-600 0 0 0x1p-600 0 0 0x1p-600 0 0\n";
  ClassifyOptions naive;
  naive.method = Method::naive;
  EXPECT_EQ(classify(line, {}), "hit 1\n");
  EXPECT_EQ(classify(line, naive), "in-plane\n");
  ClassifyOptions exact;
  exact.method = Method::exact;
  EXPECT_EQ(classify(line, exact), "hit 1\n");
}

TEST(Classify, ContractSampleOnEveryPathThatGuarantees) {
  const auto input_lines = test_support::read_lines(cases + "/classify-sample.txt");
  const auto expected = test_support::read_lines(cases + "/classify-sample.expected");
  std::string input;
  for (const auto& l : input_lines) input += l + "\n";
  for (Method method : {Method::certified, Method::exact}) {
    ClassifyOptions o;
    o.exact_t = true;
    o.method = method;
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

// ---- Every write checked -------------------------------------------------------------------------------

std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "/raykernel_cli_test_" + std::to_string(getpid()) + "_" + name;
}
void write_file(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
}

// Runs the binary with standard output sent to `stdout_target` (a path such as /dev/full); returns the status
// and standard error.
CliRun run_to(const std::string& args, const std::string& stdout_target, const std::string& stdin_text = "") {
  const std::string in = temp_path("stdin.txt"), err = temp_path("stderr.txt");
  write_file(in, stdin_text);
  const int status = std::system((cli + " " + args + " < " + in + " > " + stdout_target + " 2> " + err).c_str());
  CliRun r{};
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err);
  std::stringstream text;
  text << e.rdbuf();
  r.err = text.str();
  return r;
}

const std::string disk_full = "raykernel: I/O error writing standard output: No space left on device\n";

TEST(WriteErrors, EveryCommandExitsWithTwoWhenStandardOutputIsFull) {
  const std::string planes = temp_path("planes.txt");
  write_file(planes, "0 0 5 0 0 1\n");
  const std::string query = "0 0 0 0 0 1 0 0 5 0 0 1\n";
  const std::string png = temp_path("full.png");
  const struct {
    std::string args, input;
  } commands[] = {
      {"", ""},
      {"--help", ""},
      {"--version", ""},
      {"classify --help", ""},
      {"nearest --help", ""},
      {"render --help", ""},
      {"demo --help", ""},
      {"render --print-demo-scene", ""},
      {"demo --per-kind 3", ""},
      {"classify", query},
      {"classify --stats", query},
      {"nearest --planes " + planes, "0 0 0 0 0 1\n"},
      {"render --width 4 --height 2 --no-progress -o " + png, ""},
  };
  for (const auto& c : commands) {
    const CliRun r = run_to(c.args, "/dev/full", c.input);
    EXPECT_EQ(r.status, 2) << "raykernel " << c.args;
    EXPECT_EQ(r.err, disk_full) << "raykernel " << c.args;
  }
}

// Regression: --stats 2>/dev/full exited 0 with the statistics lost. A failed write to standard error is an I/O
// error too (exit 2), whatever else the command did; standard output is still complete.
TEST(WriteErrors, AFailedWriteToStandardErrorIsExitStatusTwo) {
  const std::string planes = temp_path("planes-stderr.txt");
  write_file(planes, "0 0 5 0 0 1\n");
  const std::string query = "0 0 0 0 0 1 0 0 5 0 0 1\n";
  for (const std::string& args : {std::string("classify --stats"), "nearest --stats --planes " + planes}) {
    const std::string input = temp_path("stdin-stderr.txt");
    write_file(input, args.starts_with("classify") ? query : "0 0 0 0 0 1\n");
    const int full = std::system((cli + " " + args + " < " + input + " > /dev/null 2> /dev/full").c_str());
    ASSERT_TRUE(WIFEXITED(full)) << args;
    EXPECT_EQ(WEXITSTATUS(full), 2) << args;
    // The same command with standard error writable: exit 0.
    const int fine = std::system((cli + " " + args + " < " + input + " > /dev/null 2> /dev/null").c_str());
    ASSERT_TRUE(WIFEXITED(fine)) << args;
    EXPECT_EQ(WEXITSTATUS(fine), 0) << args;
  }
}

// Regression: `classify < /dev/zero` grew to 2.1 GB before "read failed". A line is at most 1 MiB: a longer one
// ends the input as a read error naming the line and the limit, after the lines before it were answered.
TEST(Input, ALineLongerThanTheLimitEndsTheInputWithANamedError) {
  const std::string query = "0 0 0 0 0 1 0 0 5 0 0 1\n";
  const CliRun r = run("classify", query + std::string((1u << 20) + 1, '0') + "\n" + query);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out, "hit 5\n");
  EXPECT_EQ(r.err, "raykernel classify: I/O error reading standard input: line 2 is longer than 1,048,576 bytes, the longest line raykernel reads\n");
  // Exactly the limit is a line like any other (here an invalid one).
  const CliRun at_limit = run("classify", std::string(1u << 20, '0') + "\n" + query);
  EXPECT_EQ(at_limit.status, 1) << at_limit.err;
  EXPECT_EQ(at_limit.out.substr(at_limit.out.size() - 6), "hit 5\n");
  // /dev/zero: one endless line of NUL bytes; memory stays bounded and the command ends.
  const int status = std::system((cli + " classify < /dev/zero > /dev/null 2> /dev/null").c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2);
}

// The binary with `args`, `lines` copies of `line` written to its standard input by a thread, and a reader
// of its standard output that reads one byte and closes the pipe; SIGPIPE is ignored (in the child too), so
// writes to the closed pipe fail with EPIPE.
struct ClosedReaderRun {
  int status = -1;
  std::string err;
  bool input_all_written = false;
};
ClosedReaderRun run_with_closed_reader(const std::vector<std::string>& args, const std::string& line, int lines) {
  std::signal(SIGPIPE, SIG_IGN);
  int in[2], out[2];
  if (pipe(in) != 0 || pipe(out) != 0) return {};
  const std::string err_path = temp_path("closed_reader_stderr.txt");
  const pid_t child = fork();
  if (child == 0) {
    dup2(in[0], 0);
    dup2(out[1], 1);
    const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(err, 2);
    for (int fd : {in[0], in[1], out[0], out[1], err}) close(fd);
    std::vector<char*> argv{const_cast<char*>(cli.c_str())};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(cli.c_str(), argv.data());
    _exit(127);
  }
  close(in[0]);
  close(out[1]);
  ClosedReaderRun r;
  std::thread writer([&] {
    std::string block;
    for (int k = 0; k < 1000; ++k) block += line;
    bool ok = true;
    for (int k = 0; ok && k < lines / 1000; ++k)
      for (std::size_t done = 0; ok && done < block.size();) {
        const ssize_t n = write(in[1], block.data() + done, block.size() - done);
        ok = n > 0;
        if (ok) done += static_cast<std::size_t>(n);
      }
    r.input_all_written = ok;
    close(in[1]);
  });
  char byte = 0;
  EXPECT_EQ(read(out[0], &byte, 1), 1);
  close(out[0]);
  int status = 0;
  waitpid(child, &status, 0);
  writer.join();
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err_path);
  std::stringstream text;
  text << e.rdbuf();
  r.err = text.str();
  return r;
}

TEST(WriteErrors, ClassifyAndNearestStopReadingWhenTheReaderLeaves) {
  // 400,000 input lines (10 MB for classify). A command that kept reading after its output broke would
  // consume all of them; one that stops exits after the first failed write, and the rest of the input is
  // never written (the writer gets EPIPE once the command has exited).
  const std::string planes = temp_path("closed_reader_planes.txt");
  write_file(planes, "0 0 5 0 0 1\n");
  const ClosedReaderRun classify = run_with_closed_reader({"classify"}, "0 0 0 0 0 1 0 0 5 0 0 1\n", 400000);
  EXPECT_EQ(classify.status, 2);
  EXPECT_EQ(classify.err, "raykernel: I/O error writing standard output: Broken pipe\n");
  EXPECT_FALSE(classify.input_all_written);
  const ClosedReaderRun nearest = run_with_closed_reader({"nearest", "--planes", planes}, "0 0 0 0 0 1\n", 400000);
  EXPECT_EQ(nearest.status, 2);
  EXPECT_EQ(nearest.err, "raykernel: I/O error writing standard output: Broken pipe\n");
  EXPECT_FALSE(nearest.input_all_written);
}

// ---- Messages ------------------------------------------------------------------------------------------

TEST(Messages, OpenFailuresGiveTheFileAndTheSystemsReason) {
  const std::string dir = ::testing::TempDir();
  EXPECT_EQ(run("classify /nonexistent/queries.txt").err,
            "raykernel classify: cannot open file '/nonexistent/queries.txt': No such file or directory\n");
  CliRun r = run("classify " + dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "raykernel classify: cannot open file '" + dir + "': Is a directory\n");
  const std::string planes = temp_path("open_planes.txt");
  write_file(planes, "0 0 5 0 0 1\n");
  r = run("nearest --planes " + dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "raykernel nearest: cannot open planes file '" + dir + "': Is a directory\n");
  r = run("nearest --planes " + planes + " /nonexistent/rays.txt");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "raykernel nearest: cannot open rays file '/nonexistent/rays.txt': No such file or directory\n");
  if (geteuid() != 0) {  // root reads every file
    const std::string locked = temp_path("locked.txt");
    write_file(locked, "0 0 0 0 0 1 0 0 5 0 0 1\n");
    chmod(locked.c_str(), 0);
    EXPECT_EQ(run("classify " + locked).err, "raykernel classify: cannot open file '" + locked + "': Permission denied\n");
  }
}

TEST(Messages, BytesThatAreNotPrintableAreEscapedEverywhere) {
  // A file name, an option and a command with a control byte (0x01) and an escape (0x1b): shown as \x01 and
  // \x1b, never raw, so a message cannot move the cursor or change a terminal's colours.
  const std::string odd = "\"$(printf '/nonexistent/a\\001b\\033[31m')\"";
  EXPECT_EQ(run("classify " + odd).err,
            "raykernel classify: cannot open file '/nonexistent/a\\x01b\\x1b[31m': No such file or directory\n");
  EXPECT_EQ(run("nearest --planes " + odd).err,
            "raykernel nearest: cannot open planes file '/nonexistent/a\\x01b\\x1b[31m': No such file or directory\n");
  EXPECT_EQ(run("classify \"$(printf -- '--x\\001')\"").err,
            "raykernel classify: unknown option '--x\\x01' (see raykernel classify --help)\n");
  EXPECT_EQ(run("\"$(printf 'x\\033')\"").err.rfind("raykernel: unknown command 'x\\x1b'\n", 0), 0u);
}

// ---- Options -------------------------------------------------------------------------------------------

TEST(Options, DoubleDashEndsTheOptions) {
  // A query file whose name starts with '-': an option before "--", the file after it.
  const std::string dir = temp_path("dashdir");
  std::filesystem::create_directories(dir);
  write_file(dir + "/-q.txt", "0 0 0 0 0 1 0 0 5 0 0 1\n");
  write_file(dir + "/-p.txt", "0 0 5 0 0 1\n");
  write_file(dir + "/-r.txt", "0 0 0 0 0 1\n");
  const std::string in_dir = "cd '" + dir + "' && " + cli;
  auto shell = [&](const std::string& args) {
    FILE* p = popen((in_dir + " " + args + " 2>&1").c_str(), "r");
    std::string out;
    char buf[4096];
    for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
    const int status = pclose(p);
    return std::make_pair(WIFEXITED(status) ? WEXITSTATUS(status) : -1, out);
  };
  EXPECT_EQ(shell("classify -- -q.txt"), std::make_pair(0, std::string("hit 5\n")));
  EXPECT_EQ(shell("classify --exact-t -- -q.txt"), std::make_pair(0, std::string("hit 5 5/1\n")));
  EXPECT_EQ(shell("classify -q.txt").first, 2);  // an unknown option
  EXPECT_EQ(shell("nearest --planes -p.txt -- -r.txt"), std::make_pair(0, std::string("hit 0 5\n")));
  EXPECT_EQ(shell("classify -- -q.txt --hex").first, 2);  // "--hex" after "--" is a second file
}

TEST(Options, EveryCommandRefusesASecondFileOperandNamingBoth) {
  // Each command takes one file operand; the message names the command, what the operand is, and both files
  // (neither needs to exist: the arguments are checked before anything is opened).
  const std::pair<const char*, const char*> commands[] = {
      {"classify", "input file"}, {"triangle", "input file"}, {"nearest --planes p.txt", "rays file"},
      {"inside --mesh m.obj", "points file"}, {"render", "scene file"}, {"watertight", "mesh file"}};
  for (const auto& [command, what] : commands) {
    const CliRun r = run(std::string(command) + " first.txt second.txt");
    const std::string name = std::string(command).substr(0, std::string(command).find(' '));
    EXPECT_EQ(r.status, 2) << command;
    EXPECT_EQ(r.err, "raykernel " + name + ": more than one " + what + " ('first.txt', 'second.txt')\n") << command;
  }
}

TEST(Options, DemoValuesAreCheckedNotClamped) {
  CliRun r = run("demo --per-kind");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "raykernel demo: --per-kind needs a value (an integer from 1 to 100000000)\n");
  r = run("demo --seed");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "raykernel demo: --seed needs a value (an integer from 0 to 18446744073709551615)\n");
  // 2^64 and above, and negative values (strtoull would wrap -1 to 2^64 − 1), are refused.
  for (const char* seed : {"18446744073709551616", "99999999999999999999999", "-1", "+5", "0x10", " 7"}) {
    r = run(std::string("demo --per-kind 1 --seed '") + seed + "'");
    EXPECT_EQ(r.status, 2) << seed;
    EXPECT_EQ(r.err, std::string("raykernel demo: bad value for --seed: '") + seed +
                         "' (an integer from 0 to 18446744073709551615)\n");
  }
  for (const char* per_kind : {"0", "100000001", "1e3"}) {
    r = run(std::string("demo --per-kind ") + per_kind);
    EXPECT_EQ(r.status, 2) << per_kind;
  }
  // The largest seed is accepted, and both spellings of an option work.
  r = run("demo --per-kind=2 --seed=18446744073709551615");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("(seed 18446744073709551615)"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace raykernel::cli
