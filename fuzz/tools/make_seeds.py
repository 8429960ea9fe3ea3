#!/usr/bin/env python3
"""Writes the seed corpora and dictionaries of fuzz/ (run from anywhere; rewrites the generated files only).

  fuzz/corpus/plane/sample-NNN        each query line of tests/data/contract-cases/classify-sample.txt with
                                         12 tokens, as a raw input (selector 0x00 + 12 little-endian doubles)
  fuzz/corpus/plane/hand-<what>       hand-made degenerate cases (below), raw inputs
  fuzz/corpus/plane/kind-<kind>-N     hard-query inputs: selector 0x80 + k and a few fixed words
  fuzz/corpus/batch/mix-NNN              the classify seeds above, cut to 97-byte records, concatenated into
                                         batches of 1 to 40 queries
  fuzz/corpus/cli/contract-*             the contract's sample text files, whole and in chunks of 8 lines
  fuzz/corpus/cli/hand-<what>            hand-made texts (below)
  fuzz/corpus/nearest/contract-*         rays of tests/data/contract-cases/nearest-sample/ with its planes
  fuzz/corpus/nearest/hand-<what>        hand-made rays and planes (near ties, t out of range, invalid input)
  fuzz/corpus/nearest/pair-*, kind-*, derived-*   structured inputs: near-tie pairs, hard queries, derived planes
  fuzz/corpus/nearest_cli/contract-*     the nearest sample's planes and rays files, whole and in chunks
  fuzz/corpus/nearest_cli/hand-<what>    hand-made planes and rays texts
  fuzz/corpus/scene/scene-<name>         scenes/*.json (scenes/demo.json is demo_scene_json())
  fuzz/corpus/scene/broken-<what>        variants of the demo scene: missing fields, wrong types, edge numbers,
                                         zero vectors and sizes, syntax errors
  fuzz/dict/plane.dict                special doubles as 8-byte little-endian tokens
  fuzz/dict/cli.dict                     number syntax tokens
  fuzz/dict/nearest.dict, nearest_cli.dict, scene.dict   the same for the other harnesses

Files named regression-* (inputs that made a harness fail) and mutant-* (inputs that killed a deliberately
broken kernel) are added by hand and never touched here.
The layout of a classify input is raykernel/testkit/plane_fuzz_decoder.hpp's.
"""
import pathlib
import random
import struct
import sys

FUZZ = pathlib.Path(__file__).resolve().parent.parent
ROOT = FUZZ.parent
CASES = ROOT / "tests" / "data" / "contract-cases"

KINDS = ["random", "wide-exponents", "near-parallel", "near-coplanar", "exact-parallel", "exact-in-plane",
         "origin-on-plane", "rounding-tie", "near-tie", "subnormal", "huge-products", "t-overflow", "t-underflow",
         "above-power-of-two"]

NAN = float("nan")
INF = float("inf")


def strtod(token):
    """C strtod on a whole token, for the syntax the sample uses (decimal, hex with 0x, inf, nan)."""
    t = token.lower()
    if "0x" in t:
        return float.fromhex(token)
    return float(token)


def raw_input(values):
    assert len(values) == 12
    return b"\x00" + b"".join(struct.pack("<d", v) for v in values)


def raw_bits_input(patterns):
    return b"\x00" + b"".join(struct.pack("<Q", p) for p in patterns)


def clear_generated(directory, prefixes):
    directory.mkdir(parents=True, exist_ok=True)
    for f in directory.iterdir():
        if f.is_file() and f.name.startswith(prefixes):
            f.unlink()


