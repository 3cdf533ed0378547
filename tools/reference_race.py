#!/usr/bin/env python3
"""Time to equal error: Bounce Lab's CPU path tracer against Mitsuba 3 on the same machine.

For each scene, Mitsuba renders a converged image (the truth, cached in the work folder), then
renders at each of --mitsuba-spp; Bounce Lab's `render --mode reference` renders a ladder of
sample counts. Every render is a whole process, timed from start to exit, run one after another
(never side by side), so start-up, scene loading and BVH builds count for both. Each image's
FLIP against the truth comes from `bouncelab compare --exposure-auto` (the reference's mean at
0.18, as docs/QUALITY.md judges). For each Mitsuba render, the time Bounce Lab needs for the
same FLIP is read off its ladder (log-log interpolation between the two rungs that bracket it;
the cheapest rung's time if it already reaches it; "> ladder" when no rung does), and the ratio of the two times is printed: <= 1 means Bounce
Lab reaches Mitsuba's error in no more time.

    python3 tools/reference_race.py [--bouncelab target/release/bouncelab] [--work /tmp/race]
        [--scenes cornell,rooms,clutter] [--mitsuba-spp 64,128,256] [--ladder 32,45,64,...]
        [--variant llvm_ad_rgb] [--rr-depth 5] [--sampler independent] [--truth-spp 8192]

Both tracers render 64 bounces (Bounce Lab's default `max_bounces`; Mitsuba's max_depth 65).
Mitsuba runs its llvm variant (vectorised; needs LLVM >= 16, see tools/mitsuba_render.py) with
its own default Russian roulette (from depth 5) unless told otherwise; Bounce Lab its defaults.
Needs `pip install mitsuba numpy`. A validation tool, not part of the product or CI.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SCENES = {
    "cornell": ("assets/cornell_box.gltf", 512, 512),
    "rooms": ("assets/suite/rooms.gltf", 480, 270),
    "clutter": ("assets/suite/clutter.gltf", 480, 270),
}
MAX_BOUNCES = 64


def timed(cmd):
    """Runs `cmd` to completion; its wall-clock seconds (exits on failure, printing its output)."""
    t0 = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True)
    dt = time.perf_counter() - t0
    if r.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed:\n{r.stdout}{r.stderr}")
    return dt


def mitsuba(a, gltf, w, h, spp, out, seed=0):
    cmd = [sys.executable, os.path.join(HERE, "mitsuba_render.py"), gltf, "--out", out, "--width", str(w),
           "--height", str(h), "--spp", str(spp), "--max-bounces", str(MAX_BOUNCES), "--seed", str(seed),
           "--variant", a.variant, "--rr-depth", str(a.rr_depth), "--sampler", a.sampler]
    return timed(cmd)


def bouncelab(a, gltf, w, h, spp, out):
    cmd = [a.bouncelab, "render", gltf, "--mode", "reference", "--spp", str(spp), "--width", str(w),
           "--height", str(h), "--max-bounces", str(MAX_BOUNCES), "--out", out]
    return timed(cmd)


def flip(a, image, truth):
    r = subprocess.run([a.bouncelab, "compare", image, truth, "--exposure-auto"], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"compare {image} failed:\n{r.stderr}")
    return json.loads(r.stdout.strip().splitlines()[-1])["flip"]


def time_for(ladder, target):
    """Seconds at which the ladder's FLIP falls to `target` (log-log between bracketing rungs);
    the cheapest rung if it already reaches it (then an upper bound)."""
    if ladder and ladder[0][1] <= target:
        return ladder[0][0]
    for (t0, f0), (t1, f1) in zip(ladder, ladder[1:]):
        if f0 >= target >= f1 and f0 > f1:
            s = (math.log(f0) - math.log(target)) / (math.log(f0) - math.log(f1))
            return math.exp(math.log(t0) + s * (math.log(t1) - math.log(t0)))
    return None


def race(a, name):
    rel, w, h = SCENES[name]
    gltf = os.path.join(ROOT, rel)
    truth = os.path.join(a.work, f"{name}.{w}x{h}.rr{a.rr_depth}.{a.sampler}.truth.{a.truth_spp}.exr")
    if not os.path.exists(truth):
        dt = mitsuba(a, gltf, w, h, a.truth_spp, truth, seed=1234)
        print(f"{name}: truth, Mitsuba {a.truth_spp} spp, {dt:.1f} s", flush=True)
    ours = []
    for spp in a.ladder:
        out = os.path.join(a.work, f"{name}.bl.{spp}.exr")
        dt = bouncelab(a, gltf, w, h, spp, out)
        f = flip(a, out, truth)
        ours.append((dt, f))
        print(f"{name}: bouncelab {spp:5d} spp {dt:7.2f} s  FLIP {f:.4f}", flush=True)
    rows = []
    for spp in a.mitsuba_spp:
        out = os.path.join(a.work, f"{name}.mi.{spp}.exr")
        mitsuba(a, gltf, w, h, spp, out)  # warms Dr.Jit's kernel cache: the timed run below is warm
        dt = mitsuba(a, gltf, w, h, spp, out)
        f = flip(a, out, truth)
        ours_t = time_for(ours, f)
        ratio = f"{ours_t / dt:.2f}" if ours_t else "> ladder"
        ours_s = f"{ours_t:.2f} s" if ours_t else "-"
        print(f"{name}: mitsuba {spp:5d} spp {dt:7.2f} s  FLIP {f:.4f}  bouncelab at equal FLIP {ours_s}"
              f"  ratio {ratio}", flush=True)
        rows.append({"scene": name, "mitsuba_spp": spp, "mitsuba_s": dt, "flip": f, "bouncelab_s": ours_t})
    return {"scene": name, "size": [w, h], "ladder": [{"s": t, "flip": f} for t, f in ours], "rows": rows}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bouncelab", default=os.path.join(ROOT, "target/release/bouncelab"))
    ap.add_argument("--work", default="/tmp/race")
    ap.add_argument("--scenes", default="cornell,rooms,clutter")
    ap.add_argument("--mitsuba-spp", default="64,128,256")
    ap.add_argument("--ladder", default="32,45,64,90,128,181,256,362,512")
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--rr-depth", type=int, default=5)
    ap.add_argument("--sampler", default="independent")
    ap.add_argument("--truth-spp", type=int, default=8192)
    ap.add_argument("--json", help="also write the figures here")
    a = ap.parse_args()
    a.mitsuba_spp = [int(s) for s in a.mitsuba_spp.split(",")]
    a.ladder = [int(s) for s in a.ladder.split(",")]
    os.makedirs(a.work, exist_ok=True)
    results = [race(a, name) for name in a.scenes.split(",")]
    if a.json:
        with open(a.json, "w") as f:
            json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
