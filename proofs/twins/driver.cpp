// The C++ side of the differential runner (proofs/README.md, "The twins and the differential runner").
//
// Reads the runner's input lines ("routine x1 x2 ...", inputs as unsigned decimal 64-bit patterns),
// computes every line with the compiled kernel routine of that name, and compares the output line, bit for
// bit (every NaN written as 0x7ff8000000000000, i.e. NaNs compared as a class), with the line the extracted
// Coq twin produced for the same input. Prints the mismatches (input, C++ output, twin output) and a count
// per routine; exits 1 on any mismatch.
//
// Compiled once per variant the kernel runs (proofs/CMakeLists.txt), all with the kernel's floating-point
// flags (-ffp-contract=off, no fast-math):
//   scalar, -mfma          std::fma is the FMA instruction
//   scalar, no -mfma       std::fma is libm's fma
//   RAYKERNEL_TWIN_LANES=4 -march=x86-64-v3: the lane-templated routines instantiated for Lanes4 (the AVX2
//                          batch loop), four input lines per call
//   RAYKERNEL_TWIN_LANES=8 -march=x86-64-v4 (the AVX-512 batch loop; run only where the CPU has AVX-512),
//                          and -march=x86-64-v3 (Lanes8 lowered to AVX2 pairs)
// The lane variants run only the lane-templated routines and report the others as skipped. The BVH's ray–box
// test runs, on every variant, the scalar ray_box_entry of the driver's build (ray_box_entry) and the eight-lane
// ray_box_entries8 as the kernel compiled it for each instruction set the CPU has (ray_box_node: node_entries of
// mesh_detail::portable, ::avx2, ::avx512), each form compared with the twin and counted apart.
//
// Usage: raykernel_twin_driver INPUTS TWIN_OUTPUTS
//
// When a routine the kernel exports changes its name or signature, the function of the same name below is
// the one line to update (proofs/README.md lists them).
#include "nearest/compare_quotients.hpp"
#include "core/dot3_compensated.hpp"
#include "core/dot3_filter.hpp"
#include "core/eft.hpp"
#include "core/escalation.hpp"
#include "core/enclosure.hpp"
#include "core/error_bounds.hpp"
#include "core/expansion.hpp"
#include "core/lanes.hpp"
#include "core/quotient_boundary.hpp"
#include "core/quotient_rounding.hpp"
#include "plane/ray_plane_cascade.hpp"
#include "plane/ray_plane_stages.hpp"
#include "orient/orient_predicates.hpp"
#include "nearest/nearest_hit_internal.hpp"
#include "core/det3_stages.hpp"
#include "triangle/ray_triangle_stages.hpp"
#include "triangle/ray_triangle_cascade.hpp"
#include "sphere/ray_sphere_stages.hpp"
#include "spawn/spawn_certified.hpp"
#include "core/validation.hpp"
#include "mesh/bvh_walk.hpp"
#include <raykernel/triangle.hpp>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#ifndef RAYKERNEL_TWIN_LANES
#define RAYKERNEL_TWIN_LANES 0
#endif