# Hand-made classify cases: (name, 12 values ox oy oz dx dy dz px py pz nx ny nz). What each one is:
TWO53 = 2.0 ** 53
HAND_CLASSIFY = [
    ("hit-seed-example", [0, 0, 0, 0, 0, 1, 0, 0, 5, 0, 0, 1]),             # hit 5
    ("hit-one-tenth", [0, 0, 0, 10, 0, 0, 1, 0, 0, 1, 0, 0]),               # hit RN(1/10)
    ("behind", [0, 0, 0, 0, 0, -1, 0, 0, 5, 0, 0, 1]),                      # behind -5
    ("exact-parallel", [0, 0, 0, 1, 0, 0, 0, 0, 5, 0, 0, 1]),               # parallel
    ("exact-in-plane", [1, 2, 5, 1, -3, 0, 0, 0, 5, 0, 0, 1]),              # in-plane
    ("parallel-tilted", [3, 0, 0, 1, 1, 1, 0, 0, 0, 1, -2, 1]),             # d·n = 0, (p−o)·n = −3: parallel
    ("in-plane-tilted", [2, 1, 0, 1, 1, 1, 0, 0, 0, 1, -2, 1]),             # d·n = 0, (p−o)·n = 0: in-plane
    ("origin-on-plane", [0, 0, 5, 1, 2, 3, 7, -1, 5, 0, 0, 1]),             # hit +0
    ("origin-on-plane-negative-d", [0, 0, 5, 0, 0, -1, 7, -1, 5, 0, 0, 1]),  # hit +0 (not -0)
    # t = (2^53 + 1)/2^53 = 1 + 2^-53: halfway between 1 and 1 + 2^-52, ties to even → 1
    ("tie-to-even-down", [-1, 0, 0, TWO53, 0, 0, TWO53, 0, 0, 1, 0, 0]),
    # t = (2^53 + 3)/2^53: halfway between 1 + 2^-52 and 1 + 2^-51 → 1 + 2^-51 (even)
    ("tie-to-even-up", [-3, 0, 0, TWO53, 0, 0, TWO53, 0, 0, 1, 0, 0]),
    ("tie-behind", [1, 0, 0, TWO53, 0, 0, -TWO53, 0, 0, 1, 0, 0]),         # t = −(1 + 2^-53) → −1
    # README: products underflow in binary64; exact hit at t = 1
    ("subnormal-products-hit", [0, 0, 0, 2.0 ** -600, 0, 0, 2.0 ** -600, 0, 0, 2.0 ** -600, 0, 0]),
    # TOOLCHAIN: d·n's products underflow to 0 in doubles but d·n ≠ 0 exactly
    ("subnormal-den-sign", [0, 0, 0, -1.6e-151, 2.0e-319, 0, 1, 1, 1, 0, -1.6e-151, -1.6e-151]),
    ("subnormal-everywhere", [5e-324, -5e-324, 0, 5e-324, 1e-310, -2e-320, 1e-315, 5e-324, 3e-323,
                              -5e-324, 2.2250738585072009e-308, 1e-320]),
    ("min-subnormal-t", [0, 0, 0, 1, 0, 0, 5e-324, 0, 0, 1, 0, 0]),         # t = 2^-1074
    ("t-underflows-to-minus-zero", [2.0 ** -1000, 0, 0, -2.0 ** 600, 0, 0, 0, 0, 0, 1, 0, 0]),  # behind −0
    ("t-underflows-to-plus-zero", [-2.0 ** -1000, 0, 0, 2.0 ** 600, 0, 0, 0, 0, 0, 1, 0, 0]),   # hit +0 (rounded)
    ("t-overflows-to-inf", [0, 0, 0, 2.0 ** -1000, 0, 0, 2.0 ** 100, 0, 0, 1, 0, 0]),          # hit +inf
    ("t-overflows-to-minus-inf", [0, 0, 0, -(2.0 ** -1000), 0, 0, 2.0 ** 100, 0, 0, 1, 0, 0]),  # behind −inf
    ("t-just-below-overflow", [0, 0, 0, 1, 0, 0, 1.7976931348623157e308, 0, 0, 1, 0, 0]),    # t = DBL_MAX
    ("huge-products", [1e308, -1e308, 1e308, 1e308, 1e308, -1e308, -1e308, 1e308, 1e308, 1e308, 1e308, 1e308]),
    ("huge-difference", [-1.7e308, 0, 0, 1, 0, 0, 1.7e308, 0, 0, 1.7e308, 0, 0]),            # p − o overflows
    ("cancellation", [1e16, 1, 0, 1, 1e-16, 0, 1e16 + 2, -1, 0, 1, 1e16, 0]),
    ("signed-zeros", [-0.0, 0.0, -0.0, 0.0, -0.0, -1.0, 0.0, -0.0, 0.0, -0.0, 0.0, 1.0]),
    ("signed-zero-direction-components", [0, 0, 0, -0.0, -0.0, 2, 0, 0, 1, 0, -0.0, 1]),
    ("near-parallel", [0.1, 0.2, 0.3, 1, 1, -2.0000000000000004, 0.4, 0.5, 0.6, 1, 1, 1]),
    ("nan-origin", [NAN, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0]),
    ("nan-normal", [0, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, NAN]),
    ("inf-direction", [0, 0, 0, INF, 0, 0, 1, 0, 0, 1, 0, 0]),
    ("minus-inf-point", [0, 0, 0, 1, 0, 0, 0, -INF, 0, 1, 0, 0]),
    ("zero-direction", [0, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0]),
    ("minus-zero-direction", [0, 0, 0, -0.0, -0.0, -0.0, 1, 0, 0, 1, 0, 0]),
    ("zero-normal", [0, 0, 0, 1, 0, 0, 1, 0, 0, 0, -0.0, 0]),
    ("zero-direction-and-nan", [NAN, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0]),
]
# Bit patterns a float literal cannot spell: signalling and negative NaNs with payloads.
HAND_CLASSIFY_BITS = [
    ("nan-payload-negative", [0xFFF8000000000001] + [0] * 2 + [0x3FF0000000000000] + [0] * 5
     + [0x3FF0000000000000] + [0] * 2),
    ("signalling-nan", [0] * 3 + [0x3FF0000000000000, 0, 0] + [0x7FF0000000000001, 0, 0]
     + [0x3FF0000000000000, 0, 0]),
]

HAND_CLI = {
    "hand-readme-example": "0 0 0  0 0 1  0 0 5  0 0 1\n0 0 0  1 0 0  0 0 5  0 0 1\n0 0 0 10 0 0 1 0 0 1 0 0\n",
    "hand-blank-and-comments": "\n# a comment\n   # indented comment\n\t\r\n0 0 0 0 0 1 0 0 5 0 0 1\n\n",
    "hand-crlf": "0 0 0 0 0 1 0 0 5 0 0 1\r\n# c\r\n\r\n0 0 0 1 0 0 0 0 5 0 0 1\r\n",
    "hand-no-final-newline": "0 0 0 0 0 1 0 0 5 0 0 1\n0 0 0 0 0 -1 0 0 5 0 0 1",
    "hand-number-syntax": "1 -2.5 3e2\t0x1.8p1 .5 5. +7 -0 1e-400 0X10 0x1p-1074 4.9e-324\n"
                          "0x1P+0 0x.8p1 1E0 -0x0p0 +.5e1 1e+0 0x1.fffffffffffffp1023 2.2250738585072014e-308 1 0 0 1\n",
    "hand-invalid-tokens": "nan 0 0 1 0 0 0 0 0 1 0 0\n0 0 0 inf 0 0 1 0 0 1 0 0\n0 0 0 1 0 0 1 0 0 -infinity 0 0\n"
                           "0 0 0 1 0 0 1e400 0 0 1 0 0\n0 0 0 1 0 0 1 0 0 1 abc 0\n0 0 0 1 0 0 1 0 0 1 1.0x 0\n"
                           "0 0 0 1 0 0 1 0 0 1 0x 0\n0 0 0 1 0 0 1 0 0 1 nan(123) 0\n0 0 0 1 0 0 1 0 0 1 - 0\n"
                           "0 0 0 1 0 0 1 0 0 1 0x1p99999 0\n0 0 0 1 0 0 1 0 0 1 1,5 0\n",
    "hand-wrong-counts": "0 0 0 1 0 0 1 0 0 1 0\n0 0 0 1 0 0 1 0 0 1 0 0 7\n1\n0 0 0 1 0 0 1 0 0 1 0 0 # trailing\n",
    "hand-zero-vectors": "0 0 0 0 0 0 1 0 0 1 0 0\n0 0 0 1 0 0 1 0 0 -0 0 -0\n0 0 0 -0 -0 -0 1 0 0 0 0 0\n",
    "hand-control-bytes": "0 0 0 1 0 0 1 0 0 1 0 \x00\n0 0 0 1 0 0 1 0 0 1 0 0\x0b\n\x0c0 0 0 1 0 0 1 0 0 1 0 0\n"
                          "0 0 0 1 0 0 1 0 0 1 0 0\x7f\n\xff\xfe 0 0 1 0 0 1 0 0 1 0 0\n",
    "hand-extreme-values": "0 0 0 0x1p-600 0 0 0x1p-600 0 0 0x1p-600 0 0\n"
                           "0 0 0 -1.6e-151 2.0e-319 0 1 1 1 0 -1.6e-151 -1.6e-151\n"
                           "0 0 0 0x1p-1000 0 0 0x1p100 0 0 1 0 0\n"
                           "0x1p-1000 0 0 -0x1p600 0 0 0 0 0 1 0 0\n"
                           "-1 0 0 0x1p53 0 0 0x1p53 0 0 1 0 0\n",
    "hand-long-token": "0 0 0 1 0 0 1 0 0 1 0 " + "1" * 400 + "\n0 0 0 1 0 0 1 0 0 1 0 0." + "0" * 400 + "1\n",
    "hand-byte-order-mark": "\xef\xbb\xbf0 0 0 0 0 1 0 0 5 0 0 1\n\xef\xbb\xbf0 0 0 0 0 1 0 0 5 0 0 1\n",
    "hand-rounds-to-zero": "0 0 0 1e-400 0 0 1 0 0 1 0 0\n0 0 0 1 0 0 -2e-324 0 0 1 0 0\n0 0 0 1 0 0 1 0 0 1 0x1p-1075 0\n"
                           "0 0 0 4e-324 0 0 1 0 0 1 0 0\n0 0 0 1 0 0 1 0 0 1 0 0e-400\n0 0 0 1 0 0 1 0 0 1 0 2.4703282292062328e-324\n",
    "hand-messages": "0 0 0 0 0 1 0 0 5 0 0 1 # comment\n0,0,0,0,0,1,0,0,5,0,0,1\n0 0 0 0 0 1 0 0 5 0 0 \xe2\x80\xae1\n",
}

