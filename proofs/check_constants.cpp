// ctest proofs_constants_match: the error constants of the certified stages are exactly the numbers the
// Coq theorems are about.
//
// For every constant it checks, with exact dyadic arithmetic (no rounding anywhere), that three values
// agree with the exact value written in the table below (derived by hand from the Coq definition):
//   1. the right-hand side of `Definition NAME : R := ...` in proofs/core/Constants.v, evaluated exactly;
//   2. the literal of `inline constexpr double NAME = ...;` in the bounds headers (error_bounds.hpp and every
//      header that reopens a bounds namespace: proofs/CMakeLists.txt finds them and passes them in), read from
//      the text exactly (a hexadecimal float, an integer, or a sum or difference of them such as 1.0 - 0x1p-50);
//   3. the value the compiler gave bounds::NAME (this file includes the generated constants_headers.hpp,
//      the #include lines of those headers).
// It also fails when either file defines a constant the table does not know, so a new constant cannot
// escape the comparison, except the constants proofs/pending.txt lists as not proved yet (reported as
// PENDING; listing one that Constants.v defines is an error). `--one-ulp` (ctest
// proofs_constants_one_ulp) checks that the comparison is exact: each compiled constant moved by one ulp
// either way must compare unequal.
//
// Usage: raykernel_check_constants [--one-ulp] BOUNDS_HPP... CONSTANTS_V... PENDING_TXT
// (files told apart by their extension: the headers' constants are merged, and so are the Coq files', read in
// order with one environment, so that a later file may use an earlier file's names).
#include "constants_headers.hpp"  // generated: the headers of the bounds:: constants

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

// ---------------------------------------------------------------------------------------------------
// Exact nonnegative dyadic rationals m · 2^e, m an arbitrary-precision integer (base 2^32 limbs,
// least significant first), normalized so that m is odd or zero.
struct Dyadic {
  std::vector<std::uint32_t> limbs;  // empty for zero
  long exponent = 0;

  static Dyadic integer(std::uint64_t v) {
    Dyadic d;
    while (v != 0) {
      d.limbs.push_back(static_cast<std::uint32_t>(v));
      v >>= 32;
    }
    d.normalize();
    return d;
  }
  static Dyadic pow2(long k) {
    Dyadic d = integer(1);
    d.exponent = k;
    return d;
  }
  bool is_zero() const { return limbs.empty(); }

  void trim() {
    while (!limbs.empty() && limbs.back() == 0) limbs.pop_back();
  }
  // Shift the integer part left by `bits` (value unchanged if exponent is decreased by the caller).
  void shift_left(long bits) {
    if (is_zero() || bits == 0) return;
    const long words = bits / 32, rest = bits % 32;
    std::vector<std::uint32_t> out(limbs.size() + static_cast<std::size_t>(words) + 1, 0);
    for (std::size_t i = 0; i < limbs.size(); ++i) {
      const std::uint64_t v = static_cast<std::uint64_t>(limbs[i]) << rest;
      out[i + static_cast<std::size_t>(words)] |= static_cast<std::uint32_t>(v);
      out[i + static_cast<std::size_t>(words) + 1] |= static_cast<std::uint32_t>(v >> 32);
    }
    limbs = out;
    trim();
  }
  void normalize() {
    trim();
    if (is_zero()) {
      exponent = 0;
      return;
    }
    // Remove trailing zero bits.
    long zeros = 0;
    std::size_t i = 0;
    while (limbs[i] == 0) {
      zeros += 32;
      ++i;
    }
    std::uint32_t w = limbs[i];
    while ((w & 1u) == 0) {
      w >>= 1;
      ++zeros;
    }
    if (zeros == 0) return;
    const long words = zeros / 32, rest = zeros % 32;
    std::vector<std::uint32_t> out(limbs.size() - static_cast<std::size_t>(words), 0);
    for (std::size_t j = 0; j < out.size(); ++j) {
      std::uint64_t v = limbs[j + static_cast<std::size_t>(words)];
      if (j + static_cast<std::size_t>(words) + 1 < limbs.size())
        v |= static_cast<std::uint64_t>(limbs[j + static_cast<std::size_t>(words) + 1]) << 32;
      out[j] = static_cast<std::uint32_t>(v >> rest);
    }
    limbs = out;
    exponent += zeros;
    trim();
  }
  long bit_length() const {
    if (is_zero()) return 0;
    long n = static_cast<long>(limbs.size() - 1) * 32;
    for (std::uint32_t w = limbs.back(); w != 0; w >>= 1) ++n;
    return n;
  }

