// Comparing CLI answer lines with the contract's expected answers the way tests/data/contract-cases/README.md states:
// the word after `invalid` is free; T is compared as the double it reads back to (the sign of a zero
// matters when the exact t is not zero); the exact t is compared as a rational.
#pragma once

#include <gmpxx.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace raykernel::test_support {

inline std::vector<std::string> words(const std::string& line) {
  std::istringstream s(line);
  std::vector<std::string> w;
  for (std::string x; s >> x;) w.push_back(x);
  return w;
}

inline std::vector<std::string> read_lines(const std::string& path) {
  std::ifstream f(path);
  std::vector<std::string> lines;
  for (std::string l; std::getline(f, l);) lines.push_back(l);
  return lines;
}

inline bool parse_rational(const std::string& text, mpq_class& q) {
  if (q.set_str(text, 10) != 0 || q.get_den() == 0) return false;
  q.canonicalize();
  return true;
}

inline bool same_t(const std::string& got, const std::string& want, const mpq_class& exact) {
  const double g = std::strtod(got.c_str(), nullptr), w = std::strtod(want.c_str(), nullptr);
  if (g != w) return false;
  return w != 0 || exact == 0 || std::signbit(g) == std::signbit(w);
}

// One line of `raykernel classify --exact-t` output against the expected line.
inline bool same_classify_answer(const std::string& got_line, const std::string& want_line) {
  const auto g = words(got_line), w = words(want_line);
  if (g.empty() || w.empty() || g[0] != w[0]) return false;
  if (w[0] == "invalid") return true;
  if (w[0] == "parallel" || w[0] == "in-plane") return g == w;
  mpq_class exact_want, exact_got;
  if (w.size() != 3 || g.size() != 3 || !parse_rational(w[2], exact_want) || !parse_rational(g[2], exact_got))
    return false;
  return exact_got == exact_want && same_t(g[1], w[1], exact_want);
}

// One line of `raykernel nearest` output against the expected line.
inline bool same_nearest_answer(const std::string& got_line, const std::string& want_line) {
  const auto g = words(got_line), w = words(want_line);
  if (w.empty()) return false;
  if (w[0] == "miss") return g == w;
  if (w[0] == "invalid") return !g.empty() && g[0] == "invalid";
  if (w.size() != 3 || g.size() != 3 || g[0] != w[0] || g[1] != w[1]) return false;
  mpq_class exact;
  if (!parse_rational(w[2], exact)) exact = std::strtod(w[2].c_str(), nullptr);
  return same_t(g[2], w[2], exact);
}

}  // namespace raykernel::test_support