CLASSIFY_DICT = [
    ("zero", 0.0), ("minus_zero", -0.0), ("one", 1.0), ("minus_one", -1.0), ("two", 2.0), ("half", 0.5),
    ("three", 3.0), ("dbl_min", 2.2250738585072014e-308), ("dbl_true_min", 5e-324), ("dbl_max", 1.7976931348623157e308),
    ("minus_dbl_max", -1.7976931348623157e308), ("inf", INF), ("minus_inf", -INF), ("epsilon", 2.0 ** -52),
    ("one_plus_ulp", 1.0 + 2.0 ** -52), ("one_minus_half_ulp", 1.0 - 2.0 ** -53), ("two_53", TWO53),
    ("two_minus_537", 2.0 ** -537), ("two_511", 2.0 ** 511), ("two_minus_969", 2.0 ** -969), ("two_1000", 2.0 ** 1000),
    ("two_minus_1000", 2.0 ** -1000), ("largest_subnormal", 2.0 ** -1022 - 2.0 ** -1074), ("tenth", 0.1),
]


def dict_line(name, data):
    return name + '="' + "".join("\\x%02x" % b for b in data) + '"\n'


# ---- nearest ------------------------------------------------------------------------------------------------
# The layout of fuzz/fuzz_nearest.cpp: record 0 (97 bytes) is a classify input (ray and plane 0; raw below
# 0x80, hard query 0x80..0xBF) or, from 0xC0, a near-tie pair of kind (byte - 0xC0) mod 4 (ray, planes 0 and
# 1); every further record (49 bytes: a tag and 6 little-endian words) adds planes: a raw plane (tag < 0x40),
# the plane of a hard query of kind (tag - 0x40) mod 13 (tag < 0x80), or the derived plane (tag >> 4) & 7.
PAIR_KINDS = ["coincident", "pivot", "parallel-offset", "pivot-offset"]
DERIVED = ["coincident", "negated", "nudged", "parallel-offset", "through-ray-point", "pivot-about-point",
           "special-relation", "small-integers"]


def words_bytes(words, count):
    words = list(words) + [0] * (count - len(words))
    return b"".join(struct.pack("<Q", w & 0xFFFFFFFFFFFFFFFF) for w in words[:count])


def nearest_first_raw(ray, plane):
    return raw_input(list(ray) + list(plane))


def nearest_first_pair(kind, words):
    return bytes([0xC0 + PAIR_KINDS.index(kind)]) + words_bytes(words, 12)


def nearest_first_hard(kind, words):
    return bytes([0x80 + KINDS.index(kind)]) + words_bytes(words, 12)


def nearest_plane_raw(plane):
    return b"\x00" + b"".join(struct.pack("<d", float(v)) for v in plane)


def nearest_plane_bits(patterns):
    return b"\x00" + b"".join(struct.pack("<Q", p) for p in patterns)


def nearest_plane_hard(kind, words):
    return bytes([0x40 + KINDS.index(kind)]) + words_bytes(words, 6)


def nearest_plane_derived(op, words):
    """words[0] picks the plane K (mod the planes so far); the others are the construction's parameters."""
    return bytes([0x80 + 16 * DERIVED.index(op)]) + words_bytes(words, 6)


def nearest_input(ray, planes):
    """A ray and raw planes (at least one) as a nearest input."""
    return nearest_first_raw(ray, planes[0]) + b"".join(nearest_plane_raw(p) for p in planes[1:])