  friend Dyadic operator+(Dyadic a, Dyadic b) {
    if (a.is_zero()) return b;
    if (b.is_zero()) return a;
    const long e = std::min(a.exponent, b.exponent);
    a.shift_left(a.exponent - e);
    b.shift_left(b.exponent - e);
    Dyadic r;
    r.exponent = e;
    r.limbs.assign(std::max(a.limbs.size(), b.limbs.size()) + 1, 0);
    std::uint64_t carry = 0;
    for (std::size_t i = 0; i < r.limbs.size(); ++i) {
      std::uint64_t s = carry;
      if (i < a.limbs.size()) s += a.limbs[i];
      if (i < b.limbs.size()) s += b.limbs[i];
      r.limbs[i] = static_cast<std::uint32_t>(s);
      carry = s >> 32;
    }
    r.normalize();
    return r;
  }
  // a − b, for a ≥ b (the constants are nonnegative).
  friend Dyadic operator-(Dyadic a, Dyadic b) {
    if (b.is_zero()) return a;
    const long e = std::min(a.exponent, b.exponent);
    a.shift_left(a.exponent - e);
    b.shift_left(b.exponent - e);
    if (b.limbs.size() > a.limbs.size()) throw std::runtime_error("a negative constant");
    Dyadic r;
    r.exponent = e;
    r.limbs.assign(a.limbs.size(), 0);
    std::int64_t borrow = 0;
    for (std::size_t i = 0; i < a.limbs.size(); ++i) {
      std::int64_t d = static_cast<std::int64_t>(a.limbs[i]) - borrow - (i < b.limbs.size() ? b.limbs[i] : 0);
      borrow = d < 0 ? 1 : 0;
      r.limbs[i] = static_cast<std::uint32_t>(d + (borrow << 32));
    }
    if (borrow != 0) throw std::runtime_error("a negative constant");
    r.normalize();
    return r;
  }
  friend Dyadic operator*(const Dyadic& a, const Dyadic& b) {
    Dyadic r;
    if (a.is_zero() || b.is_zero()) return r;
    r.limbs.assign(a.limbs.size() + b.limbs.size(), 0);
    for (std::size_t i = 0; i < a.limbs.size(); ++i) {
      std::uint64_t carry = 0;
      for (std::size_t j = 0; j < b.limbs.size(); ++j) {
        const std::uint64_t t = static_cast<std::uint64_t>(a.limbs[i]) * b.limbs[j] + r.limbs[i + j] + carry;
        r.limbs[i + j] = static_cast<std::uint32_t>(t);
        carry = t >> 32;
      }
      r.limbs[i + b.limbs.size()] = static_cast<std::uint32_t>(carry);
    }
    r.exponent = a.exponent + b.exponent;
    r.normalize();
    return r;
  }
  friend bool operator==(const Dyadic& a, const Dyadic& b) {
    return a.limbs == b.limbs && a.exponent == b.exponent;
  }

  // The exact value of a finite nonnegative double.
  static Dyadic from_double(double x) {
    if (!(x >= 0) || !std::isfinite(x)) throw std::runtime_error("not a finite nonnegative double");
    if (x == 0) return {};
    int e = 0;
    const double m = std::frexp(x, &e);  // x = m · 2^e, m in [0.5, 1), exact
    Dyadic d = integer(static_cast<std::uint64_t>(std::ldexp(m, 53)));  // the 53-bit significand
    d.exponent += e - 53;
    return d;
  }
  // Representable as a binary64 number (53-bit significand, subnormals, below 2^1024).
  bool is_binary64() const {
    if (is_zero()) return true;
    const long bits = bit_length();
    return bits <= 53 && exponent >= -1074 && bits + exponent <= 1024;
  }

  std::string str() const {
    if (is_zero()) return "0";
    std::ostringstream out;
    out << "0x" << std::hex;
    for (std::size_t i = limbs.size(); i-- > 0;) {
      if (i + 1 == limbs.size())
        out << limbs[i];
      else {
        out.width(8);
        out.fill('0');
        out << limbs[i];
      }
    }
    out << std::dec << " * 2^" << exponent;
    return out.str();
  }
};

