// Plane pairs with exact and near ties along a ray (plane_pairs.hpp).
//
// The construction, in integer units (positions are integers times 2^s, the direction integers times 2^a,
// each normal integers times its own power of two; none of the scalings changes which t is smaller):
//
//   d, u, nA    random integer vectors, |components| ≤ 2^20; o = pA − u, with pA a small integer point
//   plane A     through pA with normal nA:   t_A = N/D,  N = u·nA,  D = d·nA   (d is negated if N·D < 0)
//   plane B     pivot kinds:    nB = nA + r·(d × u), r ∈ ±{1,2,3}: since (d × u) ⟂ d and ⟂ u,
//                               d·nB = D and u·nB = N exactly — a different plane through pA, same t;
//               parallel kinds: nB = ±nA (then num and den of B are ±N and ±D: the same t);
//               its point pB = pA + w with w ⟂ nB (w = nB × z for an integer z), so still t_B = t_A.
//   offset      near-tie kinds add τ = ±2^-m to the k-th coordinate of pB, where pA_k = 0 and w_k = 0
//               (w = c·(nB × e_k)), so pB_k = τ exactly. Then num_B gains τ·nB_k and
//               t_B − t_A = τ·nB_k / den_B, whose sign is known, with
//                   |t_B − t_A| / t_A = |τ·nB_k| / |N| < 2^-53
//               for m = 54 + bitlen(|nB_k|) − bitlen(|N|) + extra, extra ≥ 0, because |nB_k| < 2^bitlen(|nB_k|)
//               and |N| ≥ 2^(bitlen(|N|) − 1). 2^-53·t < ulp(t) for every normal t, so the two t are less
//               than an ulp apart; t = 2^(s−a)·N/D stays within [2^-126, 2^126], far from under- and overflow.
//
// Magnitudes: |d×u| < 2^41, |nB| < 2^43, |w| < 2^48, so every coordinate is an integer below 2^53 (exact in
// a double) and the integer arithmetic here (|N|, |D| < 2^66) fits in 128 bits.
#include <raykernel/testkit/plane_pairs.hpp>

#include <cmath>
#include <cstdint>
#include <utility>

namespace raykernel::testkit {
namespace {

__extension__ typedef __int128 int128;

struct IntVec {
  std::int64_t c[3];
};

IntVec operator+(const IntVec& a, const IntVec& b) { return {{a.c[0] + b.c[0], a.c[1] + b.c[1], a.c[2] + b.c[2]}}; }
IntVec operator-(const IntVec& a, const IntVec& b) { return {{a.c[0] - b.c[0], a.c[1] - b.c[1], a.c[2] - b.c[2]}}; }
IntVec operator*(std::int64_t s, const IntVec& a) { return {{s * a.c[0], s * a.c[1], s * a.c[2]}}; }
IntVec cross(const IntVec& a, const IntVec& b) {
  return {{a.c[1] * b.c[2] - a.c[2] * b.c[1], a.c[2] * b.c[0] - a.c[0] * b.c[2], a.c[0] * b.c[1] - a.c[1] * b.c[0]}};
}
int128 dot(const IntVec& a, const IntVec& b) {
  return int128{a.c[0]} * b.c[0] + int128{a.c[1]} * b.c[1] + int128{a.c[2]} * b.c[2];
}
bool is_zero(const IntVec& a) { return a.c[0] == 0 && a.c[1] == 0 && a.c[2] == 0; }
IntVec negated(const IntVec& a) { return (-1) * a; }
int sign(int128 x) { return (x > 0) - (x < 0); }
int bit_length(int128 x) {
  if (x < 0) x = -x;
  int n = 0;
  for (; x != 0; x >>= 1) ++n;
  return n;
}

class Words {
 public:
  explicit Words(const BitSource& bits) : bits_(bits) {}
  bool coin() { return (bits_() & 1) != 0; }
  std::int64_t integer(std::int64_t lo, std::int64_t hi) {  // uniform in [lo, hi], hi − lo < 2^32
    return lo + static_cast<std::int64_t>(bits_() % static_cast<std::uint64_t>(hi - lo + 1));
  }
  IntVec vector(std::int64_t limit) {
    return {{integer(-limit, limit), integer(-limit, limit), integer(-limit, limit)}};
  }