namespace {

using namespace raykernel::detail;
using Words = std::vector<std::uint64_t>;

constexpr std::uint64_t canonical_nan = 0x7ff8000000000000ULL;

double from_word(std::uint64_t w) { return std::bit_cast<double>(w); }

// The output tokens of one line: doubles as bit patterns (NaN canonical), integers as they are.
struct Out {
  std::string text;
  void f(double x) {
    const std::uint64_t w = std::isnan(x) ? canonical_nan : std::bit_cast<std::uint64_t>(x);
    text += ' ';
    text += std::to_string(w);
  }
  void i(long long v) {
    text += ' ';
    text += std::to_string(v);
  }
};

// ---- The lane-templated routines, written once for V = double, Lanes4, Lanes8 ----------------------------
// Each takes its inputs as V values (one query per lane) and appends one output line per lane.

template <class V>
double lane(const V& v, int k) {
  if constexpr (std::is_same_v<V, double>) {
    return v;
  } else {
    return v[k];
  }
}
template <class I>
long long lane_int(const I& v, int k) {
  if constexpr (std::is_arithmetic_v<I>) {
    return static_cast<long long>(v);
  } else {
    return static_cast<long long>(v[k]);
  }
}

template <class V>
void lanes_two_sum(const V* x, std::vector<Out>& out) {
  const DD<V> r = two_sum(x[0], x[1]);
  for (int k = 0; k < width_of<V>; ++k) out[k].f(lane(r.hi, k)), out[k].f(lane(r.lo, k));
}
template <class V>
void lanes_two_diff(const V* x, std::vector<Out>& out) {
  const DD<V> r = two_diff(x[0], x[1]);
  for (int k = 0; k < width_of<V>; ++k) out[k].f(lane(r.hi, k)), out[k].f(lane(r.lo, k));
}
template <class V>
void lanes_two_prod(const V* x, std::vector<Out>& out) {
  const DD<V> r = two_prod(x[0], x[1]);
  for (int k = 0; k < width_of<V>; ++k) out[k].f(lane(r.hi, k)), out[k].f(lane(r.lo, k));
}
template <class V>
void lanes_dot3_rounded(const V* x, std::vector<Out>& out) {
  const Dot3RoundedT<V> r = dot3_rounded(x, x + 3);
  for (int k = 0; k < width_of<V>; ++k) {
    for (int i = 0; i < 3; ++i) out[k].f(lane(r.product[i], k));
    out[k].f(lane(r.value, k));
    out[k].f(lane(r.magnitude, k));
  }
}
template <class V>
void lanes_filter_den(const V* x, std::vector<Out>& out) {
  const IntegerOf<V> s = dot3_filter_lanes(dot3_rounded(x, x + 3), bounds::filter_den_relative);
  for (int k = 0; k < width_of<V>; ++k) out[k].i(lane_int(s, k));
}
template <class V>
void lanes_filter_num(const V* x, std::vector<Out>& out) {
  const IntegerOf<V> s = dot3_filter_lanes(dot3_rounded(x, x + 3), bounds::filter_num_relative);
  for (int k = 0; k < width_of<V>; ++k) out[k].i(lane_int(s, k));
}
template <class V>
void lanes_compensated(const V* x, std::vector<Out>& out) {
  const EnclosureT<V> e = compensated_dot3(x, x + 3, x + 6, dot3_rounded(x, x + 6));
  for (int k = 0; k < width_of<V>; ++k) out[k].f(lane(e.hi, k)), out[k].f(lane(e.lo, k)), out[k].f(lane(e.radius, k));
}
template <class V>
void lanes_compensated_exact(const V* x, std::vector<Out>& out) {
  const EnclosureT<V> e = compensated_dot3_exact(x, x + 3, dot3_rounded(x, x + 3));
  for (int k = 0; k < width_of<V>; ++k) out[k].f(lane(e.hi, k)), out[k].f(lane(e.lo, k)), out[k].f(lane(e.radius, k));
}
// plane/ray_plane_stages.hpp: fast_answer and fast_relation on the terms (the batch API's form), per lane.
template <class V>
void lanes_fast_answer(const V* x, std::vector<Out>& out) {
  const FastAnswerT<V> a = fast_answer(ray_plane_terms(x, x + 3, x + 6, x + 9));
  for (int k = 0; k < width_of<V>; ++k)
    out[k].f(lane(a.t, k)), out[k].i(lane_int(a.behind, k) != 0), out[k].i(lane_int(a.certain, k) != 0),
        out[k].i(lane_int(a.relation_by_filter, k) != 0);
}
template <class V>
void lanes_fast_relation(const V* x, std::vector<Out>& out) {
  const FastRelationT<V> r = fast_relation(ray_plane_terms(x, x + 3, x + 6, x + 9));
  for (int k = 0; k < width_of<V>; ++k) out[k].i(lane_int(r.behind, k) != 0), out[k].i(lane_int(r.certain, k) != 0);
}
// quotient_rounding.hpp: prepare_divisor of den's enclosure, round_quotient of num's over it.
template <class V>
void lanes_round_quotient(const V* x, std::vector<Out>& out) {
  const DivisorT<V> d = prepare_divisor(EnclosureT<V>{x[3], x[4], x[5]});
  const QuotientRoundingT<V> r = round_quotient(EnclosureT<V>{x[0], x[1], x[2]}, d);
  for (int k = 0; k < width_of<V>; ++k)
    out[k].f(lane(r.t, k)), out[k].i(lane_int(r.certain, k) != 0), out[k].f(lane(d.hi, k)), out[k].f(lane(d.lo, k)),
        out[k].f(lane(d.reciprocal, k)), out[k].i(lane_int(d.in_range, k) != 0);
}
template <class V>
void lanes_half_gap(const V* x, std::vector<Out>& out) {
  const V h = half_gap_to_nearer_neighbour(x[0]);
  for (int k = 0; k < width_of<V>; ++k) out[k].f(lane(h, k));
}
template <class V>
void lanes_enclosure_sign(const V* x, std::vector<Out>& out) {
  const IntegerOf<V> s = enclosure_sign_lanes(EnclosureT<V>{x[0], x[1], x[2]});
  for (int k = 0; k < width_of<V>; ++k) out[k].i(lane_int(s, k));
}

struct LaneRoutine {
  int arity;
  std::function<void(const double*, std::vector<Out>&)> scalar;
#if RAYKERNEL_TWIN_LANES == 4
  std::function<void(const Lanes4*, std::vector<Out>&)> lanes;
#elif RAYKERNEL_TWIN_LANES == 8
  std::function<void(const Lanes8*, std::vector<Out>&)> lanes;
#endif
};

#if RAYKERNEL_TWIN_LANES == 4
using LaneV = Lanes4;
#elif RAYKERNEL_TWIN_LANES == 8
using LaneV = Lanes8;
#endif

#if RAYKERNEL_TWIN_LANES == 0
#define RAYKERNEL_LANE_ROUTINE(name, n) {#name, {n, lanes_##name<double>}}
#else
#define RAYKERNEL_LANE_ROUTINE(name, n) {#name, {n, lanes_##name<double>, lanes_##name<LaneV>}}
#endif

const std::map<std::string, LaneRoutine>& lane_routines() {
  static const std::map<std::string, LaneRoutine> table = {
      RAYKERNEL_LANE_ROUTINE(two_sum, 2),       RAYKERNEL_LANE_ROUTINE(two_diff, 2),
      RAYKERNEL_LANE_ROUTINE(two_prod, 2),      RAYKERNEL_LANE_ROUTINE(dot3_rounded, 6),
      RAYKERNEL_LANE_ROUTINE(filter_den, 6),    RAYKERNEL_LANE_ROUTINE(filter_num, 6),
      RAYKERNEL_LANE_ROUTINE(compensated, 9),   RAYKERNEL_LANE_ROUTINE(enclosure_sign, 3),
      RAYKERNEL_LANE_ROUTINE(fast_answer, 12),  RAYKERNEL_LANE_ROUTINE(compensated_exact, 6),
      RAYKERNEL_LANE_ROUTINE(fast_relation, 12), RAYKERNEL_LANE_ROUTINE(round_quotient, 6),
      RAYKERNEL_LANE_ROUTINE(half_gap, 1),
  };
  return table;
}

// ---- Scalar-only routines ----------------------------------------------------------------------------------
// Each takes one line's input words and returns its output tokens (false: wrong arity).

using ScalarRoutine = std::function<bool(const Words&, Out&)>;

std::vector<double> doubles(const Words& w, std::size_t from = 0) {
  std::vector<double> x;
  for (std::size_t j = from; j < w.size(); ++j) x.push_back(from_word(w[j]));
  return x;
}

Out enclosure_out(const Enclosure& e) {
  Out o;
  o.f(e.hi), o.f(e.lo), o.f(e.radius);
  return o;
}
template <std::size_t N>
void expansion_out(Out& o, const Expansion<N>& e) {
  o.i(static_cast<long long>(e.size));
  for (std::size_t i = 0; i < e.size; ++i) o.f(e.component[i]);
}
template <std::size_t N>
bool fill(Expansion<N>& e, const std::vector<double>& x, std::size_t from, std::size_t count) {
  if (count == 0 || count > N || from + count > x.size()) return false;
  e.size = count;
  for (std::size_t i = 0; i < count; ++i) e.component[i] = x[from + i];
  return true;
}
int sign_code(Sign s) { return static_cast<int>(s); }

// The ray and the sphere of the query "ox oy oz dx dy dz cx cy cz r" (the first 10 of x).
raykernel::Ray sphere_query_ray(const std::vector<double>& x) { return {{x[0], x[1], x[2]}, {x[3], x[4], x[5]}}; }
raykernel::Sphere sphere_query_sphere(const std::vector<double>& x) { return {{x[6], x[7], x[8]}, x[9]}; }

// A ray and a plane from "ox oy oz dx dy dz px py pz nx ny nz".
raykernel::Ray ray_of(const std::vector<double>& x, std::size_t at = 0) { return {{x[at], x[at + 1], x[at + 2]}, {x[at + 3], x[at + 4], x[at + 5]}}; }
raykernel::Plane plane_of(const std::vector<double>& x, std::size_t at) { return {{x[at], x[at + 1], x[at + 2]}, {x[at + 3], x[at + 4], x[at + 5]}}; }

RayPlaneTerms terms_of(const std::vector<double>& x, std::size_t plane_at = 6) {
  return ray_plane_terms(ray_of(x), plane_of(x, plane_at));
}


// ---- The escalation policy (core/escalation.hpp, proofs/core/Escalation.v) ---------------------------------------------

// One step of a sign: the Stage it counts as and its answer.
struct EscalationStep {
  raykernel::Stage stage;
  Sign answer;
};
constexpr std::size_t max_escalation_steps = 6;

// Escalation(start).sign with one SignStage per step (the steps 0 .. N−1), each decision counting that it
// was asked.
template <std::size_t... I>
Sign escalate_steps(Escalation& trace, const std::array<EscalationStep, max_escalation_steps>& steps, int& asked,
                    std::index_sequence<I...>) {
  return trace.sign(SignStage{steps[I].stage, [&] {
    ++asked;
    return steps[I].answer;
  }}...);
}
template <std::size_t N>
Sign escalate_n(Escalation& trace, const std::array<EscalationStep, max_escalation_steps>& steps, int& asked) {
  return escalate_steps(trace, steps, asked, std::make_index_sequence<N>{});
}

// "start stage_1 sign_1 ... stage_m sign_m" (m ≤ 6; a stage as its code 0..3, a sign as its code −1, 0, +1, 2
// in a two's-complement word): the answer's sign code, the trace's stage code, the number of stages asked.
bool escalate_routine(const Words& w, Out& o) {
  if (w.empty() || w.size() % 2 == 0 || (w.size() - 1) / 2 > max_escalation_steps) return false;
  const auto stage_of = [](std::uint64_t word) { return static_cast<raykernel::Stage>(word); };
  if (w[0] > 3) return false;
  std::array<EscalationStep, max_escalation_steps> steps{};
  const std::size_t m = (w.size() - 1) / 2;
  for (std::size_t k = 0; k < m; ++k) {
    const std::uint64_t stage = w[1 + 2 * k];
    const auto sign = static_cast<std::int64_t>(w[2 + 2 * k]);
    if (stage > 3 || sign < -1 || sign > 2) return false;
    steps[k] = {stage_of(stage), static_cast<Sign>(sign)};
  }
  Escalation trace(stage_of(w[0]));
  int asked = 0;
  Sign answer = Sign::uncertain;
  switch (m) {
    case 0: answer = escalate_n<0>(trace, steps, asked); break;
    case 1: answer = escalate_n<1>(trace, steps, asked); break;
    case 2: answer = escalate_n<2>(trace, steps, asked); break;
    case 3: answer = escalate_n<3>(trace, steps, asked); break;
    case 4: answer = escalate_n<4>(trace, steps, asked); break;
    case 5: answer = escalate_n<5>(trace, steps, asked); break;
    default: answer = escalate_n<6>(trace, steps, asked); break;
  }
  o.i(sign_code(answer)), o.i(static_cast<int>(trace.reached())), o.i(asked);
  return true;
}

// ---- The cascade's control flow (proofs/plane/PlaneCascadeTwins.v) ----------------------------------------------------

// The code of an invalid_input's reason (validation.cpp's wording): 3·i + k for component i of o, d, p, n
// (k: 0 NaN, 1 +inf, 2 −inf), 36 a zero direction, 37 a zero normal; −1 for any other text.
long long invalid_code(const std::string& what) {
  static const char* const vectors[4] = {"ray origin", "ray direction", "plane point", "plane normal"};
  static const char* const kinds[3] = {"NaN", "+inf", "-inf"};
  for (int v = 0; v < 4; ++v)
    for (int axis = 0; axis < 3; ++axis)
      for (int k = 0; k < 3; ++k)
        if (what == std::string(vectors[v]) + " " + "xyz"[axis] + " is " + kinds[k]) return 3 * (3 * v + axis) + k;
  if (what == "ray direction is the zero vector") return 36;
  if (what == "plane normal is the zero vector") return 37;
  return -1;
}

// The public entry point's answer, or the code of the reason it rejected the query.
template <class F>
auto public_answer(F call) -> std::pair<decltype(call()), long long> {
  try {
    return {call(), -2};
  } catch (const raykernel::invalid_input& e) {
    return {{}, invalid_code(e.what())};
  }
}

const std::map<std::string, ScalarRoutine>& scalar_routines() {
  static const std::map<std::string, ScalarRoutine> table = {
      {"refined",
       [](const Words& w, Out& o) {
         if (w.size() != 9) return false;
         const std::vector<double> x = doubles(w);
         o = enclosure_out(compensated_dot3_refined(x.data(), x.data() + 3, x.data() + 6,
                                                    dot3_rounded(x.data(), x.data() + 6)));
         return true;
       }},
      {"tail_enclosure",
       [](const Words& w, Out& o) {
         Expansion<32> e;
         if (!fill(e, doubles(w), 0, w.size())) return false;
         o = enclosure_out(expansion_tail_enclosure(e));
         return true;
       }},
      // compare_quotients.hpp
      {"filter_enclosure_den",
       [](const Words& w, Out& o) {
         if (w.size() != 6) return false;
         const std::vector<double> x = doubles(w);
         const RoundedEnclosure e = filter_enclosure(dot3_rounded(x.data(), x.data() + 3), bounds::filter_den_relative);
         o.f(e.value), o.f(e.radius);
         return true;
       }},
      {"filter_enclosure_num",
       [](const Words& w, Out& o) {
         if (w.size() != 6) return false;
         const std::vector<double> x = doubles(w);
         const RoundedEnclosure e = filter_enclosure(dot3_rounded(x.data(), x.data() + 3), bounds::filter_num_relative);
         o.f(e.value), o.f(e.radius);
         return true;
       }},
      {"propagated",
       [](const Words& w, Out& o) {
         if (w.size() != 8) return false;
         const std::vector<double> x = doubles(w);
         o.f(compare_propagated_error(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7]));
         return true;
       }},
      {"compare_filter",
       [](const Words& w, Out& o) {
         if (w.size() != 8) return false;
         const std::vector<double> x = doubles(w);
         o.i(sign_code(compare_quotients_filter({x[0], x[1]}, {x[2], x[3]}, {x[4], x[5]}, {x[6], x[7]})));
         return true;
       }},
      {"compare_compensated",
       [](const Words& w, Out& o) {
         if (w.size() != 12) return false;
         const std::vector<double> x = doubles(w);
         o = enclosure_out(compare_quotients_compensated({x[0], x[1], x[2]}, {x[3], x[4], x[5]}, {x[6], x[7], x[8]},
                                                         {x[9], x[10], x[11]}));
         return true;
       }},
      // expansion.hpp: "k e_1 .. e_k f_1 .." and "b e_1 .."
      {"exp_sum",
       [](const Words& w, Out& o) {
         if (w.empty()) return false;
         const std::size_t k = w[0];
         const std::vector<double> x = doubles(w, 1);
         Expansion<64> e, f;
         if (!fill(e, x, 0, k) || !fill(f, x, k, x.size() - k)) return false;
         Expansion<128> h;
         ExpansionBuilder::sum(e, f, h);
         expansion_out(o, h);
         return true;
       }},
      {"exp_scale",
       [](const Words& w, Out& o) {
         if (w.size() < 2) return false;
         const std::vector<double> x = doubles(w);
         Expansion<64> e;
         if (!fill(e, x, 1, x.size() - 1)) return false;
         Expansion<128> h;
         ExpansionBuilder builder;
         builder.scale(e, x[0], h);
         o.i(builder.exact());
         expansion_out(o, h);
         return true;
       }},
      {"exp_sign",
       [](const Words& w, Out& o) {
         Expansion<64> e;
         if (!fill(e, doubles(w), 0, w.size())) return false;
         o.i(sign_code(e.sign()));
         return true;
       }},
      // the call sites: "ox oy oz dx dy dz px py pz nx ny nz" (and a second plane for the comparisons)
      {"build_expansions",
       [](const Words& w, Out& o) {
         if (w.size() != 12) return false;
         const std::vector<double> x = doubles(w);
         const ExactExpansions e = ray_plane_expansions(terms_of(x));
         expansion_out(o, e.num), expansion_out(o, e.den), o.i(e.exact);
         return true;
       }},
      {"compare_expansion",
       [](const Words& w, Out& o) {
         if (w.size() != 18) return false;
         const std::vector<double> x = doubles(w);
         const RayPlaneTerms a = terms_of(x, 6), b = terms_of(x, 12);
         o.i(sign_code(compare_quotients_expansion(ray_plane_expansions(a), ray_plane_expansions(b))));
         return true;
       }},
      // quotient_boundary.hpp's round_quotient_at_boundaries: "s q k num_1 .. num_k den_1 .." (s = 0: den_sign
      // +1, else −1; at most 16 components each) → 1 and RN(Σnum/Σden), or 0 when it does not decide.
      {"quotient_boundary",
       [](const Words& w, Out& o) {
         if (w.size() < 5 || w[0] > 1 || w[2] == 0 || w[2] > 16) return false;
         const std::vector<double> x = doubles(w, 3);
         const std::size_t k = static_cast<std::size_t>(w[2]);
         Expansion<16> num, den;
         if (!fill(num, x, 0, k) || !fill(den, x, k, x.size() - k)) return false;
         const std::optional<double> r =
             round_quotient_at_boundaries(num, den, w[0] == 0 ? 1 : -1, from_word(w[1]));
         if (r) o.i(1), o.f(*r);
         else o.i(0);
         return true;
       }},
      // nearest_hit.cpp's compare_hit_distances on two candidates built as nearest_hit builds them (stage 1
      // of den and num from d and p − o, the carried signs from the input): order (0 when the exact stage
      // decides: not a twin) and stage.
      // mesh_predicates.hpp's orientation filters (proofs/orient/OrientTwins.v): orient2d_filter(p, q, r, i, j) in
      // the plane of the axes i = (k + 1) mod 3, j = (k + 2) mod 3 of the ray's axis k (as inside() calls it),
      // "k p q r"; orient3d_filter(o, a, b, c), "o a b c". Output: +1, −1 or 0.
      {"orient2d",
       [](const Words& w, Out& o) {
         if (w.size() != 10 || w[0] > 2) return false;
         const std::vector<double> x = doubles(w, 1);
         const int k = static_cast<int>(w[0]), i = (k + 1) % 3, j = (k + 2) % 3;
         const raykernel::Vec3 p{x[0], x[1], x[2]}, q{x[3], x[4], x[5]}, r{x[6], x[7], x[8]};
         o.i(raykernel::mesh_detail::orient2d_filter(p, q, r, i, j));
         return true;
       }},
      {"orient3d",
       [](const Words& w, Out& o) {
         if (w.size() != 12) return false;
         const std::vector<double> x = doubles(w);
         const raykernel::Vec3 p{x[0], x[1], x[2]}, a{x[3], x[4], x[5]}, b{x[6], x[7], x[8]}, c{x[9], x[10], x[11]};
         o.i(raykernel::mesh_detail::orient3d_filter(p, a, b, c));
         return true;
       }},
      // sphere/ray_sphere_stages.hpp: sphere_expansions on "ox oy oz dx dy dz cx cy cz r" (the flag, then s.a,
      // s.b, s.c, s.d); sphere_abc_expansions on the same (the flag, then s.a, s.b, s.c); and sphere_root_side on
      // the same query's sphere_abc_expansions (as the cascade calls it), the root (word 0: −1, else +1) and the
      // boundary's doubles x, y (the side's sign code).
      {"sphere_expansions",
       [](const Words& w, Out& o) {
         if (w.size() != 10) return false;
         const std::vector<double> x = doubles(w);
         SphereExpansions s;
         sphere_expansions(sphere_query_ray(x), sphere_query_sphere(x), s);
         o.i(s.builder.exact());
         expansion_out(o, s.a), expansion_out(o, s.b), expansion_out(o, s.c), expansion_out(o, s.d);
         return true;
       }},
      {"sphere_abc_expansions",
       [](const Words& w, Out& o) {
         if (w.size() != 10) return false;
         const std::vector<double> x = doubles(w);
         SphereExpansions s;
         sphere_abc_expansions(sphere_query_ray(x), sphere_query_sphere(x), s);
         o.i(s.builder.exact());
         expansion_out(o, s.a), expansion_out(o, s.b), expansion_out(o, s.c);
         return true;
       }},
      {"sphere_root_side",
       [](const Words& w, Out& o) {
         if (w.size() != 13) return false;
         const std::vector<double> x = doubles(w);
         SphereExpansions s;
         sphere_abc_expansions(sphere_query_ray(x), sphere_query_sphere(x), s);
         o.i(sign_code(sphere_root_side(s, w[10] == 0 ? -1 : 1, x[11], x[12])));
         return true;
       }},
      // spawn/spawn_certified.hpp (proofs/spawn/SpawnTwins.v): midpoint_offset on "x y o" and affine_enclosure on
      // "o D.hi D.lo D.radius d N.hi N.lo N.radius"; each the enclosure (hi, lo, radius).
      {"midpoint_offset",
       [](const Words& w, Out& o) {
         if (w.size() != 3) return false;
         const std::vector<double> x = doubles(w);
         o = enclosure_out(midpoint_offset(x[0], x[1], x[2]));
         return true;
       }},
      {"affine_enclosure",
       [](const Words& w, Out& o) {
         if (w.size() != 8) return false;
         const std::vector<double> x = doubles(w);
         o = enclosure_out(affine_enclosure(x[0], Enclosure{x[1], x[2], x[3]}, x[4], Enclosure{x[5], x[6], x[7]}));
         return true;
       }},
      // core/escalation.hpp's policy (proofs/core/Escalation.v): Escalation(start).sign over 0..6 stages (above).
      {"escalate", escalate_routine},
      {"nearest_compare",
       [](const Words& w, Out& o) {
         if (w.size() != 22) return false;
         const std::vector<double> x = doubles(w);
         const raykernel::Ray ray = ray_of(x);
         const raykernel::Plane pa = plane_of(x, 6), pb = plane_of(x, 12);
         const double d[3] = {x[3], x[4], x[5]};
         auto stage1 = [&](const raykernel::Plane& p, bool num) {
           const double n[3] = {p.normal.x, p.normal.y, p.normal.z};
           const double diff[3] = {p.point.x - x[0], p.point.y - x[1], p.point.z - x[2]};
           return num ? dot3_rounded(diff, n) : dot3_rounded(d, n);
         };
         HitCandidate a(0, ray, pa, stage1(pa, false), stage1(pa, true));
         HitCandidate b(1, ray, pb, stage1(pb, false), stage1(pb, true));
         a.num_sign = static_cast<Sign>(static_cast<int>(x[18]));
         a.den_sign = static_cast<Sign>(static_cast<int>(x[19]));
         b.num_sign = static_cast<Sign>(static_cast<int>(x[20]));
         b.den_sign = static_cast<Sign>(static_cast<int>(x[21]));
         const DistanceOrder r = compare_hit_distances(a, b);
         o.i(r.stage == raykernel::Stage::exact ? 0 : r.sign), o.i(static_cast<int>(r.stage));
         return true;
       }},
      // The cascade's control flow: intersect_traced (relation, t and the stages that decided them) and the
      // public intersect (fast path, then the cascade), or the invalid_input both report.
      {"cascade_intersect",
       [](const Words& w, Out& o) {
         if (w.size() != 12) return false;
         const std::vector<double> x = doubles(w);
         const raykernel::Ray ray = ray_of(x);
         const raykernel::Plane plane = plane_of(x, 6);
         const auto [traced, traced_invalid] = public_answer([&] { return raykernel::intersect_traced(ray, plane); });
         const auto [pub, pub_invalid] = public_answer([&] { return raykernel::intersect(ray, plane); });
         if (traced_invalid != -2 || pub_invalid != -2) {  // both must reject, for the same reason
           o.i(0), o.i(traced_invalid == pub_invalid ? traced_invalid : -3), o.i(0), o.i(0), o.i(0), o.i(0), o.i(0);
           return true;
         }
         const int rs = static_cast<int>(traced.relation_stage), ts = static_cast<int>(traced.t_stage);
         const int rel = static_cast<int>(traced.intersection.relation), pub_rel = static_cast<int>(pub.relation);
         if (traced.relation_stage == raykernel::Stage::exact) {
           o.i(1), o.i(0), o.i(3), o.i(0), o.i(3), o.i(0), o.i(0);
         } else if (traced.t_stage == raykernel::Stage::exact) {
           o.i(2), o.i(rel), o.i(rs), o.i(0), o.i(3), o.i(pub_rel), o.i(0);
         } else {
           o.i(2), o.i(rel), o.i(rs), o.f(traced.intersection.t), o.i(ts), o.i(pub_rel), o.f(pub.t);
         }
         return true;
       }},
      // relation (fast_relation, then certified_signs) and certified_signs' signs and stage.
      {"cascade_relation",
       [](const Words& w, Out& o) {
         if (w.size() != 12) return false;
         const std::vector<double> x = doubles(w);
         const raykernel::Ray ray = ray_of(x);
         const raykernel::Plane plane = plane_of(x, 6);
         const auto [rel, invalid] = public_answer([&] { return raykernel::relation(ray, plane); });
         if (invalid != -2) {
           o.i(0), o.i(invalid), o.i(0), o.i(0), o.i(0);
           return true;
         }
         RayPlaneCascade query(ray, plane);
         const CertifiedSigns signs = certified_signs(query);
         if (signs.stage == raykernel::Stage::exact) {
           o.i(1), o.i(0), o.i(3), o.i(0), o.i(0);
         } else {
           o.i(2), o.i(static_cast<int>(rel)), o.i(static_cast<int>(signs.stage)), o.i(static_cast<int>(signs.num)),
               o.i(static_cast<int>(signs.den));
         }
         return true;
       }},
      // The one-query forms: den and num as the two lanes of a Lanes2.
      {"fast_answer_pair",
       [](const Words& w, Out& o) {
         if (w.size() != 12) return false;
         const std::vector<double> x = doubles(w);
         const FastAnswer a = fast_answer(ray_of(x), plane_of(x, 6));
         o.f(a.t), o.i(a.behind), o.i(a.certain), o.i(a.relation_by_filter);
         return true;
       }},
      {"fast_relation_pair",
       [](const Words& w, Out& o) {
         if (w.size() != 12) return false;
         const std::vector<double> x = doubles(w);
         const FastRelationT<double> r = fast_relation(ray_of(x), plane_of(x, 6));
         o.i(r.behind), o.i(r.certain);
         return true;
       }},
  };
  return table;
}