Dyadic operator*(std::uint64_t k, const Dyadic& d) { return Dyadic::integer(k) * d; }
Dyadic operator+(std::uint64_t k, const Dyadic& d) { return Dyadic::integer(k) + d; }

// ---------------------------------------------------------------------------------------------------
// The table: every constant, the exact value derived from its Coq definition, and the compiled value.
namespace b = raykernel::detail::bounds;
namespace mb = raykernel::bounds;  // the mesh headers' (ray_box.hpp, mesh_predicates.hpp)

struct Row {
  const char* name;
  const char* coq_formula;  // as in proofs/core/Constants.v, for the messages
  Dyadic expected;
  std::optional<double> compiled;   // double constants
  std::optional<long> compiled_int; // int constants
};

std::vector<Row> table() {
  return {
      {"unit_roundoff", "bpow radix2 (-53)", Dyadic::pow2(-53), b::unit_roundoff, {}},
      {"min_subnormal", "bpow radix2 (-1074)", Dyadic::pow2(-1074), b::min_subnormal, {}},
      // (2^53 − 1)·2^971 = 2^1024 − 2^971, std::numeric_limits<double>::max()
      {"largest_finite", "9007199254740991 * bpow radix2 (971)",
       Dyadic::integer((std::uint64_t{1} << 53) - 1) * Dyadic::pow2(971), b::largest_finite, {}},
      {"exact_product_threshold", "bpow radix2 (-968)", Dyadic::pow2(-968), b::exact_product_threshold, {}},
      // (3 + 16u)u = 3·2^-53 + 2^-102
      {"filter_den_relative", "(3 + 16 * u) * u", 3 * Dyadic::pow2(-53) + Dyadic::pow2(-102),
       b::filter_den_relative, {}},
      // (4 + 32u)u = 2^-51 + 2^-101
      {"filter_num_relative", "(4 + 32 * u) * u", Dyadic::pow2(-51) + Dyadic::pow2(-101), b::filter_num_relative,
       {}},
      {"filter_absolute", "3 * mu", 3 * Dyadic::pow2(-1074), b::filter_absolute, {}},
      {"compensated_relative", "bpow radix2 (-101)", Dyadic::pow2(-101), b::compensated_relative, {}},
      {"compensated_absolute", "bpow radix2 (-1070)", Dyadic::pow2(-1070), b::compensated_absolute, {}},
      {"refined_relative", "bpow radix2 (-150)", Dyadic::pow2(-150), b::refined_relative, {}},
      {"refined_low_relative", "bpow radix2 (-52)", Dyadic::pow2(-52), b::refined_low_relative, {}},
      // 8μ = 2^-1071
      {"refined_absolute", "8 * mu", 8 * Dyadic::pow2(-1074), b::refined_absolute, {}},
      {"tail_sum_relative", "bpow radix2 (-48)", Dyadic::pow2(-48), b::tail_sum_relative, {}},
      {"tail_sum_absolute", "2 * mu", 2 * Dyadic::pow2(-1074), b::tail_sum_absolute, {}},
      {"tail_sum_max_terms", "32", Dyadic::integer(32), {}, b::tail_sum_max_terms},
      {"quotient_min_magnitude", "bpow radix2 (-900)", Dyadic::pow2(-900), b::quotient_min_magnitude, {}},
      {"divisor_min_magnitude", "bpow radix2 (-1000)", Dyadic::pow2(-1000), b::divisor_min_magnitude, {}},
      {"divisor_max_magnitude", "bpow radix2 (1000)", Dyadic::pow2(1000), b::divisor_max_magnitude, {}},
      {"half_gap_min_magnitude", "bpow radix2 (-968)", Dyadic::pow2(-968), b::half_gap_min_magnitude, {}},
      {"quotient_relative", "bpow radix2 (-101)", Dyadic::pow2(-101), b::quotient_relative, {}},
      {"quotient_enclosure_factor", "1 + bpow radix2 (-9)", 1 + Dyadic::pow2(-9), b::quotient_enclosure_factor,
       {}},
      {"quotient_test_factor", "1 + bpow radix2 (-45)", 1 + Dyadic::pow2(-45), b::quotient_test_factor, {}},
      // (2 + 16u)u = 2^-52 + 2^-102
      {"compare_filter_relative", "(2 + 16 * u) * u", Dyadic::pow2(-52) + Dyadic::pow2(-102),
       b::compare_filter_relative, {}},
      // 1 + 16u = 1 + 2^-49
      {"compare_propagation_factor", "1 + 16 * u", 1 + Dyadic::pow2(-49), b::compare_propagation_factor, {}},
      // 8μ = 2^-1071
      {"compare_absolute", "8 * mu", 8 * Dyadic::pow2(-1074), b::compare_absolute, {}},
      {"compare_compensated_relative", "bpow radix2 (-101)", Dyadic::pow2(-101), b::compare_compensated_relative,
       {}},
      // Ray–triangle (error_bounds.hpp's and Constants.v's last sections).
      {"triangle_absolute_scale", "bpow radix2 (-1070)", Dyadic::pow2(-1070), b::triangle_absolute_scale, {}},
      {"triangle_absolute", "bpow radix2 (-1069)", Dyadic::pow2(-1069), b::triangle_absolute, {}},
      {"triangle_filter_pi_relative", "8 * u", 8 * Dyadic::pow2(-53), b::triangle_filter_pi_relative, {}},
      {"triangle_filter_num_relative", "9 * u", 9 * Dyadic::pow2(-53), b::triangle_filter_num_relative, {}},
      {"triangle_filter_den_relative", "10 * u", 10 * Dyadic::pow2(-53), b::triangle_filter_den_relative, {}},
      {"triangle_compensated_relative", "128 * (u * u)", 128 * Dyadic::pow2(-106), b::triangle_compensated_relative,
       {}},
      {"triangle_compensated_den_relative", "256 * (u * u)", 256 * Dyadic::pow2(-106),
       b::triangle_compensated_den_relative, {}},
      // Ray–sphere, stage 1 (ray_sphere_filter.hpp; sphere/SphereFilter.v).
      {"sphere_filter_c_relative", "8 * u", 8 * Dyadic::pow2(-53), b::sphere_filter_c_relative, {}},
      {"sphere_filter_c_absolute", "8 * mu", 8 * Dyadic::pow2(-1074), b::sphere_filter_c_absolute, {}},
      {"sphere_filter_d_relative", "32 * u", 32 * Dyadic::pow2(-53), b::sphere_filter_d_relative, {}},
      {"sphere_filter_d_floor", "bpow radix2 (-1018)", Dyadic::pow2(-1018), b::sphere_filter_d_floor, {}},
      {"sphere_filter_d_absolute", "64 * mu", 64 * Dyadic::pow2(-1074), b::sphere_filter_d_absolute, {}},
      // Ray–sphere roots, the boundary filter (ray_sphere_boundary_filter.hpp; sphere/SphereBoundaryFilter.v,
      // `sphere_boundary_q_sound` and `sphere_boundary_slope_sound`).
      {"sphere_boundary_q_relative", "bpow radix2 (-96)", Dyadic::pow2(-96), b::sphere_boundary_q_relative, {}},
      {"sphere_boundary_q_absolute", "bpow radix2 (-1060)", Dyadic::pow2(-1060), b::sphere_boundary_q_absolute, {}},
      {"sphere_boundary_tail", "bpow radix2 (-45)", Dyadic::pow2(-45), b::sphere_boundary_tail, {}},
      {"sphere_boundary_slope_relative", "bpow radix2 (-49)", Dyadic::pow2(-49), b::sphere_boundary_slope_relative,
       {}},
      {"sphere_boundary_slope_floor", "bpow radix2 (-1000)", Dyadic::pow2(-1000), b::sphere_boundary_slope_floor, {}},
      {"sphere_boundary_slope_absolute", "bpow radix2 (-1070)", Dyadic::pow2(-1070),
       b::sphere_boundary_slope_absolute, {}},
      // The BVH's ray–box test (ray_box.hpp; box/RayBox.v): K = 1 ∓ 2^-50, τ = 2^-1022, case B's range.
      // 1 − 2^-50 = (2^50 − 1)·2^-50
      {"ray_box_near_factor", "1125899906842623 * bpow radix2 (-50)",
       Dyadic::integer((std::uint64_t{1} << 50) - 1) * Dyadic::pow2(-50), mb::ray_box_near_factor, {}},
      {"ray_box_far_factor", "1 + bpow radix2 (-50)", 1 + Dyadic::pow2(-50), mb::ray_box_far_factor, {}},
      {"ray_box_absolute", "bpow radix2 (-1022)", Dyadic::pow2(-1022), mb::ray_box_absolute, {}},
      {"ray_box_min_direction", "bpow radix2 (-1022)", Dyadic::pow2(-1022), mb::ray_box_min_direction, {}},
      {"ray_box_max_direction", "bpow radix2 (1022)", Dyadic::pow2(1022), mb::ray_box_max_direction, {}},
      {"ray_box_max_parameter", "bpow radix2 (1022)", Dyadic::pow2(1022), mb::ray_box_max_parameter, {}},
      // The point-in-mesh orientation filters (mesh_predicates.hpp; orient/OrientFilter.v).
      {"orient2d_filter_relative", "bpow radix2 (-51)", Dyadic::pow2(-51), mb::orient2d_filter_relative, {}},
      {"orient2d_filter_absolute", "bpow radix2 (-1071)", Dyadic::pow2(-1071), mb::orient2d_filter_absolute, {}},
      {"orient3d_filter_relative", "bpow radix2 (-49)", Dyadic::pow2(-49), mb::orient3d_filter_relative, {}},
      {"orient3d_filter_min_difference", "bpow radix2 (-300)", Dyadic::pow2(-300), mb::orient3d_filter_min_difference,
       {}},
      {"orient3d_filter_max_difference", "bpow radix2 (300)", Dyadic::pow2(300), mb::orient3d_filter_max_difference,
       {}},
      // spawn's certified fast path (spawn/spawn_certified.hpp; spawn/SpawnRounding.v, spawn/SpawnAffine.v).
      {"midpoint_offset_relative", "bpow radix2 (-52)", Dyadic::pow2(-52), mb::midpoint_offset_relative, {}},
      {"affine_propagation_factor", "1 + bpow radix2 (-50)", 1 + Dyadic::pow2(-50), mb::affine_propagation_factor, {}},
      {"affine_absolute", "bpow radix2 (-1060)", Dyadic::pow2(-1060), mb::affine_absolute, {}},
  };
}

