#!/usr/bin/env python3
"""Development levels for MRT: random rows of three box rooms joined by doorways (the kind of
level issue 12 names), for diagnosing the runtime against a brute force at its texels
(`bouncelab probe-mrt` with a .gltf path) without touching the held-out levels of
`tools/unseen_levels.py`. Sizes, doorway places and the spot differ per seed.

Usage: python3 tools/dev_levels.py OUT_DIR [COUNT]  (writes OUT_DIR/dev_rooms_<seed>.gltf)

The shapes level designers build (corridors of any length, L- and T-shaped rooms, ceiling steps,
wall-wide doorways, pillars, a 60 m hall, two storeys with a stairwell) are written by
`bouncelab dev-levels OUT_DIR` from the fitter's own test levels, and `bouncelab probe-mrt
shape:NAME` compares MRT with a brute-force path tracer in each of their rooms.
"""

import random
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from unseen_levels import CEILING, FLOOR, WALL, Writer  # noqa: E402


def dev_rooms(seed):
    rng = random.Random(1000 + seed)
    w = Writer()
    wall, floor, ceil = w.material("wall", WALL), w.material("floor", FLOOR), w.material("ceiling", CEILING)
    t = 0.2
    h = rng.uniform(2.6, 3.2)
    depth = rng.uniform(3.5, 6.0)
    widths = [rng.uniform(3.5, 6.5) for _ in range(3)]
    xs = []
    x = 0.0
    for wd in widths:
        xs.append((x, x + wd))
        x += wd + t
    x0, x1 = -t, xs[-1][1] + t
    w.slab("floor", [x0, -t, -t], [x1, 0.0, depth + t], floor)
    w.slab("ceiling", [x0, h, -t], [x1, h + t, depth + t], ceil)
    w.slab("south", [x0, 0, -t], [x1, h, 0.0], wall)
    w.slab("north", [x0, 0, depth], [x1, h, depth + t], wall)
    w.slab("west", [x0, 0, 0.0], [0.0, h, depth], wall)
    w.slab("east", [xs[-1][1], 0, 0.0], [x1, h, depth], wall)
    door_w, door_h = rng.uniform(0.8, 1.4), rng.uniform(2.0, min(2.3, h - 0.2))
    for k in range(2):
        xa = xs[k][1]
        za = rng.uniform(0.3, depth - door_w - 0.3)
        zb = za + door_w
        w.slab(f"partition_{k}_a", [xa, 0, 0.0], [xa + t, h, za], wall)
        w.slab(f"partition_{k}_b", [xa, 0, zb], [xa + t, h, depth], wall)
        w.slab(f"lintel_{k}", [xa, door_h, za], [xa + t, h, zb], wall)
    lx = rng.uniform(0.8, widths[0] - 0.8)
    lz = rng.uniform(0.8, depth - 0.8)
    aim = [rng.uniform(-0.6, 0.6), -1.0, rng.uniform(-0.6, 0.6)]
    w.light("spot", "spot", 40.0, [lx, h - 0.3, lz], aim, cone=(0.35, 0.6))
    w.camera([xs[2][1] - 0.3, 1.6, depth - 0.3], [xs[2][0], 0.8, 1.0], 1.2, 0.05)
    return w


def main():
    import argparse

    parser = argparse.ArgumentParser(description="Write MRT development levels (rows of three rooms).")
    parser.add_argument("out", help="output folder")
    parser.add_argument("count", nargs="?", type=int, default=4, help="how many levels (default 4)")
    args = parser.parse_args()
    out, count = Path(args.out), args.count
    out.mkdir(parents=True, exist_ok=True)
    for seed in range(count):
        dev_rooms(seed).write(out / f"dev_rooms_{seed}.gltf")


if __name__ == "__main__":
    main()
