#!/usr/bin/env python3
"""cross_device_table.py A B [NAME_A NAME_B] - how far one device's images are from another's: two
folders written by scripts/cross_device_renders.sh on two devices (same commit). For each scene and
pipeline, B against A: the largest difference of any pixel's R, G or B, the largest share of the
per-pixel bound 1e-2 |a| + 1e-4 peak (the visibility test's bound for untextured scenes, peak = the
largest value of A's reference image), and the RMSE over the peak; then, on each device, visibility
against that device's reference, in the same units. Needs numpy and OpenCV with OpenEXR
(Debian: python3-opencv); OPENCV_IO_ENABLE_OPENEXR is set here."""
import os
import sys

os.environ["OPENCV_IO_ENABLE_OPENEXR"] = "1"
import cv2  # noqa: E402
import numpy as np  # noqa: E402

SCENES = ["spheres", "desk_lamp", "mug", "snowman"]
PIPES = ["naive", "visibility", "reference"]


def read(folder, scene, pipe):
    path = os.path.join(folder, "%s_%s.exr" % (scene, pipe))
    img = cv2.imread(path, cv2.IMREAD_UNCHANGED)
    if img is None:
        raise SystemExit("cannot read %s" % path)
    return img[..., :3].astype(np.float64)


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
    print("| scene | visibility vs the reference on %s: max | bound usage | RMSE / peak | on %s: max | bound usage | RMSE / peak |"
          % (na, nb))
    print("|---|---:|---:|---:|---:|---:|---:|")
    for s in SCENES:
        peak = read(a, s, "reference").max()
        cols = [compare(read(f, s, "visibility"), read(f, s, "reference"), peak) for f in (a, b)]
        print("| %s | %s | %s |" % (s, cols[0], cols[1]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
