#!/usr/bin/env python3
"""Where a camera path's rotation error accumulates: drift or jumps.

Both paths are compared frame by frame (matched by frame index, rotations
relative to each path's first frame, no other alignment). Per row every STEP
frames:
  world error    the axis-angle vector (deg) of R_est R_gt^-1 in the first
                 camera's axes (the file's OpenGL axes: x right, y up, z back):
                 a slow drift grows steadily about one axis;
  step error     the axis-angle vector (deg) of the error of the relative
                 rotation from this row's frame to the next row's, in that
                 frame's camera axes: a jump at a window hand-over shows as
                 one large step;
  true step      the true rotation over those frames (deg).

  python3 bench/rotation_drift.py GT.camera.csv EST.camera.csv [STEP]
"""
import csv
import math
import sys


def read_rotations(path):
    rows = csv.DictReader(line for line in open(path) if not line.startswith("#"))
    return {int(r["frame"]): [float(r[k]) for k in ("qw", "qx", "qy", "qz")] for r in rows}


def mul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return [w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2]


def inverse(q):
    return [q[0], -q[1], -q[2], -q[3]]


def rotation_vector_deg(q):
    if q[0] < 0:
        q = [-v for v in q]
    s = math.sqrt(q[1] ** 2 + q[2] ** 2 + q[3] ** 2)
    if s < 1e-12:
        return [0.0, 0.0, 0.0]
    angle = math.degrees(2 * math.atan2(s, q[0]))
    return [angle * v / s for v in q[1:]]


def norm(v):
    return math.sqrt(sum(x * x for x in v))


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    gt, est = read_rotations(sys.argv[1]), read_rotations(sys.argv[2])
    step = int(sys.argv[3]) if len(sys.argv) == 4 else 10
    frames = sorted(set(gt) & set(est))
    if len(frames) < 2 or step < 1:
        sys.exit("rotation_drift: fewer than two frames in common (or STEP < 1)")
    g0, e0 = inverse(gt[frames[0]]), inverse(est[frames[0]])
    rel_gt = {f: mul(g0, gt[f]) for f in frames}
    rel_est = {f: mul(e0, est[f]) for f in frames}
    print("frame | world error x y z (deg) | norm | step error x y z (deg) to frame | true step (deg)")
    rows = frames[::step]
    for i, f in enumerate(rows):
        world = rotation_vector_deg(mul(rel_est[f], inverse(rel_gt[f])))
        line = "%5d | %6.2f %6.2f %6.2f | %5.2f" % (f, *world, norm(world))
        if i + 1 < len(rows):
            n = rows[i + 1]
            step_gt = mul(inverse(rel_gt[f]), rel_gt[n])
            step_est = mul(inverse(rel_est[f]), rel_est[n])
            err = rotation_vector_deg(mul(step_est, inverse(step_gt)))
            line += " | %6.2f %6.2f %6.2f to %d | %5.1f" % (*err, n, norm(rotation_vector_deg(step_gt)))
        print(line)


if __name__ == "__main__":
    main()
