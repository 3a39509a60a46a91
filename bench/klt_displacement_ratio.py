#!/usr/bin/env python3
"""How much of a rotating camera's image motion KLT measures, by frame and by
place in the picture.

For a camera that only rotates (pan, tilt, whip; any zoom), a pixel's true
motion from frame t-1 to t does not depend on depth: it is the homography
K_t R_t^T R_{t-1} K_{t-1}^-1 of the ground truth. Every consecutive pair of a
track's observations (`hapcine_track_truth ... --errors-out FILE`) is compared
with it: the KLT displacement projected on the true one, divided by the true
one's length (1 = exact, < 1 = short). The median ratio is printed per frame
near the centre (|x - W/2| < 0.2 W) and at the left/right edges (|x - W/2| >
0.3 W), where a rotation's (1 + x^2 / f^2) growth of image motion measures the
focal length: edges short of the centre read as a longer lens, and the pan or
tilt comes out that much short. Then the same ratios pooled by true speed.

  python3 bench/klt_displacement_ratio.py ERRORS.csv GT.camera.csv [FIRST LAST]

(GT.camera.csv: the file's OpenGL axes, x right, y up, z back; its header's
width= and height= give the picture size.)
"""
import collections
import csv
import math
import statistics
import sys


def read_truth(path):
    header = {}
    for line in open(path):
        if line.startswith("#") and "=" in line:
            k, v = line[1:].strip().split("=", 1)
            header[k.strip()] = v.strip()
    rows = csv.DictReader(line for line in open(path) if not line.startswith("#"))
    cams = {int(r["frame"]): ([float(r[k]) for k in ("qw", "qx", "qy", "qz")], float(r["focal_px"]))
            for r in rows}
    return cams, int(header["width"]), int(header["height"])


def rotation_matrix(q):
    w, x, y, z = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def apply(m, v, transpose=False):
    if transpose:
        return [sum(m[j][i] * v[j] for j in range(3)) for i in range(3)]
    return [sum(m[i][j] * v[j] for j in range(3)) for i in range(3)]


def true_position(cams, size, f0, f1, px):
    """Where the ray through pixel px of frame f0 lands in frame f1 (rotation only)."""
    (q0, focal0), (q1, focal1) = cams[f0], cams[f1]
    w, h = size
    ray = [(px[0] - w / 2) / focal0, -(px[1] - h / 2) / focal0, -1.0]  # pixel y down, camera y up, z back
    c = apply(rotation_matrix(q1), apply(rotation_matrix(q0), ray), transpose=True)
    return (w / 2 + focal1 * c[0] / -c[2], h / 2 - focal1 * c[1] / -c[2])


def read_steps(path):
    """Per frame t: (position at t-1, position at t) of every track seen at both."""
    seen = collections.defaultdict(dict)
    for r in csv.DictReader(open(path)):
        seen[int(r["track"])][int(r["frame"])] = (float(r["x"]), float(r["y"]))
    steps = collections.defaultdict(list)
    for track in seen.values():
        for frame, px in track.items():
            if frame - 1 in track:
                steps[frame].append((track[frame - 1], px))
    return steps


def median(v):
    return statistics.median(v) if v else float("nan")


def main():
    if len(sys.argv) not in (3, 5):
        sys.exit(__doc__)
    cams, w, h = read_truth(sys.argv[2])
    steps = read_steps(sys.argv[1])
    first, last = (int(sys.argv[3]), int(sys.argv[4])) if len(sys.argv) == 5 else (min(steps), max(steps))
    pooled = collections.defaultdict(lambda: ([], []))  # speed bin -> (centre, edge) ratios
    print("frame  true_px  centre  edge_left  edge_right  n_centre  n_edge")
    for frame in range(first, last + 1):
        if frame not in steps or frame - 1 not in cams or frame not in cams:
            continue
        centre, left, right, speeds = [], [], [], []
        for a, b in steps[frame]:
            t = true_position(cams, (w, h), frame - 1, frame, a)
            tx, ty = t[0] - a[0], t[1] - a[1]
            n2 = tx * tx + ty * ty
            speeds.append(math.sqrt(n2))
            if n2 < 1.0:  # under a pixel of motion the ratio is noise
                continue
            ratio = ((b[0] - a[0]) * tx + (b[1] - a[1]) * ty) / n2
            x = a[0] - w / 2
            (centre if abs(x) < 0.2 * w else left if x < -0.3 * w else right if x > 0.3 * w else []).append(ratio)
        speed = median(speeds)
        if speed < 1.0:
            continue
        print(f"{frame:5d}  {speed:7.1f}  {median(centre):6.4f}  {median(left):9.4f}  {median(right):10.4f}"
              f"  {len(centre):8d}  {len(left) + len(right):6d}")
        bin_px = 10 * int(speed // 10)
        pooled[bin_px][0].extend(centre)
        pooled[bin_px][1].extend(left + right)
    print("\ntrue px/frame  centre  edges  (median ratio over the frames of that speed)")
    for bin_px in sorted(pooled):
        c, e = pooled[bin_px]
        print(f"{bin_px:3d}-{bin_px + 10:<3d}        {median(c):6.4f}  {median(e):6.4f}")


if __name__ == "__main__":
    main()