// ---- Ray–triangle stages 1 and 2 (kernel/src/triangle/; twins: proofs/triangle/TriangleTwins.v) ---------------------
// Queries "ox oy oz dx dy dz ax ay az bx by bz cx cy cz". Run in every variant: their Lanes4 code is compiled
// for the variant's target (SSE2 pairs without -march, AVX2 with x86-64-v3 and v4), the scalar code too.

raykernel::Ray triangle_ray(const std::vector<double>& x) { return {{x[0], x[1], x[2]}, {x[3], x[4], x[5]}}; }
raykernel::Triangle triangle_of(const std::vector<double>& x) {
  return {{x[6], x[7], x[8]}, {x[9], x[10], x[11]}, {x[12], x[13], x[14]}};
}
template <class V>
void enclosure_lane_out(Out& o, const EnclosureT<V>& e, int k) {
  o.f(lane(e.hi, k)), o.f(lane(e.lo, k)), o.f(lane(e.radius, k));
}

// A triangle routine from its body on the parsed query: body(ray, triangle, out), or, with a leading integer
// word (options, rule or index) at most max_word, body(word, ray, triangle, out). Any other arity or a
// larger word is a wrong input line (false).
template <class Body>
ScalarRoutine triangle_routine(Body body) {
  return [body](const Words& w, Out& o) {
    if (w.size() != 15) return false;
    const std::vector<double> x = doubles(w);
    body(triangle_ray(x), triangle_of(x), o);
    return true;
  };
}
template <class Body>
ScalarRoutine triangle_routine(std::uint64_t max_word, Body body) {
  return [max_word, body](const Words& w, Out& o) {
    if (w.size() != 16 || w[0] > max_word) return false;
    const std::vector<double> x = doubles(w, 1);
    body(w[0], triangle_ray(x), triangle_of(x), o);
    return true;
  };
}