 private:
  const BitSource& bits_;
};

Vec3 to_vec3(const IntVec& a, int exponent) {
  return {std::ldexp(static_cast<double>(a.c[0]), exponent), std::ldexp(static_cast<double>(a.c[1]), exponent),
          std::ldexp(static_cast<double>(a.c[2]), exponent)};
}

double& component(Vec3& v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }

bool is_pivot(PlaneTieKind kind) { return kind == PlaneTieKind::pivot || kind == PlaneTieKind::pivot_offset; }
bool is_offset(PlaneTieKind kind) {
  return kind == PlaneTieKind::parallel_offset || kind == PlaneTieKind::pivot_offset;
}

}  // namespace

std::string_view to_string(PlaneTieKind kind) noexcept {
  switch (kind) {
    case PlaneTieKind::coincident: return "coincident";
    case PlaneTieKind::pivot: return "pivot";
    case PlaneTieKind::parallel_offset: return "parallel-offset";
    case PlaneTieKind::pivot_offset: return "pivot-offset";
  }
  return "?";
}

PlanePair make_plane_pair_near_tie(const BitSource& bits) {
  Words words(bits);
  const auto kind = all_plane_tie_kinds[static_cast<std::size_t>(words.integer(0, plane_tie_kind_count - 1))];
  return make_plane_pair_near_tie(kind, bits);
}

PlanePair make_plane_pair_near_tie(PlaneTieKind kind, const BitSource& bits) {
  Words words(bits);
  constexpr std::int64_t limit = std::int64_t{1} << 20;

  // d, u, nA with N ≠ 0, D ≠ 0 (and, for the pivot kinds, d × u ≠ 0 so that the normals differ). Random
  // draws fail this with probability about 2^-20; a shrinker driving every word to 0 always does, hence
  // the fixed fallback (D = 11, N = 24, d × u = (25, −23, −26)).
  IntVec d{}, u{}, nA{};
  bool found = false;
  for (int attempt = 0; attempt < 8 && !found; ++attempt) {
    d = words.vector(limit);
    u = words.vector(limit);
    nA = words.vector(limit);
    found = dot(d, nA) != 0 && dot(u, nA) != 0 && !(is_pivot(kind) && is_zero(cross(d, u)));
  }
  if (!found) {
    d = {{3, 1, 2}};
    u = {{5, -7, 11}};
    nA = {{1, 2, 3}};
  }
  if (sign(dot(u, nA)) != sign(dot(d, nA))) d = negated(d);  // t = N/D > 0: both planes are hit
  const int128 N = dot(u, nA);

  IntVec nB = nA;
  if (is_pivot(kind)) {
    const std::int64_t r = words.integer(1, 3);
    nB = nA + (words.coin() ? -r : r) * cross(d, u);
  } else if (words.coin()) {
    nB = negated(nA);  // the same plane's other orientation: num and den both change sign
  }
  const int128 D_B = dot(d, nB);  // ±D, never 0

  // The coordinate k that carries the offset: one where nB_k ≠ 0 (nB ≠ 0, since d·nB ≠ 0).
  int k = static_cast<int>(words.integer(0, 2));
  while (nB.c[k] == 0) k = (k + 1) % 3;

  IntVec pA = words.vector(1 << 7);
  pA.c[k] = 0;
  const IntVec o = pA - u;
  IntVec axis{};
  axis.c[k] = 1;
  const IntVec w = is_offset(kind) ? words.integer(-15, 15) * cross(nB, axis)  // w_k = 0
                                   : cross(nB, words.vector(15));              // any w ⟂ nB
  const IntVec pB = pA + w;

  // The offset τ = ±2^-m in position units (see the header comment for the bound), and the exact order.
  int order = 0;
  int tau_exponent = 0;
  bool tau_negative = false;
  if (is_offset(kind)) {
    tau_exponent = -(54 + bit_length(nB.c[k]) - bit_length(N) + static_cast<int>(words.integer(0, 10)));
    tau_negative = words.coin();
    order = (tau_negative ? -1 : 1) * sign(nB.c[k]) * sign(D_B);  // sign of t_B − t_A = τ·nB_k / den_B
  }

  // Scalings by powers of two: positions share one, the direction and each normal have their own.
  const int s = static_cast<int>(words.integer(-30, 30));
  const int a = static_cast<int>(words.integer(-30, 30));
  const int bA = static_cast<int>(words.integer(-30, 30));
  const int bB = static_cast<int>(words.integer(-30, 30));
  PlanePair pair{kind,
                 {to_vec3(o, s), to_vec3(d, a)},
                 {Plane{to_vec3(pA, s), to_vec3(nA, bA)}, Plane{to_vec3(pB, s), to_vec3(nB, bB)}},
                 order};
  if (is_offset(kind)) {
    component(pair.planes[1].point, k) = std::ldexp(tau_negative ? -1.0 : 1.0, s + tau_exponent);
  }

  // The same permutation and sign flips of the coordinates for every vector: dot products and differences
  // are unchanged exactly.
  const int permutation[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const int* perm = permutation[words.integer(0, 5)];
  const bool flip[3] = {words.coin(), words.coin(), words.coin()};
  for (Vec3* v : {&pair.ray.origin, &pair.ray.direction, &pair.planes[0].point, &pair.planes[0].normal,
                  &pair.planes[1].point, &pair.planes[1].normal}) {
    Vec3 shuffled{};
    for (int i = 0; i < 3; ++i) {
      const double c = component(*v, perm[i]);
      component(shuffled, i) = flip[i] ? -c : c;
    }
    *v = shuffled;
  }

  if (words.coin()) {  // which plane comes first is random too: nearest() is 0 or 1 equally often
    std::swap(pair.planes[0], pair.planes[1]);
    pair.order = -pair.order;
  }
  return pair;
}

}  // namespace raykernel::testkit