// ---------------------------------------------------------------------------------------------------
// proofs/core/Constants.v: `Definition NAME : R := EXPR.` with EXPR over integers, earlier names,
// `bpow radix2 (k)`, `+`, `*` and parentheses; `Definition NAME : nat := N.`
std::string read_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string strip_coq_comments(const std::string& text) {
  std::string out;
  int depth = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text.compare(i, 2, "(*") == 0) {
      ++depth;
      ++i;
    } else if (depth > 0 && text.compare(i, 2, "*)") == 0) {
      --depth;
      ++i;
    } else if (depth == 0) {
      out += text[i];
    }
  }
  return out;
}

class CoqExpression {
 public:
  CoqExpression(const std::string& text, const std::map<std::string, Dyadic>& env) : env_(env) {
    std::regex token(R"(\s*([A-Za-z_][A-Za-z0-9_']*|[0-9]+|[-+*()]))");
    std::smatch m;
    std::string rest = text;
    while (std::regex_search(rest, m, token, std::regex_constants::match_continuous)) {
      tokens_.push_back(m[1]);
      rest = m.suffix();
    }
    if (rest.find_first_not_of(" \t\r\n") != std::string::npos)
      throw std::runtime_error("unsupported syntax in Constants.v near: " + rest);
  }
  Dyadic evaluate() {
    Dyadic v = sum();
    if (pos_ != tokens_.size()) throw std::runtime_error("trailing tokens in Constants.v expression");
    return v;
  }

