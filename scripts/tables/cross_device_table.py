#!/usr/bin/env python3
"""cross_device_table.py A B [NAME_A NAME_B] - how far one device's images are from another's: two
folders written by scripts/cross_device_renders.sh on two devices (same commit). For each scene and
pipeline, B against A: the largest difference of any pixel's R, G or B, the largest share of the
per-pixel bound 1e-2 |a| + 1e-4 peak (the visibility test's bound for untextured scenes, peak = the
largest value of A's reference image), and the RMSE over the peak; then, on each device, visibility
against that device's reference with either surface (reference_ray: surface=ray), in the same units; then the angle in radians between the shading
normals (the debug view `normal`) of naive and visibility on each device and of visibility between
the devices, over the pixels where all four show a surface. Needs numpy; the images are read by
scripts/exr_read.py."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from exr_read import read_exr  # noqa: E402

SCENES = ["spheres", "desk_lamp", "mug", "snowman"]
PIPES = ["naive", "visibility", "reference", "reference_ray"]


def read(folder, scene, pipe):
    path = os.path.join(folder, "%s_%s.exr" % (scene, pipe))
    try:
        return read_exr(path, ("R", "G", "B")).astype(np.float64)
    except (OSError, ValueError) as e:
        raise SystemExit("cannot read %s: %s" % (path, e))


def compare(x, ref, peak):
    d = np.abs(x - ref)
    usage = (d / (1e-2 * np.abs(ref) + 1e-4 * peak)).max()
    return "%.3g | %.3g | %.2g" % (d.max(), usage, np.sqrt((d ** 2).mean()) / peak)


def main(argv):
    if len(argv) not in (3, 5):
        sys.stderr.write(__doc__)
        return 2
    a, b = argv[1], argv[2]
    na, nb = (argv[3], argv[4]) if len(argv) == 5 else ("A", "B")
    print("| scene | pipeline | %s vs %s: max | bound usage | RMSE / peak |" % (nb, na))
    print("|---|---|---:|---:|---:|")
    for s in SCENES:
        peak = read(a, s, "reference").max()
        for p in PIPES:
            print("| %s | %s | %s |" % (s, p, compare(read(b, s, p), read(a, s, p), peak)))
    print()
    print("| scene | visibility vs reference on %s: max | bound usage | RMSE / peak | on %s: max | bound usage | RMSE / peak "
          "| vs reference_ray on %s: max | bound usage | RMSE / peak | on %s: max | bound usage | RMSE / peak |"
          % (na, nb, na, nb))
    print("|---|" + "---:|" * 12)
    for s in SCENES:
        peak = read(a, s, "reference").max()
        cols = [compare(read(f, s, "visibility"), read(f, s, r), peak) for r in ("reference", "reference_ray")
                for f in (a, b)]
        print("| %s | %s |" % (s, " | ".join(cols)))
    print()
    print("| scene | pixels | naive vs visibility normal on %s: median | p99 | max | on %s: median | p99 | max | "
          "visibility's normal, %s vs %s: median | p99 | max |" % (na, nb, nb, na))
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for s in SCENES:
        nrm = {(f, p): read_normal(f, s, p) for f in (a, b) for p in ("naive", "visibility")}
        mask = np.logical_and.reduce([m for _, m in nrm.values()])
        cols = []
        for x, y in (((a, "naive"), (a, "visibility")), ((b, "naive"), (b, "visibility")),
                     ((b, "visibility"), (a, "visibility"))):
            ang = np.arccos(np.clip((nrm[x][0] * nrm[y][0]).sum(axis=2), -1, 1))[mask]
            cols.append("%.1e | %.1e | %.1e" % (np.median(ang), np.percentile(ang, 99), ang.max()))
        print("| %s | %d | %s |" % (s, mask.sum(), " | ".join(cols)))
    return 0


def read_normal(folder, scene, pipe):
    """the unit shading normal of the debug view (n/2 + 1/2) and where the view drew a surface"""
    raw = read(folder, scene, pipe + "_normal")
    n = raw * 2 - 1
    return n / np.maximum(np.linalg.norm(n, axis=2, keepdims=True), 1e-9), raw.max(axis=2) > 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