ULP7 = 2.0 ** -50  # ulp of 7 (in [4, 8))
HAND_NEAREST = [
    # the contract sample's planes 6-8: z = 7, its predecessor and successor; plane 3 is z = 7 again, normal -2
    ("contract-z7-neighbours", [0, 0, 0, 0, 0, 1],
     [[0, 0, 7, 0, 0, 1], [0, 0, 7 - ULP7 / 2, 0, 0, 1], [0, 0, 7 + ULP7, 0, 0, 1], [0, 0, 7, 0, 0, -2]]),
    # coincident planes (the same plane, other points and scaled normals): exact ties, the first hit wins
    ("coincident-scaled-normals", [1, 2, 3, 0.1, 0.2, 0.3],
     [[0, 0, 0, 1, -1, 0], [0, 0, 10, 1, 1, 1], [10, 0, 0, 2, 2, 2], [5, 5, 0, -0.5, -0.5, -0.5], [1, 2, 7, 3, 3, 3]]),
    # planes through one point of the ray, (2, 2, 2) = o + 2d: exact ties at t = 2
    ("pivot-common-point", [0, 0, 0, 1, 1, 1],
     [[0, 0, 5, 0, 0, -1], [2, 2, 2, 1, 0, 0], [2, 2, 2, 0, 1, 0], [2, 2, 2, 1, 2, 3], [2, 2, 2, 3, -1, 1]]),
    # the origin on several planes: t = +0 ties; plane 0 contains the ray (in-plane, never hit)
    ("origin-ties", [1, 1, 1, 0, 0, -1],
     [[0, 0, 1, 1, -1, 0], [1, 1, 1, 0, 0, 1], [0, 0, 2, 1, 0, 1], [3, 1, 1, 0, 0, -1], [1, 1, 0, 0, 0, 1]]),
    # behind, parallel and in-plane only: a miss (the reversed ray hits the behind plane)
    ("all-miss", [0, 0, 0, 1, 0, 0], [[-5, 0, 0, 1, 0, 0], [0, 3, 0, 0, 1, 0], [0, 0, 0, 0, 0, 1]]),
    # t = 5 ahead and t = -5 behind: the ray and the reversed ray pick different planes
    ("ahead-and-behind", [0, 0, 0, 0, 1, 0], [[0, -5, 0, 0, 1, 0], [0, 5, 0, 0, 1, 0]]),
    # both t beyond the double range (both round to +inf): the smaller exact t (plane 1) wins
    ("t-overflow-order", [0, 0, 0, 2.0 ** -1000, 0, 0],
     [[2.0 ** 100 * (1 + 2.0 ** -52), 0, 0, 1, 0, 0], [2.0 ** 100, 0, 0, 1, 0, 0]]),
    # both t below the subnormal range (both round to +0): the smaller exact t (plane 1) wins
    ("t-underflow-order", [0, 0, 0, 2.0 ** 600, 0, 0],
     [[2.0 ** -500 * (1 + 2.0 ** -52), 0, 0, 1, 0, 0], [2.0 ** -500, 0, 0, 1, 0, 0]]),
    # t in the subnormal range, less than a subnormal ulp apart
    ("t-subnormal-near-tie", [0, 0, 0, 2.0 ** 100, 0, 0],
     [[2.0 ** -975 * 3, 0, 0, 1, 0, 0], [2.0 ** -975 * 3 - 2.0 ** -1022, 0, 0, 1, 0, 0], [2.0 ** -975 * 3, 0, 0, 7, 0, 0]]),
    # t just below 2 and exactly 2: adjacent doubles across a binade boundary
    ("t-power-of-two-boundary", [0, 0, 0, 1, 0, 0],
     [[2, 0, 0, 1, 0, 0], [2 - 2.0 ** -52, 0, 0, 1, 0, 0], [2 - 2.0 ** -53, 0, 0, 1, 0, 0]]),
    # direction and normals near parallel: t large, differing in the last bits
    ("near-parallel-ties", [0, 0, 0, 1, 1e-15, 0],
     [[0, 1, 0, 0, 1, 0], [0, 1, 0, 1e-30, 1, 0], [0, 1 + 2.0 ** -52, 0, 0, 1, 0]]),
    # products that overflow and underflow binary64
    ("huge-and-tiny", [1e308, -1e308, 0, 1e-300, 1e-300, 1e-300],
     [[-1e308, 1e308, 1e308, 1e308, 1e308, 1e308], [5e-324, 0, 0, 1e-320, 1e-310, 1], [0, 0, 1e300, 0, 0, 1e300]]),
    # invalid input: the ray's reason comes first, then the first invalid plane
    ("invalid-ray-nan", [NAN, 0, 0, 1, 0, 0], [[1, 0, 0, 1, 0, 0]]),
    ("invalid-ray-zero-direction", [0, 0, 0, 0, -0.0, 0], [[1, 0, 0, 1, 0, 0], [1, 0, 0, 0, 0, 0]]),
    ("invalid-plane-2-zero-normal", [0, 0, 0, 1, 0, 0], [[1, 0, 0, 1, 0, 0], [2, 0, 0, 1, 0, 0], [3, 0, 0, 0, -0.0, 0],
                                                       [4, INF, 0, 1, 0, 0]]),
    ("invalid-plane-1-inf", [0, 0, 0, 1, 0, 0], [[1, 0, 0, 1, 0, 0], [-INF, 0, 0, 1, 0, 0]]),
    ("invalid-ray-and-plane", [0, 0, INF, 1, 0, 0], [[1, 0, 0, 0, 0, 0]]),
    # the moved ray o + d of the batch check overflows to inf
    ("moved-ray-overflows", [1.7e308, 0, 0, 1.7e308, 0, 0], [[0, 0, 0, 1, 0, 0]]),
]


def write_nearest(fuzz):
    corpus = fuzz / "corpus" / "nearest"
    clear_generated(corpus, ("contract-", "hand-", "pair-", "kind-", "derived-"))
    planes = [[strtod(t) for t in line.split()] for line in (CASES / "nearest-sample" / "planes.txt").read_text().splitlines()
              if line.split() and not line.lstrip().startswith("#")]
    rays = [[strtod(t) for t in line.split()] for line in (CASES / "nearest-sample" / "rays.txt").read_text().splitlines()
            if line.split() and not line.lstrip().startswith("#")]
    winners = [line.split() for line in (CASES / "nearest-sample" / "expected.txt").read_text().splitlines()]
    count = 0
    for i, ray in enumerate(rays):
        # every 10th ray against all 50 planes; the rays whose answer is one of the hand-made planes 0-10
        # (a pivot, z = 7 and its neighbours, coincident planes) against those 11 planes
        if i % 10 == 0:
            (corpus / ("contract-ray-%03d" % (i + 1))).write_bytes(nearest_input(ray, planes))
            count += 1
        if winners[i][0] == "hit" and int(winners[i][1]) <= 10:
            (corpus / ("contract-ties-%03d" % (i + 1))).write_bytes(nearest_input(ray, planes[:11]))
            count += 1
    for name, ray, ps in HAND_NEAREST:
        (corpus / ("hand-" + name)).write_bytes(nearest_input([float(v) for v in ray], [[float(v) for v in p] for p in ps]))

    rng = random.Random(5)  # fixed: the corpus is reproducible

    def some_words(n):
        return [rng.getrandbits(64) for _ in range(n)]

    # each pair kind, alone and with derived planes
    for kind in PAIR_KINDS:
        (corpus / ("pair-%s-0" % kind)).write_bytes(nearest_first_pair(kind, []))
        (corpus / ("pair-%s-1" % kind)).write_bytes(nearest_first_pair(kind, some_words(12)))
        data = nearest_first_pair(kind, some_words(12))
        for op in DERIVED:
            data += nearest_plane_derived(op, some_words(6))
        (corpus / ("pair-%s-2" % kind)).write_bytes(data)
    # each hard kind with a few planes: raw, hard, derived
    for kind in KINDS:
        data = nearest_first_hard(kind, some_words(12))
        data += nearest_plane_hard(KINDS[rng.randrange(len(KINDS))], some_words(6))
        for op in rng.sample(DERIVED, 3):
            data += nearest_plane_derived(op, some_words(6))
        (corpus / ("kind-%s" % kind)).write_bytes(data)
    # each derived kind: three planes of it after a pair, a hard query, and a raw query
    firsts = [nearest_first_pair("pivot", some_words(12)), nearest_first_hard("near-parallel", some_words(12)),
              nearest_first_raw([0.5, -1, 2, 1, 3, -2], [1, 1, 1, 2, 0.5, 1])]
    for op in DERIVED:
        for j, first in enumerate(firsts):
            data = first + b"".join(nearest_plane_derived(op, [k] + some_words(5)) for k in range(3))
            (corpus / ("derived-%s-%d" % (op, j))).write_bytes(data)

    tokens = [("zero", 0.0), ("minus_zero", -0.0), ("one", 1.0), ("minus_one", -1.0), ("seven", 7.0),
              ("seven_minus_ulp", 7 - ULP7 / 2), ("seven_plus_ulp", 7 + ULP7), ("dbl_true_min", 5e-324),
              ("dbl_max", 1.7976931348623157e308), ("inf", INF), ("two_minus_1000", 2.0 ** -1000),
              ("two_600", 2.0 ** 600), ("one_plus_ulp", 1.0 + 2.0 ** -52)]
    with open(fuzz / "dict" / "nearest.dict", "w") as f:
        f.write("# libFuzzer dictionary for fuzz_nearest: record tags and special doubles (generated by\n"
                "# fuzz/tools/make_seeds.py)\n")
        for k, kind in enumerate(PAIR_KINDS):
            f.write(dict_line("first_pair_%s" % kind.replace("-", "_"), bytes([0xC0 + k])))
        for k, op in enumerate(DERIVED):
            f.write(dict_line("derived_%s" % op.replace("-", "_"), bytes([0x80 + 16 * k])))
        for k, kind in enumerate(KINDS):
            f.write(dict_line("plane_of_%s" % kind.replace("-", "_"), bytes([0x40 + k])))
        for name, v in tokens:
            f.write(dict_line(name, struct.pack("<d", v)))
        f.write(dict_line("nan", struct.pack("<Q", 0x7FF8000000000000)))
    return count