 private:
  const std::string& peek() const {
    static const std::string end;
    return pos_ < tokens_.size() ? tokens_[pos_] : end;
  }
  std::string next() {
    if (pos_ >= tokens_.size()) throw std::runtime_error("unexpected end of Constants.v expression");
    return tokens_[pos_++];
  }
  void expect(const std::string& t) {
    if (next() != t) throw std::runtime_error("expected '" + t + "' in Constants.v expression");
  }
  Dyadic sum() {
    Dyadic v = product();
    while (peek() == "+") {
      next();
      v = v + product();
    }
    return v;
  }
  Dyadic product() {
    Dyadic v = factor();
    while (peek() == "*") {
      next();
      v = v * factor();
    }
    return v;
  }
  Dyadic factor() {
    const std::string t = next();
    if (t == "(") {
      Dyadic v = sum();
      expect(")");
      return v;
    }
    if (t == "bpow") {
      expect("radix2");
      expect("(");
      bool negative = false;
      if (peek() == "-") {
        next();
        negative = true;
      }
      const long k = std::stol(next());
      expect(")");
      return Dyadic::pow2(negative ? -k : k);
    }
    if (std::isdigit(static_cast<unsigned char>(t[0]))) return Dyadic::integer(std::stoull(t));
    const auto it = env_.find(t);
    if (it == env_.end()) throw std::runtime_error("unknown name in Constants.v expression: " + t);
    return it->second;
  }