const std::map<std::string, ScalarRoutine>& triangle_routines() {
  static const std::map<std::string, ScalarRoutine> table = {
      // triangle_filter_values and the stage-1 signs det3_filter_lanes gives them (the full cascade's
      // det3_filter_sign takes the same values, up to the sign of a zero, as the filter view of
      // triangle_compensated_values_by_lanes: tri_compensated_lanes below).
      {"tri_filter",
       triangle_routine([](const raykernel::Ray& ray, const raykernel::Triangle& tri, Out& o) {
         const TriangleFilterValues f = triangle_filter_values(ray, tri);
         for (const FilterTerm<double>& t : f.value) o.f(t.v), o.f(t.m);
         o.f(f.absolute_d), o.f(f.absolute_e);
         for (int v = 0; v < triangle_value_count; ++v)
           o.i(det3_filter_lanes(f.value[static_cast<std::size_t>(v)], filter_relative(v), f.absolute(v)));
       })},
      // fast_relation's stage 1: triangle_relation_lanes with the π constant on every lane, then
      // triangle_num_filter.
      {"tri_relation_lanes",
       triangle_routine([](const raykernel::Ray& ray, const raykernel::Triangle& tri, Out& o) {
         const TriangleLanes<FilterTerm<Lanes4>> s1 = triangle_relation_lanes(ray, tri);
         for (int k = 0; k < 4; ++k) o.f(s1.lanes.v[k]), o.f(s1.lanes.m[k]);
         o.f(s1.absolute[0]);
         const auto sign = det3_filter_lanes(s1.lanes, bounds::triangle_filter_pi_relative, s1.absolute);
         for (int k = 0; k < 4; ++k) o.i(sign[k]);
         const TriangleNumFilter num = triangle_num_filter(ray, tri);
         o.f(num.value.v), o.f(num.value.m), o.f(num.absolute);
         o.i(det3_filter_lanes(num.value, bounds::triangle_filter_num_relative, num.absolute));
       })},
      // triangle_compensated_values and each value's enclosure.
      {"tri_compensated",
       triangle_routine([](const raykernel::Ray& ray, const raykernel::Triangle& tri, Out& o) {
         const TriangleCompensatedValues c = triangle_compensated_values(ray, tri);
         for (const CompensatedTerm<double>& t : c.value) o.f(t.h), o.f(t.l), o.f(t.m);
         o.f(c.absolute_d), o.f(c.absolute_e);
         for (int v = 0; v < triangle_value_count; ++v) enclosure_lane_out(o, c.enclosure(v), 0);
       })},
      // fast_triangle_intersection's stages 1 and 2: triangle_compensated_lanes, the lanes' filter signs and
      // enclosures, den summed from the lanes with its filter sign and enclosure.
      {"tri_compensated_lanes",
       triangle_routine([](const raykernel::Ray& ray, const raykernel::Triangle& tri, Out& o) {
         const TriangleLanes<CompensatedTerm<Lanes4>> s2 = triangle_compensated_lanes(ray, tri);
         for (int k = 0; k < 4; ++k) o.f(s2.lanes.h[k]), o.f(s2.lanes.l[k]), o.f(s2.lanes.m[k]);
         for (int k = 0; k < 4; ++k) o.f(s2.absolute[k]);
         const Lanes4 relative{bounds::triangle_filter_pi_relative, bounds::triangle_filter_pi_relative,
                               bounds::triangle_filter_pi_relative, bounds::triangle_filter_num_relative};
         const auto filter = det3_filter_lanes(filter_view(s2.lanes), relative, s2.absolute);
         for (int k = 0; k < 4; ++k) o.i(filter[k]);
         const EnclosureT<Lanes4> e = det3_enclosure(s2.lanes, bounds::triangle_compensated_relative, s2.absolute);
         for (int k = 0; k < 4; ++k) enclosure_lane_out(o, e, k);
         const CompensatedTerm<double> den = (lane(s2.lanes, 0) + lane(s2.lanes, 1)) + lane(s2.lanes, 2);
         o.f(den.h), o.f(den.l), o.f(den.m);
         o.i(det3_filter_lanes(filter_view(den), bounds::triangle_filter_den_relative, s2.absolute[0]));
         enclosure_lane_out(o, det3_enclosure(den, bounds::triangle_compensated_den_relative, s2.absolute[0]), 0);
       })},
      // Stage 3 (proofs/triangle/TriangleStage3Twins.v): value_expansion of determinant v (the first word, an integer
      // 0..4), its components, exact flag and sign.
      {"tri_expansion",
       triangle_routine(4, [](std::uint64_t word, const raykernel::Ray& ray, const raykernel::Triangle& tri, Out& o) {
         const ExpansionValue<192> e = value_expansion(ray, tri, static_cast<int>(word));
         o.i(static_cast<long long>(e.e.size));
         for (std::size_t k = 0; k < e.e.size; ++k) o.f(e.e.component[k]);
         o.i(e.exact ? 1 : 0);
         o.i(static_cast<int>(e.sign()));
       })},
      // The relation's fast path (proofs/triangle/TriangleCascadeTwins.v): fast_triangle_relation, and when it
      // answers the public relation(), for the owned rule and the closed one.
      {"tri_fast_relation",
       triangle_routine([](const raykernel::Ray& ray, const raykernel::Triangle& tri, Out& o) {
         for (const raykernel::TriangleRule rule : {raykernel::TriangleRule::owned, raykernel::TriangleRule::closed}) {
           const auto c = fast_triangle_relation(ray, tri, rule);
           o.i(c ? 1 : 0);
           if (!c) continue;
           o.i(static_cast<int>(c->classification.relation)), o.i(static_cast<int>(c->classification.location));
           o.i(c->classification.owned ? 1 : 0), o.i(static_cast<int>(c->stage));
           const raykernel::TriangleClassification p = raykernel::relation(ray, tri, rule);
           o.i(static_cast<int>(p.relation)), o.i(static_cast<int>(p.location)), o.i(p.owned ? 1 : 0);
         }
       })},
      // The mesh leaves' screen (triangle/ray_triangle_stages.hpp, triangle_screen; the twin in
      // proofs/twins/Extract.v, TriScreen): "o d" and four triangles "a b c"; per triangle 1 for a certain miss,
      // 2 or 3 for a line the screen finds through the interior that inside_relation (from the screen's lane of
      // den, as classify_screened decides) says is a hit or behind, 0 otherwise.
      {"tri_leaf_screen",
       [](const Words& w, Out& o) {
         if (w.size() != 42) return false;
         const std::vector<double> x = doubles(w);
         const raykernel::Ray ray{{x[0], x[1], x[2]}, {x[3], x[4], x[5]}};
         raykernel::Triangle t[4];
         const raykernel::Triangle* p[4];
         for (std::size_t k = 0; k < 4; ++k) {
           const double* v = &x[6 + 9 * k];
           t[k] = {{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}};
           p[k] = &t[k];
         }
         const TriangleScreen screen = triangle_screen(ray, p);
         for (int k = 0; k < 4; ++k) {
           int code = 0;
           if ((screen.missed >> k) & 1u) {
             code = 1;
           } else if ((screen.inside >> k) & 1u) {
             const InsideRelation through = inside_relation(ray, t[k], lane(screen.den, k), screen.absolute);
             if (through.num_sign != uncertain_lane)
               code = through.classification(screen.den_sign[k]).relation == raykernel::TriangleRelation::hit ? 2 : 3;
           }
           o.i(code);
         }
         return true;
       }},
      // The intersection's fast path (proofs/triangle/TriangleIntersectTwins.v): the options from the first word
      // (t + 2 · barycentric), fast_triangle_intersection and, when it answers, the public intersect_traced
      // and intersect, for the owned rule and the closed one.
      {"tri_fast_intersect",
       triangle_routine(3, [](std::uint64_t word, const raykernel::Ray& ray, const raykernel::Triangle& tri, Out& o) {
         auto intersection_out = [&o](const raykernel::TriangleIntersection& r) {
           o.i(static_cast<int>(r.relation)), o.i(static_cast<int>(r.location)), o.i(r.owned ? 1 : 0);
           o.f(r.t), o.f(r.barycentric[0]), o.f(r.barycentric[1]), o.f(r.barycentric[2]);
         };
         auto traced_out = [&](const raykernel::TracedTriangleIntersection& r) {
           intersection_out(r.intersection);
           o.i(static_cast<int>(r.relation_stage)), o.i(static_cast<int>(r.rounding_stage));
         };
         for (const raykernel::TriangleRule rule : {raykernel::TriangleRule::owned, raykernel::TriangleRule::closed}) {
           const raykernel::TriangleOptions options{rule, (word & 1) != 0, (word & 2) != 0};
           const auto a = fast_triangle_intersection(ray, tri, options);
           o.i(a ? 1 : 0);
           if (!a) continue;
           traced_out(*a);
           traced_out(raykernel::intersect_traced(ray, tri, options));
           intersection_out(raykernel::intersect(ray, tri, options));
         }
       })},
      // The full cascade's control flow (proofs/triangle/TriangleCascadeFlowTwins.v): the options and the rule from the
      // first word (t + 2 · barycentric + 4 · closed), triangle_intersection_cascade and the public
      // intersect_traced; "0 0" for invalid input (then the public entry point must throw); an answer as "1"
      // (the classification is the exact stage's) or "2 relation location owned relation_stage rounding_stage t
      // ua ub uc" (four 0 when the rounding stage is the exact one).
      {"tri_cascade_intersect",
       triangle_routine(7, [](std::uint64_t word, const raykernel::Ray& ray, const raykernel::Triangle& tri, Out& o) {
         auto traced_out = [&o](const raykernel::TracedTriangleIntersection& r) {
           if (r.relation_stage == raykernel::Stage::exact) return o.i(1);
           const raykernel::TriangleIntersection& i = r.intersection;
           o.i(2), o.i(static_cast<int>(i.relation)), o.i(static_cast<int>(i.location)), o.i(i.owned ? 1 : 0);
           o.i(static_cast<int>(r.relation_stage)), o.i(static_cast<int>(r.rounding_stage));
           if (r.rounding_stage == raykernel::Stage::exact) return o.i(0), o.i(0), o.i(0), o.i(0);
           o.f(i.t), o.f(i.barycentric[0]), o.f(i.barycentric[1]), o.f(i.barycentric[2]);
         };
         const raykernel::TriangleRule rule = (word & 4) != 0 ? raykernel::TriangleRule::closed : raykernel::TriangleRule::owned;
         const raykernel::TriangleOptions options{rule, (word & 1) != 0, (word & 2) != 0};
         const auto [pub, invalid] = public_answer([&] { return raykernel::intersect_traced(ray, tri, options); });
         if (!(is_valid(ray) & is_valid(tri))) {
           o.i(0), o.i(invalid != -2 ? 0 : 9);
           return;
         }
         traced_out(triangle_intersection_cascade(ray, tri, options));
         if (invalid != -2) o.i(9);
         else traced_out(pub);
       })},
      // The rule from the first word (1: closed); triangle_relation_cascade ("1", or "2 relation location owned
      // stage") and the public relation ("2 relation location owned", or "1" when it is the exact stage's: the
      // fast path did not answer and the cascade's stage is the exact one).
      {"tri_cascade_relation",
       triangle_routine(1, [](std::uint64_t word, const raykernel::Ray& ray, const raykernel::Triangle& tri, Out& o) {
         const raykernel::TriangleRule rule = word != 0 ? raykernel::TriangleRule::closed : raykernel::TriangleRule::owned;
         const auto [pub, invalid] = public_answer([&] { return raykernel::relation(ray, tri, rule); });
         if (!(is_valid(ray) & is_valid(tri))) {
           o.i(0), o.i(invalid != -2 ? 0 : 9);
           return;
         }
         const TracedTriangleClassification c = triangle_relation_cascade(ray, tri, rule);
         if (c.stage == raykernel::Stage::exact)
           o.i(1);
         else
           o.i(2), o.i(static_cast<int>(c.classification.relation)), o.i(static_cast<int>(c.classification.location)),
               o.i(c.classification.owned ? 1 : 0), o.i(static_cast<int>(c.stage));
         if (invalid != -2)
           o.i(9);
         else if (!fast_triangle_relation(ray, tri, rule) && c.stage == raykernel::Stage::exact)
           o.i(1);
         else
           o.i(2), o.i(static_cast<int>(pub.relation)), o.i(static_cast<int>(pub.location)), o.i(pub.owned ? 1 : 0);
       })},
  };
  return table;
}

