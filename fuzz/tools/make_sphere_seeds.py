#!/usr/bin/env python3
"""Writes the seed corpus and dictionary of fuzz_sphere (run from anywhere; rewrites the generated files only).

  fuzz/corpus/sphere/sample-NNN     each query line of tests/data/contract-cases/sphere-sample.txt with 10
                                    tokens, as a raw input (selector 0x00 + 10 little-endian doubles)
  fuzz/corpus/sphere/kind-<kind>-N  hard-query inputs: selector 0x80 + k and fixed words
  fuzz/dict/sphere.dict             special doubles as 8-byte little-endian tokens, and the selectors

Files named regression-* are added by hand and never touched here. The layout is fuzz/fuzz_sphere.cpp's.
"""
import pathlib
import random
import struct

from make_triangle_seeds import FUZZ, ROOT, strtod, write_dictionary

KINDS = ["random", "tangent", "near-tangent", "on-surface", "near-surface", "rounding-tie", "far-cancel",
         "wide-exponents", "tiny-direction", "huge-direction", "tiny", "huge"]


def main():
    corpus = FUZZ / "corpus" / "sphere"
    corpus.mkdir(parents=True, exist_ok=True)
    for f in corpus.iterdir():
        if not f.name.startswith("regression-"):
            f.unlink()
    n = 0
    for line in (ROOT / "tests/data/contract-cases/sphere-sample.txt").read_text().splitlines():
        tokens = line.split()
        if len(tokens) != 10 or tokens[0].startswith("#"):
            continue
        try:
            values = [strtod(t) for t in tokens]
        except ValueError:
            continue
        (corpus / ("sample-%03d" % n)).write_bytes(b"\x00" + b"".join(struct.pack("<d", v) for v in values))
        n += 1
    rng = random.Random(29)
    for k, kind in enumerate(KINDS):
        for i in range(4):
            words = [rng.getrandbits(64) for _ in range(24)]
            data = bytes([0x80 + k]) + b"".join(struct.pack("<Q", w) for w in words)
            (corpus / ("kind-%s-%d" % (kind, i))).write_bytes(data)
    write_dictionary(FUZZ / "dict" / "sphere.dict", "fuzz_sphere", "make_sphere_seeds.py", KINDS)


if __name__ == "__main__":
    main()