  const std::map<std::string, Dyadic>& env_;
  std::vector<std::string> tokens_;
  std::size_t pos_ = 0;
};

std::map<std::string, Dyadic> parse_coq_constants(const std::string& path, std::map<std::string, Dyadic> env = {}) {
  const std::string text = strip_coq_comments(read_file(path));
  std::regex definition(R"(Definition\s+([A-Za-z_][A-Za-z0-9_']*)\s*:\s*(R|nat)\s*:=\s*([^.]*)\.)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), definition); it != std::sregex_iterator(); ++it) {
    const std::string name = (*it)[1];
    env[name] = CoqExpression((*it)[3], env).evaluate();
  }
  return env;
}

// ---------------------------------------------------------------------------------------------------
// The bounds headers: `inline constexpr double NAME = LITERAL;` (a hexadecimal float, or a sum or difference of
// hexadecimal floats and integers such as 1.0 - 0x1p-50) or `... int NAME = N;`
int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

Dyadic parse_term(const std::string& literal) {
  std::smatch m;
  if (std::regex_match(literal, m, std::regex(R"(0[xX]([0-9a-fA-F]*)(?:\.([0-9a-fA-F]*))?[pP]([-+]?[0-9]+))"))) {
    Dyadic v;
    const std::string digits = m[1].str() + m[2].str();
    for (char c : digits) v = Dyadic::integer(16) * v + Dyadic::integer(static_cast<std::uint64_t>(hex_digit(c)));
    const long exponent = std::stol(m[3]) - 4 * static_cast<long>(m[2].str().size());
    return v * Dyadic::pow2(exponent);
  }
  if (std::regex_match(literal, m, std::regex(R"(([0-9]+)(?:\.0*)?)"))) return Dyadic::integer(std::stoull(m[1]));
  throw std::runtime_error("bounds headers: write constants as hexadecimal floats (0x1.8p-52) or integers, "
                           "or sums and differences of them, not: " + literal);
}

Dyadic parse_literal(const std::string& literal) {
  // terms separated by " + " and " - ", evaluated left to right
  std::regex term(R"(\s*([-+])?\s*(0[xX][0-9a-fA-F]*(?:\.[0-9a-fA-F]*)?[pP][-+]?[0-9]+|[0-9]+(?:\.0*)?))");
  std::smatch m;
  std::string rest = literal;
  Dyadic value;
  bool first = true;
  while (std::regex_search(rest, m, term, std::regex_constants::match_continuous) && m.length(0) > 0) {
    const std::string sign = m[1];
    if (first == !sign.empty()) throw std::runtime_error("bounds headers: cannot read the constant " + literal);
    const Dyadic t = parse_term(m[2]);
    value = first ? t : sign == "+" ? value + t : value - t;
    first = false;
    rest = m.suffix();
  }
  if (first || rest.find_first_not_of(" \t\r\n") != std::string::npos)
    throw std::runtime_error("bounds headers: cannot read the constant " + literal);
  return value;
}

// proofs/pending.txt: lines "constant NAME" (and "file NAME.v", used by check_assumptions.cmake).
std::vector<std::string> parse_pending_constants(const std::string& path) {
  std::istringstream in(read_file(path));
  std::vector<std::string> names;
  std::string kind, name;
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    if (fields >> kind >> name && kind == "constant") names.push_back(name);
  }
  return names;
}

std::map<std::string, Dyadic> parse_cpp_constants(const std::string& path) {
  const std::string text = read_file(path);
  std::map<std::string, Dyadic> values;
  std::regex definition(R"(inline\s+constexpr\s+(double|int)\s+([A-Za-z_][A-Za-z0-9_]*)\s*=\s*([^;]+?)\s*;)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), definition); it != std::sregex_iterator(); ++it)
    values[(*it)[2]] = parse_literal((*it)[3]);
  return values;
}

}  // namespace

