#!/usr/bin/env python3
"""Writes the seed corpora and dictionaries of fuzz/ (run from anywhere; rewrites the generated files only).

  fuzz/corpus/classify/sample-NNN        each query line of tests/data/contract-cases/classify-sample.txt with
                                         12 tokens, as a raw input (selector 0x00 + 12 little-endian doubles)
  fuzz/corpus/classify/hand-<what>       hand-made degenerate cases (below), raw inputs
  fuzz/corpus/classify/kind-<kind>-N     hard-query inputs: selector 0x80 + k and a few fixed words
  fuzz/corpus/batch/mix-NNN              the classify seeds above, cut to 97-byte records, concatenated into
                                         batches of 1 to 40 queries
  fuzz/corpus/cli/contract-*             the contract's sample text files, whole and in chunks of 8 lines
  fuzz/corpus/cli/hand-<what>            hand-made texts (below)
  fuzz/dict/classify.dict                special doubles as 8-byte little-endian tokens
  fuzz/dict/cli.dict                     number syntax tokens

Files named regression-* (inputs that made a harness fail) and mutant-* (inputs that killed a deliberately
broken kernel) are added by hand and never touched here.
The layout of a classify input is raykernel/testing/fuzz_decoder.hpp's.
"""
import pathlib
import random
import struct
import sys

FUZZ = pathlib.Path(__file__).resolve().parent.parent
ROOT = FUZZ.parent
CASES = ROOT / "tests" / "data" / "contract-cases"

KINDS = ["random", "wide-exponents", "near-parallel", "near-coplanar", "exact-parallel", "exact-in-plane",
         "origin-on-plane", "rounding-tie", "near-tie", "subnormal", "huge-products", "t-overflow", "t-underflow"]

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


def main():
    classify = FUZZ / "corpus" / "classify"
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

    with open(FUZZ / "dict" / "classify.dict", "w") as f:
        f.write("# libFuzzer dictionary for fuzz_classify: special doubles as little-endian bit patterns\n"
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
                  "0 0 0 1 0 0 1 0 0 1 0 0\n", "0 0 0 0 0 0 ", "0 0 0 "]
    with open(FUZZ / "dict" / "cli.dict", "w") as f:
        f.write("# libFuzzer dictionary for fuzz_cli: number syntax (generated by fuzz/tools/make_seeds.py)\n")
        for i, t in enumerate(cli_tokens):
            f.write(dict_line("t%02d" % i, t.encode("latin-1")))

    print("classify: %d sample lines, %d hand-made, %d hard-query seeds; batch: %d; cli: %d files"
          % (count, len(HAND_CLASSIFY) + len(HAND_CLASSIFY_BITS), 4 * len(KINDS), m, len(list(cli.iterdir()))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