// ---- The BVH's ray–box test (box/ray_box.hpp, mesh/bvh_walk.hpp; proofs/box/RayBoxTwins.v) -----------------------
// Routines with more than one compiled form: each line gives one output per form, each compared with the twin's
// line and counted under "routine[form]".

using Forms = std::vector<std::pair<std::string, Out>>;
using FormRoutine = std::function<bool(const Words&, Forms&)>;

// A binary32 value given as the double it converts to (NaN: any NaN).
bool binary32_word(std::uint64_t w, float& v) {
  const double x = from_word(w);
  v = static_cast<float>(x);
  return std::isnan(x) || std::bit_cast<std::uint64_t>(static_cast<double>(v)) == w;
}

// The input of ray_box_entry and ray_box_node: the slabs, t_min, t_max and a node whose every slot holds a child.
bool ray_box_node_input(const Words& w, raykernel::BvhRayTraversal::Slabs& s, raykernel::BvhNode& node, double& t_min,
                        double& t_max) {
  using raykernel::BvhNode;
  if (w.size() != 11 + 6 * BvhNode::width) return false;
  for (std::size_t k = 0; k < 3; ++k) {
    s.origin[k] = from_word(w[k]);
    s.inverse_direction[k] = from_word(w[3 + k]);
    s.enters_at_hi[k] = w[6 + k] != 0;
  }
  t_min = from_word(w[9]), t_max = from_word(w[10]);
  for (std::size_t f = 0; f < 6; ++f)
    for (std::size_t slot = 0; slot < BvhNode::width; ++slot)
      if (!binary32_word(w[11 + BvhNode::width * f + slot], node.bounds[f][slot])) return false;
  for (std::size_t slot = 0; slot < BvhNode::width; ++slot)
    node.first[slot] = static_cast<std::uint32_t>(slot + 1), node.count[slot] = 1;
  return true;
}

