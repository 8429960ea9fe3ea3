#!/usr/bin/env python3
"""Writes the seed corpus of fuzz_closest (fuzz/fuzz_closest.cpp, words of fuzz/mesh_words.hpp): query points at
vertices, on edges and faces, on the grid around the mesh, at every scale, with extra triangles (shared vertices,
degenerate, copies), and non-finite points.

    fuzz/tools/make_closest_seeds.py     (from the repository root; rewrites fuzz/corpus/closest/seed-*)
"""
import os
import struct

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
corpus = os.path.join(root, "corpus", "closest")
os.makedirs(corpus, exist_ok=True)
for f in os.listdir(corpus):
    if f.startswith("seed-"):
        os.remove(os.path.join(corpus, f))


def head(cube, scale_code, extra):
    return bytes([(1 if cube else 0) | (scale_code << 1) | (extra << 6)])


def vertex(index):  # tag 0x40: a vertex coordinate (index counts vertices then axes)
    return struct.pack("<Q", (0x40 << 56) | index)


def quarter(k):  # tag 0x80: (k mod 17 − 8)/4 of the scale
    return struct.pack("<Q", (0x80 << 56) | k)


def integer(k):  # tag 0xC0: (k mod 9 − 4) times the scale
    return struct.pack("<Q", (0xC0 << 56) | k)


def raw(x):  # tag < 0x40: the raw bits (the top 6 bits of the double come from the tag)
    bits = struct.unpack("<Q", struct.pack("<d", x))[0]
    return struct.pack("<Q", ((bits >> 58) << 56) | (bits & ((1 << 56) - 1)))


seeds = {
    "vertex": head(False, 4, 0) + vertex(0) + vertex(6) + vertex(12),
    "outside-vertex": head(False, 4, 0) + integer(6) + integer(4) + integer(4),
    "edge-midpoint-grid": head(False, 4, 0) + quarter(10) + quarter(10) + quarter(8),
    "centre": head(True, 4, 0) + quarter(8) + quarter(8) + quarter(8),
    "cube-corner": head(True, 4, 0) + integer(0) + integer(0) + integer(0),
    "cube-face": head(True, 4, 0) + quarter(10) + quarter(9) + integer(8),
    "tiny-scale": head(False, 0, 0) + quarter(11) + quarter(3) + quarter(14),
    "huge-scale": head(True, 7, 0) + quarter(1) + quarter(16) + quarter(12),
    "degenerate-extra": head(False, 4, 1) + vertex(0) + vertex(1) + vertex(2) + vertex(0) + vertex(1) + vertex(2)
    + quarter(12) + quarter(12) + quarter(12) + quarter(13) + quarter(9) + quarter(6),
    "copy-extra": head(False, 4, 1) + vertex(0) + vertex(6) + vertex(12) + vertex(2) + vertex(8) + vertex(14)
    + vertex(4) + vertex(10) + vertex(16) + quarter(9) + quarter(9) + quarter(9),
    "sliver-extra": head(True, 4, 2) + raw(0.1) + raw(0.2) + raw(0.3) + raw(0.1) + raw(0.2) + raw(0.30000000000000004)
    + raw(0.7) + raw(0.2) + raw(0.3) + raw(0.1) + raw(0.2) + raw(0.3) + raw(-0.1) + raw(0.2) + raw(0.3)
    + raw(0.5) + raw(0.5) + raw(0.5) + raw(0.2) + raw(0.2) + raw(0.31),
    "raw-point": head(False, 4, 0) + raw(0.3) + raw(-0.7) + raw(1e-300),
    "subnormal-point": head(False, 0, 0) + raw(5e-324) + raw(0.0) + raw(-5e-324),
    "nan-point": head(False, 4, 0) + raw(float("nan")) + raw(0.0) + raw(0.0),
    "inf-point": head(False, 4, 0) + raw(0.0) + raw(float("inf")) + raw(0.0),
}
for name, data in seeds.items():
    with open(os.path.join(corpus, "seed-" + name), "wb") as f:
        f.write(data)
print(f"{len(seeds)} seeds in {corpus}")