int main(int argc, char** argv) {
  bool one_ulp = false;
  std::vector<std::string> paths;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--one-ulp")
      one_ulp = true;
    else
      paths.push_back(arg);
  }
  std::vector<std::string> headers, coq_files, pending_files;
  for (const std::string& path : paths) {
    auto ends_with = [&](const std::string& suffix) {
      return path.size() >= suffix.size() && path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
    };
    (ends_with(".hpp") ? headers : ends_with(".v") ? coq_files : pending_files).push_back(path);
  }
  if (headers.empty() || coq_files.empty() || pending_files.size() != 1) {
    std::cerr << "usage: raykernel_check_constants [--one-ulp] BOUNDS_HPP... CONSTANTS_V... PENDING_TXT\n";
    return 2;
  }

  int failures = 0;
  auto fail = [&](const std::string& message) {
    std::cerr << "FAIL: " << message << '\n';
    ++failures;
  };

  try {
    const std::vector<Row> rows = table();

    if (one_ulp) {
      // The comparison is exact: a constant moved by one ulp either way no longer matches.
      for (const Row& row : rows) {
        if (!row.compiled) continue;
        for (double direction : {-HUGE_VAL, HUGE_VAL}) {
          const double moved = std::nextafter(*row.compiled, direction);
          if (moved >= 0 && std::isfinite(moved) && Dyadic::from_double(moved) == row.expected)
            fail(std::string(row.name) + ": a one-ulp change is not detected");
        }
      }
      std::cout << (failures == 0 ? "ok: every constant changed by one ulp fails the comparison\n" : "");
      return failures == 0 ? 0 : 1;
    }

    std::map<std::string, Dyadic> cpp;
    for (const std::string& h : headers) cpp.merge(parse_cpp_constants(h));
    std::map<std::string, Dyadic> coq;
    for (const std::string& v : coq_files) coq = parse_coq_constants(v, coq);
    const std::vector<std::string> pending = parse_pending_constants(pending_files[0]);
    auto is_pending = [&](const std::string& name) {
      for (const std::string& p : pending)
        if (p == name) return true;
      return false;
    };
    for (const std::string& name : pending) {
      if (coq.count(name) != 0)
        fail(name + " is defined in Constants.v: remove it from pending.txt and add it to check_constants.cpp");
      else if (cpp.count(name) != 0)
        std::cout << "PENDING: " << name << " (a bounds header) has no proof yet (proofs/pending.txt)\n";
    }

    for (const Row& row : rows) {
      const std::string name = row.name;
      const std::string want = row.expected.str();
      if (!row.expected.is_binary64()) fail(name + ": the table's value " + want + " is not a binary64 number");

      const auto c = coq.find(name);
      if (c == coq.end())
        fail(name + ": no `Definition " + name + "` in the Coq constants files");
      else if (!(c->second == row.expected))
        fail(name + ": Constants.v gives " + c->second.str() + ", expected " + want + " (" + row.coq_formula + ")");

      const auto h = cpp.find(name);
      if (h == cpp.end())
        fail(name + ": no `inline constexpr` " + name + " in the bounds headers");
      else if (!(h->second == row.expected))
        fail(name + ": the literal in the bounds header is " + h->second.str() + ", the proofs use " + want + " (" +
             row.coq_formula + ")");

      if (row.compiled && !(Dyadic::from_double(*row.compiled) == row.expected))
        fail(name + ": the compiled value is " + Dyadic::from_double(*row.compiled).str() + ", the proofs use " +
             want);
      if (row.compiled_int && !(Dyadic::integer(static_cast<std::uint64_t>(*row.compiled_int)) == row.expected))
        fail(name + ": the compiled value differs from " + want);
    }
    for (const auto& [name, value] : coq) {
      bool known = false;
      for (const Row& row : rows) known = known || name == row.name;
      if (!known) fail(name + " is defined in Constants.v but not checked (add it to check_constants.cpp)");
    }
    for (const auto& [name, value] : cpp) {
      bool known = false;
      for (const Row& row : rows) known = known || name == row.name;
      if (!known && !is_pending(name))
        fail(name + " is defined in a bounds header but not checked (add it to Constants.v and check_constants.cpp)");
    }
    if (failures == 0)
      std::cout << "ok: " << rows.size() << " constants agree exactly between the bounds headers, their compiled values "
                << "and the Coq constants files\n";
  } catch (const std::exception& e) {
    fail(e.what());
  }
  return failures == 0 ? 0 : 1;
}