const std::map<std::string, FormRoutine>& form_routines() {
  static const std::map<std::string, FormRoutine> table = {
      // make_slabs on "ox oy oz dx dy dz Mx My Mz": per axis the inverse and enters_at_hi.
      {"ray_box_setup",
       [](const Words& w, Forms& forms) {
         if (w.size() != 9) return false;
         const std::vector<double> x = doubles(w);
         const raykernel::Ray ray{{x[0], x[1], x[2]}, {x[3], x[4], x[5]}};
         const raykernel::BvhRayTraversal::Slabs s = raykernel::mesh_detail::make_slabs(ray, {x[6], x[7], x[8]});
         Out o;
         for (std::size_t k = 0; k < 3; ++k) o.f(s.inverse_direction[k]), o.i(s.enters_at_hi[k] ? 1 : 0);
         forms.emplace_back("make_slabs", o);
         return true;
       }},
      // "o0 o1 o2 inv0 inv1 inv2 h0 h1 h2 t_min t_max" and a node's 48 face words (bounds[f][s] at 8·f + s, each
      // a binary32 value as a double): per slot the entry bound and the met bit. ray_box_entry: the scalar test
      // on node.box(s) (its twin ray_box_entry_b). ray_box_node: node_entries of each instruction set the CPU
      // has (its twin ray_box_entries8_b: the lanes' broadcast turns −0 into +0), the walk's state set up as
      // start_walk does (set_walk_ray of the slabs, t_min, t_max); every slot holds a child (first = s + 1,
      // count = 1), so node_entries masks no slot.
      {"ray_box_entry",
       [](const Words& w, Forms& forms) {
         raykernel::BvhRayTraversal::Slabs s{};
         raykernel::BvhNode node{};
         double t_min = 0, t_max = 0;
         if (!ray_box_node_input(w, s, node, t_min, t_max)) return false;
         Out scalar;
         for (int slot = 0; slot < raykernel::BvhNode::width; ++slot) {
           double entry = 0;
           const bool met = raykernel::mesh_detail::ray_box_entry(s, node.box(slot), t_min, t_max, entry);
           scalar.f(entry), scalar.i(met ? 1 : 0);
         }
         forms.emplace_back("scalar", scalar);
         return true;
       }},
      {"ray_box_node",
       [](const Words& w, Forms& forms) {
         using raykernel::BvhNode;
         namespace md = raykernel::mesh_detail;
         raykernel::BvhRayTraversal::Slabs s{};
         BvhNode node{};
         double t_min = 0, t_max = 0;
         if (!ray_box_node_input(w, s, node, t_min, t_max)) return false;
         raykernel::detail::BvhWalk walk;
         md::set_walk_ray(walk, s);
         walk.t_min = t_min, walk.t_max = t_max;
         using NodeEntries = unsigned (*)(const raykernel::detail::BvhWalk&, const BvhNode&, double, double,
                                          double*) noexcept;
         const std::pair<const char*, NodeEntries> isas[] = {
             {"portable", md::portable::node_entries},
             {"avx2", __builtin_cpu_supports("x86-64-v3") ? md::avx2::node_entries : nullptr},
             {"avx512", __builtin_cpu_supports("x86-64-v4") ? md::avx512::node_entries : nullptr}};
         for (const auto& [isa, entries_of] : isas) {
           if (entries_of == nullptr) continue;
           std::array<double, BvhNode::width> entries{};
           const unsigned met = entries_of(walk, node, t_min, t_max, entries.data());
           Out o;
           for (int slot = 0; slot < BvhNode::width; ++slot)
             o.f(entries[static_cast<std::size_t>(slot)]), o.i((met >> slot) & 1u);
           forms.emplace_back(isa, o);
         }
         return true;
       }},
  };
  return table;
}

