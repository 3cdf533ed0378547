#!/usr/bin/env python3
"""Print simple statistics of linear EXR images (validation helper, not product/CI code).

Used to compare Bounce Lab renders against the Mitsuba 3 reference produced by
tools/mitsuba_render.py.

Usage: python3 tools/exr_stats.py A.exr [B.exr]
Prints width, height, mean RGB and mean luminance (Rec.709: 0.2126, 0.7152, 0.0722)
of A; with B also the ratio of mean luminances A/B and the RGB RMSE between A and B.
"""
import sys
import numpy as np
import mitsuba as mi

mi.set_variant("scalar_rgb")
LUM = np.array([0.2126, 0.7152, 0.0722])


def load(path):
    img = np.array(mi.Bitmap(path), dtype=np.float64)
    if img.ndim == 2:
        img = img[:, :, None]
    return np.repeat(img, 3, axis=2) if img.shape[2] == 1 else img[:, :, :3]  # drop alpha


def stats(name, img):
    rgb = img.reshape(-1, 3).mean(axis=0)
    lum = float(rgb @ LUM)
    print(f"{name}: {img.shape[1]}x{img.shape[0]}  mean RGB = ({rgb[0]:.6f}, {rgb[1]:.6f}, {rgb[2]:.6f})"
          f"  mean luminance = {lum:.6f}")
    return lum


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    a = load(sys.argv[1])
    la = stats(sys.argv[1], a)
    if len(sys.argv) == 3:
        b = load(sys.argv[2])
        lb = stats(sys.argv[2], b)
        print(f"luminance ratio A/B = {la / lb:.6f}")
        if a.shape == b.shape:
            print(f"RMSE = {np.sqrt(np.mean((a - b) ** 2)):.6f}")
        else:
            print(f"RMSE: n/a (size mismatch {a.shape} vs {b.shape})")


if __name__ == "__main__":
    main()
