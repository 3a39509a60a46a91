#!/usr/bin/env python3
"""Writes a long synthetic camera path (*.camera.csv) for the memory benchmark
(bench/memory.sh): a film of SECONDS at FPS, a new shot every 12 s, slow pans,
tilts, dollies and zooms, all columns as `hapcine estimate` writes them
(--minimal: only the ten required columns, with short numbers, the smallest
rows a reader meets).

  python3 bench/long_camera_path.py SECONDS FPS OUT.camera.csv [--minimal]
"""
import math
import sys


def main():
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    seconds, fps, out = float(sys.argv[1]), float(sys.argv[2]), sys.argv[3]
    minimal = len(sys.argv) == 5 and sys.argv[4] == "--minimal"
    n = int(round(seconds * fps))
    models = ["rotation", "general", "rotation+zoom", "static"]
    with open(out, "w", buffering=1 << 20) as f:
        f.write("# width=1920\n# height=1080\n# fps=%g\n# source=long film.mp4\n" % fps)
        if minimal:
            f.write("frame,time_s,x,y,z,qw,qx,qy,qz,fov_deg\n")
            for i in range(n):
                f.write("%d,%.3f,0,0,%.4f,1,0,0,0,60\n" % (i, i / fps, -0.001 * (i % 1000)))
            return
        f.write("frame,time_s,x,y,z,qw,qx,qy,qz,fov_deg,focal_px,pan_deg,tilt_deg,roll_deg,"
                "shot,model,confidence\n")
        shot_frames = int(12 * fps)
        for i in range(n):
            shot, j = divmod(i, shot_frames)
            u = j / fps
            pan = 0.5 * u * (1 if shot % 2 else -1)
            tilt = 3 * math.sin(0.2 * u)
            x, z = 0.02 * u, -0.01 * u * (shot % 3)
            fov = 50 + 5 * math.sin(0.1 * u) if shot % 4 == 2 else 50
            hp, ht = math.radians(pan) / 2, math.radians(tilt) / 2
            qw, qx = math.cos(hp) * math.cos(ht), math.cos(hp) * math.sin(ht)
            qy, qz = math.sin(hp) * math.cos(ht), -math.sin(hp) * math.sin(ht)
            focal = 960 / math.tan(math.radians(fov) / 2)
            f.write("%d,%.6f,%.17g,0,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.6f,%.6f,0.000000,"
                    "%d,%s,0.9%03d\n" % (i, i / fps, x, z, qw, qx, qy, qz, fov, focal, pan, tilt,
                                         shot, models[shot % 4], j % 1000))


if __name__ == "__main__":
    main()