// ---- Input, comparison, report ------------------------------------------------------------------------------

struct Line {
  std::string name;
  Words words;
  std::string text;
};

bool parse(const std::string& text, Line& line) {
  std::istringstream in(text);
  if (!(in >> line.name)) return false;
  line.words.clear();
  for (std::string token; in >> token;) line.words.push_back(std::stoull(token));
  line.text = text;
  return true;
}

struct Tally {
  std::map<std::string, long> checked, mismatched, skipped;
  int reported = 0;
};

// Runs every line of INPUTS through the compiled routine and compares with the line of TWIN_OUTPUTS.
int check(const char* inputs_path, const char* expected_path, Tally& tally) {
  std::ifstream inputs(inputs_path), expected(expected_path);
  if (!inputs || !expected) {
    std::cerr << "cannot read " << inputs_path << " or " << expected_path << '\n';
    return 2;
  }
  std::vector<Line> lines;
  std::vector<std::string> want;
  for (std::string text, expect; std::getline(inputs, text);) {
    Line line;
    if (!parse(text, line)) continue;
    if (!std::getline(expected, expect)) {
      std::cerr << expected_path << " has fewer lines than " << inputs_path << '\n';
      return 2;
    }
    lines.push_back(std::move(line));
    want.push_back(std::move(expect));
  }

  // (form: the compiled form of a routine with several, counted as "routine[form]")
  auto compare = [&](std::size_t index, const std::string& got_tokens, const std::string& form = "") {
    const std::string got = lines[index].name + got_tokens;
    const std::string key = form.empty() ? lines[index].name : lines[index].name + "[" + form + "]";
    ++tally.checked[key];
    if (got == want[index]) return;
    ++tally.mismatched[key];
    if (tally.reported++ < 20)
      std::cerr << "MISMATCH " << inputs_path << ":" << index + 1 << (form.empty() ? "" : " (" + form + ")") << ": "
                << lines[index].text << "\n  C++:  " << got << "\n  twin: " << want[index] << '\n';
  };

  for (std::size_t i = 0; i < lines.size();) {
    const Line& line = lines[i];
    if (const auto lr = lane_routines().find(line.name); lr != lane_routines().end()) {
      const LaneRoutine& r = lr->second;
#if RAYKERNEL_TWIN_LANES == 0
      if (static_cast<int>(line.words.size()) != r.arity) {
        std::cerr << "line " << i + 1 << ": wrong arity\n";
        return 2;
      }
      std::vector<double> x(line.words.size());
      for (std::size_t j = 0; j < x.size(); ++j) x[j] = from_word(line.words[j]);
      std::vector<Out> out(1);
      r.scalar(x.data(), out);
      compare(i, out[0].text);
      ++i;
#else
      // W consecutive lines of the same routine fill the lanes; a shorter tail is padded by repeating its
      // last line (whose extra outputs are not compared).
      constexpr int W = RAYKERNEL_TWIN_LANES;
      std::size_t n = 0;
      while (n < W && i + n < lines.size() && lines[i + n].name == line.name) ++n;
      std::vector<LaneV> x(static_cast<std::size_t>(r.arity));
      for (int k = 0; k < W; ++k) {
        const Line& l = lines[i + std::min<std::size_t>(static_cast<std::size_t>(k), n - 1)];
        if (static_cast<int>(l.words.size()) != r.arity) {
          std::cerr << "line " << i + 1 + static_cast<std::size_t>(k) << ": wrong arity\n";
          return 2;
        }
        for (int j = 0; j < r.arity; ++j)
          x[static_cast<std::size_t>(j)][k] = from_word(l.words[static_cast<std::size_t>(j)]);
      }
      std::vector<Out> out(W);
      r.lanes(x.data(), out);
      for (std::size_t k = 0; k < n; ++k) compare(i + k, out[k].text);
      i += n;
#endif
      continue;
    }
    if (const auto tr = triangle_routines().find(line.name); tr != triangle_routines().end()) {
      Out out;
      if (!tr->second(line.words, out)) {
        std::cerr << "line " << i + 1 << ": wrong arity for " << line.name << '\n';
        return 2;
      }
      compare(i, out.text);
      ++i;
      continue;
    }
    if (const auto fr = form_routines().find(line.name); fr != form_routines().end()) {
      Forms forms;
      if (!fr->second(line.words, forms)) {
        std::cerr << "line " << i + 1 << ": wrong arity or input for " << line.name << '\n';
        return 2;
      }
      for (const auto& [form, out] : forms) compare(i, out.text, form);
      ++i;
      continue;
    }
    if (const auto sr = scalar_routines().find(line.name); sr != scalar_routines().end()) {
#if RAYKERNEL_TWIN_LANES == 0
      Out out;
      if (!sr->second(line.words, out)) {
        std::cerr << "line " << i + 1 << ": wrong arity for " << line.name << '\n';
        return 2;
      }
      compare(i, out.text);
#else
      ++tally.skipped[line.name];
#endif
      ++i;
      continue;
    }
    std::cerr << "line " << i + 1 << ": unknown routine " << line.name << '\n';
    return 2;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || argc % 2 == 0) {
    std::cerr << "usage: raykernel_twin_driver INPUTS TWIN_OUTPUTS [INPUTS TWIN_OUTPUTS ...]\n";
    return 2;
  }
#if RAYKERNEL_TWIN_LANES == 8 && defined(__AVX512F__)
  __builtin_cpu_init();
  if (!__builtin_cpu_supports("avx512f")) {
    std::cout << "SKIPPED: this CPU has no AVX-512 (the -march=x86-64-v4 build cannot run)\n";
    return 77;
  }
#endif
  __builtin_cpu_init();
  Tally tally;
  for (int k = 1; k + 1 < argc; k += 2)
    if (const int status = check(argv[k], argv[k + 1], tally); status != 0) return status;

  long total_mismatches = 0;
  for (const auto& [name, count] : tally.checked) {
    total_mismatches += tally.mismatched[name];
    std::cout << name << ": " << count << " inputs, " << tally.mismatched[name] << " mismatches\n";
  }
  for (const auto& [name, count] : tally.skipped)
    std::cout << name << ": " << count << " inputs skipped (not lane-templated)\n";
  std::cout << (total_mismatches == 0 ? "ok: the compiled routines and the Coq twins agree bit for bit\n"
                                      : "FAILED: the compiled routines and the Coq twins disagree\n");
  return total_mismatches == 0 ? 0 : 1;
}