# ---- nearest_cli ------------------------------------------------------------------------------------------
# The planes text, a line "%%", the rays text (fuzz/fuzz_nearest_cli.cpp); without a "%%" line the whole text
# is both files.
HAND_NEAREST_CLI = {
    "hand-readme-example": "0 0 5 0 0 1\n0 0 7 0 0 -2\n%%\n0 0 0 0 0 1\n0 0 0 1 0 0\n0 0 9 0 0 1\n",
    "hand-z7-neighbours": "0 0 7 0 0 1\n0 0 0x1.bffffffffffffp+2 0 0 1\n0 0 0x1.c000000000001p+2 0 0 1\n0 0 7 0 0 3\n%%\n"
                          "0 0 0 0 0 1\n0 0 14 0 0 -1\n0 0 0x1.bffffffffffffp+2 0 0 1\n1 1 1 0 0 0x1p-1074\n",
    "hand-coincident-and-pivot": "0 0 10 1 1 1\n10 0 0 2 2 2\n2 2 2 1 0 0\n2 2 2 0 1 0\n%%\n0 0 0 1 1 1\n0 0 0 -1 -1 -1\n",
    "hand-no-separator": "0 0 1 0 0 1\n1 2 3 4 5 6\n-1 0.5 2 0 1 0\n",
    "hand-empty-planes": "%%\n0 0 0 0 0 1\n# comment\n\n1 1 1 1 0 0\n",
    "hand-comments-and-blanks": "# planes\n\n   # indented\n0 0 5 0 0 1\n\t\r\n%%\n# rays\n0 0 0 0 0 1\n\n",
    "hand-crlf": "0 0 5 0 0 1\r\n0 0 3 0 0 1\r\n%%\n0 0 0 0 0 1\r\n0 0 9 0 0 -1\r\n",
    "hand-separator-variants": "0 0 5 0 0 1\n%%\r\n%%\n %%\n%%\n0 0 0 0 0 1\n",
    "hand-invalid-plane-token": "0 0 5 0 0 1\n0 0 6 0 0 x\n%%\n0 0 0 0 0 1\n",
    "hand-invalid-plane-zero-normal": "# first\n0 0 5 0 0 1\n\n1 2 3 0 -0 0\n%%\n0 0 0 0 0 1\n",
    "hand-invalid-plane-count": "0 0 5 0 0\n%%\n0 0 0 0 0 1\n",
    "hand-invalid-plane-nan": "0 0 5 0 0 1\nnan 0 5 0 0 1\n%%\n0 0 0 0 0 1\n",
    "hand-invalid-plane-overflow": "0 0 1e309 0 0 1\n%%\n0 0 0 0 0 1\n",
    "hand-invalid-plane-last-line-no-newline": "0 0 5 0 0 1\n0 0 5 0 0",
    "hand-invalid-rays": "0 0 5 0 0 1\n%%\n0 0 0 0 0 0\n0 0 0 0 0 1 7\n0 0 inf 0 0 1\n0 0 0 0x 0 1\n1e400 0 0 1 0 0\n"
                         "0 0 0 0 0 1\n",
    "hand-number-syntax": "0x1p1 .5 5. 0X1P-1 +1 -0\n%%\n1e-400 0x1p-1074 4.9e-324 -0 +.5e1 0x.8p1\n",
    "hand-extreme-values": "0 0 0x1p100 0 0 1\n0 0 0x1.0000000000001p100 0 0 1\n0 0 -1 0 0 1\n%%\n"
                           "0 0 0 0 0 0x1p-1000\n0 0 0 0 0 -0x1p-1000\n0 0 0 0x1p-600 0 0x1p-600\n",
    "hand-control-bytes": "0 0 5 0 0 1\x0b\n\x0c0 0 3 0 0 1\n%%\n0 0 0 0 0 1\x00\n\xff 0 0 0 0 1\n0 0 0 0 0 1\x7f\n",
    "hand-long-token": "0 0 5 0 0 " + "1" * 400 + "\n%%\n0 0 0 0 0 0." + "0" * 400 + "1\n",
    "hand-byte-order-mark": "\xef\xbb\xbf0 0 5 0 0 1\n%%\n0 0 0 0 0 1\n",
    "hand-rounds-to-zero": "0 0 5 0 0 1\n%%\n0 0 0 0 0 1e-400\n0 0 0 0 0 -2e-324\n0 0 0 0 0 4e-324\n",
    "hand-rounds-to-zero-plane": "0 0 5 0 0 1\n0 0 5 0 0 1e-400\n%%\n0 0 0 0 0 1\n",
}


