// A program built the way the caller in the field is: with -ffast-math, whose start-up code
// (crtfastmath.o) sets flush-to-zero and denormals-are-zero before main. It runs every public entry point
// of the library on N subnormal-heavy hard queries (ray–plane queries, and ray–triangle queries for the
// triangle entry points), in that environment and in the default one, and
// fails unless every answer is the same, bit for bit, and the environment is left as it was after every
// call (tests/support/entry_points.hpp). ctest runs it on N = 2·10^4 (test `fast_math_program`); the default is 10^5.
//
// This file itself is compiled with -ffast-math: it compares no doubles, it only calls the library and
// compares text.
#include "support/entry_points.hpp"

#include <cstdio>
#include <cstdlib>
#include <string>

#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

int main(int argc, char** argv) {
  using namespace raykernel;
  const std::size_t count = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 100000;
#if defined(__x86_64__)
  const unsigned start = _mm_getcsr();
  if ((start & 0x8040u) != 0x8040u) {
    std::printf("fast_math_program: MXCSR is %#x at start: FTZ and DAZ are not set, so this test would prove nothing "
                "(was it linked with -ffast-math?)\n", start);
    return 1;
  }
#endif
  const std::vector<testkit::Query> queries = test_support::environment_test_queries(count, 0xfa57);
  const std::vector<testkit::TriangleQuery> triangles = test_support::environment_test_triangle_queries(count, 0x7fa57);

  // The reference: the same calls with the default environment installed.
#if defined(__x86_64__)
  _mm_setcsr(0x1F80u);
#endif
  const test_support::EntryPointAnswers want = test_support::answers_of_every_entry_point(queries, triangles);
#if defined(__x86_64__)
  _mm_setcsr(start);
#endif
  const test_support::EntryPointAnswers got = test_support::answers_of_every_entry_point(queries, triangles);

  std::size_t mismatches = 0, compared = 0;
  for (std::size_t k = 0; k < want.names.size(); ++k) {
    std::size_t here = 0, answered = 0;
    for (std::size_t i = 0; i < want.answers[k].size(); ++i) {
      answered += !want.answers[k][i].empty();
      if (got.answers[k][i] == want.answers[k][i]) continue;
      if (++here <= 3)
        std::printf("MISMATCH %s, query %zu (%s):\n  default:   %s\n  fast-math: %s\n", want.names[k].c_str(), i,
                    test_support::query_text(want, k, i, queries, triangles).c_str(), want.answers[k][i].c_str(), got.answers[k][i].c_str());
    }
    std::printf("%-46s %zu queries, %zu differ\n", want.names[k].c_str(), answered, here);
    mismatches += here;
    compared += answered;
  }
  std::printf("fast_math_program: %zu answers compared under FTZ+DAZ (MXCSR %#x), %zu differ from the default "
              "environment's\n", compared, static_cast<unsigned>(_mm_getcsr()), mismatches);
  return mismatches == 0 ? 0 : 1;
}
