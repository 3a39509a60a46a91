#!/usr/bin/env python3
"""Summarise platform tracks (*.platform.csv, docs/formats.md) as a Markdown
table: per file, the DOF that moves most (relative to the largest value of
any DOF), its peak and when, its value at the end, the largest move back
against the direction of the peak before the peak's camera move ends
(counter-motion, --move-end seconds), and the limiter counts.

  python3 scripts/platform_summary.py --move-end 6 *.platform.csv
"""
import argparse
import csv
import sys

COLS = ["x_m", "y_m", "z_m", "pitch_deg", "yaw_deg", "roll_deg"]
NAMES = ["sway", "heave", "surge", "pitch", "yaw", "roll"]


def read(path):
    meta, rows = {}, []
    with open(path) as f:
        lines = [l for l in f]
    body = []
    for l in lines:
        if l.startswith("#"):
            k, _, v = l[1:].strip().partition("=")
            meta[k] = v
        else:
            body.append(l)
    for r in csv.DictReader(body):
        rows.append(r)
    return meta, rows


def summarise(path, move_end):
    meta, rows = read(path)
    t = [float(r["time_s"]) for r in rows]
    # mm and deg side by side: pick the DOF with the largest peak in its own unit x scale
    best = None
    for c, n in zip(COLS, NAMES):
        scale = 1000.0 if c.endswith("_m") else 1.0
        v = [float(r[c]) * scale for r in rows]
        peak_i = max(range(len(v)), key=lambda i: abs(v[i]))
        if best is None or abs(v[peak_i]) > abs(best[2][best[1]]):
            best = (n, peak_i, v, "mm" if scale > 1 else "deg")
    name, peak_i, v, unit = best
    sign = 1 if v[peak_i] >= 0 else -1
    run, counter = -1e9, 0.0
    for ti, vi in zip(t, v):
        if ti > move_end:
            break
        run = max(run, sign * vi)
        counter = max(counter, run - sign * vi)
    return (path, name, v[peak_i], unit, t[peak_i], v[-1], counter,
            meta.get("clamped_samples", "?"), meta.get("stroke_limited_samples", "?"))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("tracks", nargs="+")
    ap.add_argument("--move-end", type=float, default=6.0,
                    help="time the camera move ends, s (Table 1 clips: 6)")
    a = ap.parse_args()
    print("| track | main DOF | peak | at (s) | end | counter-motion before move end | limited | stroke-limited |")
    print("|---|---|---|---|---|---|---|---|")
    for p in a.tracks:
        path, n, pk, u, tp, end, cm, cl, sl = summarise(p, a.move_end)
        print(f"| {path} | {n} | {pk:+.1f} {u} | {tp:.2f} | {end:+.1f} {u} | {cm:.2f} {u} | {cl} | {sl} |")


if __name__ == "__main__":
    sys.exit(main())