def write_nearest_cli(fuzz):
    corpus = fuzz / "corpus" / "nearest_cli"
    clear_generated(corpus, ("contract-", "hand-"))
    planes = (CASES / "nearest-sample" / "planes.txt").read_bytes()
    rays = (CASES / "nearest-sample" / "rays.txt").read_bytes()
    (corpus / "contract-sample").write_bytes(planes + b"%%\n" + rays)
    plane_lines = planes.splitlines(keepends=True)
    ray_lines = rays.splitlines(keepends=True)
    for c in range(0, len(ray_lines), 8):  # all planes, 8 rays
        (corpus / ("contract-sample.rays%03d" % (c // 8))).write_bytes(planes + b"%%\n" + b"".join(ray_lines[c:c + 8]))
    for c in range(0, len(plane_lines), 8):  # 8 planes, also read as rays
        (corpus / ("contract-planes.part%03d" % (c // 8))).write_bytes(b"".join(plane_lines[c:c + 8]))
    for name, text in HAND_NEAREST_CLI.items():
        (corpus / name).write_bytes(text.encode("latin-1"))


# ---- scene --------------------------------------------------------------------------------------------------
# Scene files (fuzz/fuzz_scene.cpp): the example scenes, the built-in demo, and broken variants of the demo.
def demo_scene_text():
    """The text of demo_scene_json(): scenes/demo.json, which the build compiles in."""
    return (ROOT / "scenes" / "demo.json").read_text()


def scene_variants(demo):
    """(name, text) of broken or unusual variants of the demo scene, each aimed at one check of the parser."""
    import copy
    import json

    def edit(name, change):
        doc = copy.deepcopy(demo)
        change(doc)
        return name, json.dumps(doc, indent=1)

    def delete(path):
        def change(doc):
            for key in path[:-1]:
                doc = doc[key]
            del doc[path[-1]]
        return change

    def put(path, value):
        def change(doc):
            for key in path[:-1]:
                doc = doc[key]
            doc[path[-1]] = value
        return change

    out = []
    for path in [["image"], ["camera"], ["planes"], ["image", "width"], ["image", "height"], ["camera", "eye"],
                 ["camera", "target"], ["camera", "up"], ["camera", "perspective"], ["camera", "perspective", "fov_degrees"],
                 ["planes", 0, "point"], ["planes", 0, "normal"], ["planes", 0, "checker"], ["planes", 1, "color"],
                 ["planes", 0, "checker", "colors"], ["planes", 0, "checker", "size"], ["fog", "distance"]]:
        out.append(edit("missing-" + "-".join(str(k) for k in path), delete(path)))
    for name, path, value in [
            ("width-string", ["image", "width"], "960"), ("width-fraction", ["image", "width"], 960.5),
            ("width-negative", ["image", "width"], -1), ("width-zero", ["image", "width"], 0),
            ("height-too-large", ["image", "height"], 10 ** 9), ("samples-zero", ["image", "samples_per_pixel"], 0),
            ("seed-negative", ["image", "seed"], -1), ("seed-huge", ["image", "seed"], 2 ** 64 - 1),
            ("eye-string", ["camera", "eye"], "x"), ("eye-two-numbers", ["camera", "eye"], [1, 2]),
            ("eye-four-numbers", ["camera", "eye"], [1, 2, 3, 4]), ("eye-null-component", ["camera", "eye"], [1, None, 3]),
            ("eye-is-target", ["camera", "eye"], [-0.4, 0.9, -2.0]), ("up-zero", ["camera", "up"], [0, 0, -0.0]),
            ("up-along-view", ["camera", "up"], [-1.3, -0.9, -10.0]), ("fov-zero", ["camera", "perspective", "fov_degrees"], 0),
            ("fov-180", ["camera", "perspective", "fov_degrees"], 180), ("fov-wide", ["camera", "perspective", "fov_degrees"], 179.999999),
            ("near-zero", ["camera", "perspective", "near"], 0), ("near-negative", ["camera", "perspective", "near"], -1),
            ("near-huge", ["camera", "perspective", "near"], 1e300), ("near-tiny", ["camera", "perspective", "near"], 5e-324),
            ("normal-zero", ["planes", 0, "normal"], [0, 0, 0]), ("normal-minus-zero", ["planes", 0, "normal"], [-0.0, 0, -0.0]),
            ("normal-subnormal", ["planes", 0, "normal"], [0, 5e-324, 0]), ("normal-huge", ["planes", 2, "normal"], [1.7976931348623157e308, 0, -1e308]),
            ("point-huge", ["planes", 1, "point"], [1e308, -1e308, 1e308]), ("eye-huge", ["camera", "eye"], [1e308, 1e308, 1e308]),
            ("eye-and-target-far-apart", ["camera", "target"], [-1e308, -1e308, -1e308]),
            ("color-out-of-range", ["planes", 1, "color"], [2, 0, 0]), ("color-negative", ["planes", 1, "color"], [0, -0.1, 0]),
            ("colors-three", ["planes", 0, "checker", "colors"], [[0, 0, 0], [1, 1, 1], [0.5, 0.5, 0.5]]),
            ("checker-size-zero", ["planes", 0, "checker", "size"], 0), ("checker-size-tiny", ["planes", 0, "checker", "size"], 5e-324),
            ("checker-size-huge", ["planes", 0, "checker", "size"], 1e308),
            ("u-axis-along-normal", ["planes", 0, "checker", "u_axis"], [0, 2, 0]), ("u-axis-zero", ["planes", 0, "checker", "u_axis"], [0, 0, 0]),
            ("u-axis-tilted", ["planes", 0, "checker", "u_axis"], [1, 1, 1e-300]),
            ("planes-object", ["planes"], {}), ("planes-empty", ["planes"], []), ("plane-number", ["planes", 0], 7),
            ("name-number", ["planes", 0, "name"], 5), ("description-number", ["description"], 7),
            ("background-string", ["background"], "blue"), ("background-array", ["background"], [0.1, 0.2, 0.3]),
            ("background-extra-field", ["background", "sunset"], [1, 0, 0]), ("fog-zero", ["fog", "distance"], 0),
            ("fog-array", ["fog"], [150]), ("unknown-field", ["planez"], []), ("unknown-field-escaped", ["a/b~c"], 1),
            ("both-color-and-checker", ["planes", 0, "color"], [0, 0, 0]),
            ("both-projections", ["camera", "orthographic"], {"height": 4}),
            ("fov-and-window", ["camera", "perspective", "window"], {"left": -1, "right": 1, "bottom": -1, "top": 1})]:
        out.append(edit(name, put(path, value)))

    def orthographic(extra):
        def change(doc):
            del doc["camera"]["perspective"]
            doc["camera"]["orthographic"] = extra
        return change
    for name, extra in [("orthographic", {"height": 6}), ("orthographic-huge", {"height": 1e308}),
                        ("orthographic-window", {"window": {"left": -3, "right": 3, "bottom": -1, "top": 2}, "near": -5}),
                        ("orthographic-window-empty", {"window": {"left": 1, "right": 1, "bottom": -1, "top": 2}}),
                        ("orthographic-window-large", {"window": {"left": -1e300, "right": 1e300, "bottom": -1e300, "top": 1e300}}),
                        ("orthographic-none", {})]:
        out.append(edit(name, orthographic(extra)))

    def window(w, near):
        def change(doc):
            doc["camera"]["perspective"] = {"window": w} if near is None else {"window": w, "near": near}
        return change
    out.append(edit("perspective-window", window({"left": -0.2, "right": 0.1, "bottom": -0.05, "top": 0.1}, 0.1)))
    out.append(edit("perspective-window-no-near", window({"left": -0.2, "right": 0.1, "bottom": -0.05, "top": 0.1}, None)))
    out.append(edit("perspective-window-large", window({"left": -1e300, "right": 1e300, "bottom": -1, "top": 1}, 1e300)))
    out.append(edit("perspective-window-reversed", window({"left": 1, "right": -1, "bottom": -1, "top": 1}, 1)))

    def many_planes(doc):
        doc["planes"] = [{"point": [0, 0, -k], "normal": [k % 3, 1, k % 5], "color": [k / 50, 0.5, 0.5]} for k in range(50)]
    out.append(edit("planes-fifty", many_planes))

    text = json.dumps(demo, indent=1)
    out += [("syntax-empty", ""), ("syntax-null", "null"), ("syntax-array", "[]"), ("syntax-string", '"scene"'),
            ("syntax-open-brace", "{"), ("syntax-truncated", text[:200]), ("syntax-trailing-garbage", text + "x"),
            ("syntax-nan", text.replace("0.92", "NaN", 1)), ("syntax-infinity", text.replace("0.92", "Infinity", 1)),
            ("syntax-number-overflow", text.replace('"normal": [0, 1, 0]', '"normal": [0, 1e400, 0]', 1)),
            ("syntax-number-overflow-negative", text.replace('"eye": [0.9', '"eye": [-1e99999', 1)),
            ("syntax-comment", "// a comment\n" + text), ("syntax-bom", "\ufeff" + text),
            ("syntax-deep-nesting", "[" * 2000 + "]" * 2000), ("syntax-nesting-at-the-limit", "[" * 64 + "]" * 64),
            ("syntax-deep-nesting-unclosed", "[" * 100000), ("syntax-deep-nesting-objects", '{"a~/": ' * 100),
            ("mesh-file-nul", '{"camera": {"eye": [0, 2, 6], "target": [0, 0, 0]}, "planes": [], '
                              '"meshes": [{"file": "octahedron.off\\u0000x"}]}'), ("syntax-deep-nesting-in-field", text.replace('"fog": {"distance": 150}', '"fog": ' + "[" * 500 + "]" * 500)),
            ("syntax-invalid-utf8", text.replace('"floor"', '"fl\udcffor"', 1)),
            ("duplicate-keys", text.replace('"fog": {', '"fog": {"distance": -1, ', 1)),
            ("duplicate-keys-nested", text.replace('"name": "pool",', '"name": "pool", "name": "pond",', 1)),
            ("numbers-as-big-integers", text.replace('"width": 960', '"width": 18446744073709551616', 1)),
            ("integer-with-exponent", text.replace('"width": 960', '"width": 9.6e2', 1)),
            ("integer-with-fraction-zero", text.replace('"seed": 1', '"seed": 1.000', 1)),
            ("seed-two-64", text.replace('"seed": 1', '"seed": 1.8446744073709552e19', 1)),
            ("seed-minus-zero", text.replace('"seed": 1', '"seed": -0.0', 1)),
            ("minimal", '{"camera": {"eye": [0, 2, 6], "target": [0, 0, 0]},\n "planes": [{"point": [0, 0, 0], "normal": [0, 1, 0]},'
                        ' {"point": [0, 0, -4], "normal": [0, 0, 1]}]}'),
            ("minimal-looking-down", '{"camera": {"eye": [0, 5, 0], "target": [0, 0, 0]}, "planes": []}'),
            ("ray-start-eye", text.replace('"near": 0.1}', '"near": 0.1, "ray_start": "eye"}', 1)),
            ("ray-start-unknown", text.replace('"near": 0.1}', '"near": 0.1, "ray_start": "pupil"}', 1))]
    return out


def write_scene(fuzz):
    corpus = fuzz / "corpus" / "scene"
    clear_generated(corpus, ("scene-", "demo-", "broken-"))
    import json
    for f in sorted((ROOT / "scenes").glob("*.json")):
        (corpus / ("scene-" + f.stem)).write_bytes(f.read_bytes())
    demo = demo_scene_text()
    if demo.encode() != (ROOT / "scenes" / "demo.json").read_bytes():  # render_test keeps them identical
        (corpus / "demo-scene-json").write_text(demo)
    for name, text in scene_variants(json.loads(demo)):
        (corpus / ("broken-" + name)).write_bytes(text.encode("utf-8", "surrogateescape"))

    tokens = ['{', '}', '[', ']', ':', ',', '"', 'true', 'false', 'null', '0', '-0', '1', '-1', '0.5', '1e308', '1e309',
              '1e400', '-1e400', '5e-324', '1.7976931348623157e308', '2.2250738585072014e-308', '179.99999999999997',
              '18446744073709551615', '18446744073709551616', '-9223372036854775809', '\\u0000', '\\"', '\\/', '~0', '~1',
              '[0, 0, 0]', '[0, 1, 0]', '[1e308, 1e308, 1e308]', '[0.5, 0.5, 0.5]', '1e3', '9.6e2', '1.8446744073709552e19',
              '"eye"', '"near_plane"']
    fields = ["description", "image", "width", "height", "samples_per_pixel", "seed", "camera", "eye", "target", "up",
              "perspective", "orthographic", "fov_degrees", "near", "window", "left", "right", "bottom", "top",
              "background", "horizon", "zenith", "fog", "distance", "planes", "name", "point", "normal", "color",
              "checker", "colors", "size", "u_axis", "ray_start"]
    with open(fuzz / "dict" / "scene.dict", "w") as f:
        f.write("# libFuzzer dictionary for fuzz_scene: JSON syntax, numbers at the edges of binary64, the scene format's\n"
                "# field names (generated by fuzz/tools/make_seeds.py)\n")
        for i, t in enumerate(tokens):
            f.write(dict_line("j%02d" % i, t.encode()))
        for name in fields:
            f.write(dict_line("field_" + name, ('"%s":' % name).encode()))


def main():
    classify = FUZZ / "corpus" / "plane"
    cli = FUZZ / "corpus" / "cli"
    clear_generated(classify, ("sample-", "hand-", "kind-"))
    clear_generated(cli, ("contract-", "hand-"))

    sample = (CASES / "classify-sample.txt").read_text().splitlines()
    count = 0
    for number, line in enumerate(sample, start=1):
        tokens = line.split()
        if len(tokens) != 12 or tokens[0].startswith("#"):
            continue
        try:
            values = [strtod(t) for t in tokens]
        except ValueError:
            continue  # a bad token: a CLI case, not a query
        (classify / ("sample-%03d" % number)).write_bytes(raw_input(values))
        count += 1

    for name, values in HAND_CLASSIFY:
        (classify / ("hand-" + name)).write_bytes(raw_input([float(v) for v in values]))
    for name, patterns in HAND_CLASSIFY_BITS:
        (classify / ("hand-" + name)).write_bytes(raw_bits_input(patterns))

    rng = random.Random(4)  # fixed: the corpus is reproducible
    for k, kind in enumerate(KINDS):
        for i in range(4):
            words = [0] * 24 if i == 0 else [rng.getrandbits(64) for _ in range(24)]
            data = bytes([0x80 + k]) + b"".join(struct.pack("<Q", w) for w in words)
            (classify / ("kind-%s-%d" % (kind, i))).write_bytes(data)

    batch = FUZZ / "corpus" / "batch"
    clear_generated(batch, ("mix-",))
    records = [(f.read_bytes() + bytes(97))[:97] for f in sorted(classify.iterdir())
               if f.name.startswith(("sample-", "hand-", "kind-"))]
    sizes = [1, 3, 8, 9, 17, 33, 40]
    start, m = 0, 0
    while start < len(records):
        size = sizes[m % len(sizes)]
        (batch / ("mix-%03d" % m)).write_bytes(b"".join(records[start:start + size]))
        start += size
        m += 1

    for src, name in [(CASES / "classify-sample.txt", "contract-classify-sample.txt"),
                      (CASES / "nearest-sample" / "planes.txt", "contract-nearest-planes.txt"),
                      (CASES / "nearest-sample" / "rays.txt", "contract-nearest-rays.txt")]:
        text = src.read_bytes()
        (cli / name).write_bytes(text)
        lines = text.splitlines(keepends=True)
        for c in range(0, len(lines), 8):
            (cli / ("%s.part%03d" % (name, c // 8))).write_bytes(b"".join(lines[c:c + 8]))
    for name, text in HAND_CLI.items():
        (cli / name).write_bytes(text.encode("latin-1"))

    with open(FUZZ / "dict" / "plane.dict", "w") as f:
        f.write("# libFuzzer dictionary for fuzz_plane: special doubles as little-endian bit patterns\n"
                "# (generated by fuzz/tools/make_seeds.py)\n")
        for name, v in CLASSIFY_DICT:
            f.write(dict_line(name, struct.pack("<d", v)))
        f.write(dict_line("nan", struct.pack("<Q", 0x7FF8000000000000)))
        f.write(dict_line("minus_nan", struct.pack("<Q", 0xFFF8000000000000)))
        for k in range(len(KINDS)):
            f.write(dict_line("selector_%s" % KINDS[k].replace("-", "_"), bytes([0x80 + k])))

    cli_tokens = ["0x", "0X", "p", "P", "p-1074", "p+1023", "e", "E", "e-400", "e308", "e309", "e-324", ".", "-", "+",
                  "-0", "inf", "-inf", "infinity", "nan", "nan(1)", "#", " ", "\t", "\r", "\n", "\r\n", "\x0b", "\x0c",
                  "0x1p-1074", "0x1.fffffffffffffp1023", "0x1p1024", "4.9e-324", "2.4703282292062327e-324",
                  "2.4703282292062328e-324", "1.7976931348623157e308", "1.7976931348623158e308",
                  "1.7976931348623159e308", "2.2250738585072011e-308", "0.1", "1e16", "9007199254740993",
                  "0 0 0 1 0 0 1 0 0 1 0 0\n", "0 0 0 0 0 0 ", "0 0 0 ", "\xef\xbb\xbf", "1e-400", "-2e-324", "0x1p-1075",
                  ","]
    with open(FUZZ / "dict" / "cli.dict", "w") as f:
        f.write("# libFuzzer dictionary for fuzz_cli: number syntax (generated by fuzz/tools/make_seeds.py)\n")
        for i, t in enumerate(cli_tokens):
            f.write(dict_line("t%02d" % i, t.encode("latin-1")))
    nearest_tokens = cli_tokens[:42] + ["%%\n", "\n%%\n", "0 0 0 0 0 1\n", "0 0 5 0 0 1\n", "0 0 0 ",
                                        "0x1.bffffffffffffp+2", "0x1.c000000000001p+2", "\xef\xbb\xbf", "1e-400"]
    with open(FUZZ / "dict" / "nearest_cli.dict", "w") as f:
        f.write("# libFuzzer dictionary for fuzz_nearest_cli: number syntax, the %% line between the planes and the\n"
                "# rays, plane and ray lines (generated by fuzz/tools/make_seeds.py)\n")
        for i, t in enumerate(nearest_tokens):
            f.write(dict_line("t%02d" % i, t.encode("latin-1")))

    nearest = write_nearest(FUZZ)
    write_nearest_cli(FUZZ)
    write_scene(FUZZ)
    files = {h: len(list((FUZZ / "corpus" / h).iterdir())) for h in ("nearest", "nearest_cli", "scene")}
    print("nearest: %d contract seeds, %d files; nearest_cli: %d files; scene: %d files"
          % (nearest, files["nearest"], files["nearest_cli"], files["scene"]))
    print("classify: %d sample lines, %d hand-made, %d hard-query seeds; batch: %d; cli: %d files"
          % (count, len(HAND_CLASSIFY) + len(HAND_CLASSIFY_BITS), 4 * len(KINDS), m, len(list(cli.iterdir()))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
