#!/usr/bin/env python3
"""Writes scenes/spheres-cover.json: a scene in the spirit of the cover of Ray Tracing in One Weekend — a huge
ground sphere (centre (0, -1000, 0), radius 1000), three large spheres on it and some hundreds of small ones —
in which contact is exact, so that the textbook formula has something to get wrong:

- "resting" small spheres touch the ground exactly: the centre is the ground's centre plus (a, b, c)·s with
  a² + b² + c² = n² in integers and s = 2^-10, so the distance between the centres is n·s = 1000 + r exactly
  (r = n·s − 1000, a dyadic), every coordinate an exact double;
- "pairs" of small spheres touch each other exactly: offsets (3, 0, 4)·k between centres whose radii sum to 5k;
- the others float just above the ground, or sink into it, by 2^-20 (a gap or an overlap far below what a
  pixel shows);
- "twins": a sphere given twice with the same centre, the second radius larger by a few ulps (as Mitsuba's
  nested spheres 4·10^-5 apart, PR #1871, but closer). The larger one is always hit first; plain doubles
  compute equal or reversed t for most rays and show the inner one in speckles.

Deterministic (a fixed seed); run it again to regenerate the file. Usage: make_sphere_scene.py [OUTPUT]."""
import json
import math
import random
import sys

S = 2.0 ** -10           # the lattice step of the resting spheres' centres
GROUND_R = 1000.0
N0 = int(GROUND_R / S)   # n·s = 1000 + r


def resting_centres(rng, count):
    """Integer (a, b, c, n) with a² + b² + c² = n², n·s − 1000 a radius in [0.15, 0.3], |a|, |c|·s ≤ 11."""
    found = []
    tries = 0
    while len(found) < count and tries < 2000000:
        tries += 1
        r_units = rng.randrange(int(0.15 / S), int(0.3 / S))
        n = N0 + r_units
        x = rng.uniform(-11, 11)
        a = int(round(x / S))
        k = rng.randrange(1, 200)           # n − b
        rest = k * (2 * n - k) - a * a      # = c²
        if rest < 0:
            continue
        c = math.isqrt(rest)
        if c * c != rest or c * S > 11:
            continue
        if rng.random() < 0.5:
            c = -c
        b = n - k
        found.append(((a * S, b * S - GROUND_R, c * S), n * S - GROUND_R))
    return found


def colour(rng):
    return [round(rng.uniform(0.15, 0.95), 3) for _ in range(3)]


def main():
    rng = random.Random(20261129)
    spheres = [{"name": "ground", "center": [0, -1000, 0], "radius": 1000, "color": [0.5, 0.5, 0.5]},
               {"name": "glass", "center": [0, 1, 0], "radius": 1, "color": [0.85, 0.9, 0.95]},
               {"name": "brown", "center": [-4, 1, 0], "radius": 1, "color": [0.4, 0.2, 0.1]},
               {"name": "metal", "center": [4, 1, 0], "radius": 1, "color": [0.7, 0.6, 0.5]}]
    big = [(0, 1, 0), (-4, 1, 0), (4, 1, 0)]

    def clear_of_big(c, r):
        return all(math.dist(c, b) > 1 + r + 0.05 for b in big)

    for centre, r in resting_centres(rng, 500):
        if clear_of_big(centre, r):
            spheres.append({"center": list(centre), "radius": r, "color": colour(rng)})
    # Pairs touching each other exactly, floating a little above the ground.
    for _ in range(40):
        k = 0.0625 * rng.randrange(1, 4)                      # radii summing to 5k
        r1 = k * rng.randrange(1, 5)
        r2 = 5 * k - r1
        x, z = round(rng.uniform(-10, 10) * 64) / 64, round(rng.uniform(-10, 10) * 64) / 64
        c1 = (x, r1 + 0.5, z)
        c2 = (x + 3 * k, r1 + 0.5, z + 4 * k)
        if clear_of_big(c1, r1) and clear_of_big(c2, r2):
            spheres.append({"center": list(c1), "radius": r1, "color": colour(rng)})
            spheres.append({"center": list(c2), "radius": r2, "color": colour(rng)})
    # Near misses of the ground: 2^-20 above or below contact.
    for _ in range(60):
        r = round(rng.uniform(0.15, 0.3) * 256) / 256
        x, z = round(rng.uniform(-11, 11) * 64) / 64, round(rng.uniform(-11, 11) * 64) / 64
        y = math.sqrt((GROUND_R + r) ** 2 - x * x - z * z) - GROUND_R + rng.choice([-1, 1]) * 2.0 ** -20
        if clear_of_big((x, y, z), r):
            spheres.append({"center": [x, y, z], "radius": r, "color": colour(rng)})

    # Twins: the same centre, the second radius a few ulps larger (its colour another), listed second.
    for x, z, r in ((2.0, 2.5, 0.5), (-2.5, 2.0, 0.4), (1.5, -2.75, 0.45), (6.5, 1.25, 0.35)):
        outer = r
        for _ in range(rng.randrange(1, 4)):
            outer = math.nextafter(outer, 1.0)
        spheres.append({"name": "twin inner", "center": [x, r, z], "radius": r, "color": [0.9, 0.15, 0.1]})
        spheres.append({"name": "twin outer", "center": [x, r, z], "radius": outer, "color": [0.1, 0.3, 0.9]})

    scene = {
        "description": "In the spirit of the cover of Ray Tracing in One Weekend: a ground sphere of radius 1000, "
                       "three spheres of radius 1 and small spheres, most resting on the ground with exact contact "
                       "(integer points of a sphere, tools/make_sphere_scene.py), pairs touching each other exactly, "
                       "and some 2^-20 above or below contact; four twins, a sphere given again with a radius a few ulps "
                       "larger. Plain doubles show the inner twin in speckles; the exact nearest hit shows the outer one.",
        "image": {"width": 600, "height": 400, "samples_per_pixel": 1, "seed": 1},
        "camera": {"eye": [13, 2, 3], "target": [0, 0, 0], "up": [0, 1, 0],
                   "perspective": {"fov_degrees": 20, "near": 0.1, "ray_start": "eye"}},
        "background": {"horizon": [1.0, 1.0, 1.0], "zenith": [0.5, 0.7, 1.0]},
        "spheres": spheres,
    }
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/spheres-cover.json"
    with open(out, "w") as f:
        json.dump(scene, f, indent=None, separators=(", ", ": "))
        f.write("\n")
    print(f"wrote {out}: {len(spheres)} spheres")


if __name__ == "__main__":
    main()
