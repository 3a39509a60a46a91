#!/usr/bin/env python3
"""The Blender and Nuke .chan exports, run in Blender itself (headless).

Usage: camera_exports_blender_test.py HAPCINE_EXE

Writes a two-shot camera path (a pan right with a zoom and travel, then a
one-frame shot), exports it with `hapcine convert --to-blender` and
`--to-nuke-chan`, runs the script in `blender --background`, imports the
.chan with Blender's own Nuke importer (rotation order ZXY, Y up -> Z up),
and reads every camera's matrix_world and lens back per frame. Both must
match the path mapped independently here (docs/formats.md, "Camera
exports"). The script runs twice, as a user re-running it would. Exits 77
(ctest: skipped) when `blender` is not installed.
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

SKIPPED = 77
WIDTH, HEIGHT, FPS = 1920, 1080, 25
SENSOR_WIDTH_MM = 36.0

READBACK = r'''
import json, sys
import addon_utils, bpy
out_json, chan_file = sys.argv[sys.argv.index('--') + 1:][:2]
scene = bpy.context.scene

def sample(obj, frames):
    rows = {}
    for f in frames:
        scene.frame_set(f)
        ev = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
        rows[f] = {'matrix': [list(r) for r in ev.matrix_world],
                   'euler_z': ev.rotation_euler.z, 'lens': ev.data.lens}
    return rows

result = {'fps': scene.render.fps, 'fps_base': scene.render.fps_base,
          'resolution': [scene.render.resolution_x, scene.render.resolution_y],
          'range': [scene.frame_start, scene.frame_end],
          'scene_camera': scene.camera.name,
          'markers': sorted([m.frame, m.name, m.camera.name] for m in scene.timeline_markers),
          'cameras': {}}
for obj in bpy.data.objects:
    if obj.name.startswith('hapcine_shot'):
        result.setdefault('objects', []).append(obj.name)
        keys = obj.animation_data.action.fcurves.find('location', index=0).keyframe_points
        result['cameras'][obj.name] = sample(obj, [int(k.co[0]) for k in keys])

addon_utils.enable('io_anim_nuke_chan', default_set=True)
data = bpy.data.cameras.new('chan')
data.sensor_fit = 'HORIZONTAL'
chan_camera = bpy.data.objects.new('chan', data)
scene.collection.objects.link(chan_camera)
bpy.context.view_layer.objects.active = chan_camera
bpy.ops.import_scene.import_chan(filepath=chan_file, rotation_order='ZXY', z_up=True,
                                 sensor_width=36.0, sensor_height=36.0 * 1080 / 1920)
frames = [int(line.split()[0]) for line in open(chan_file) if line.strip()]
result['chan'] = sample(chan_camera, frames)
with open(out_json, 'w') as f:
    json.dump(result, f)
'''


def quat_mul(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw)


def axis_quat(axis, deg):
    h = math.radians(deg) / 2
    q = [math.cos(h), 0.0, 0.0, 0.0]
    q[1 + axis] = math.sin(h)
    return tuple(q)


def quat_matrix(q):
    w, x, y, z = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def path_frames():
    """(frame, shot, centre, (pan, tilt, roll), hfov): a pan right with a zoom in
    and some travel, then a one-frame shot."""
    frames = []
    for i in range(6):
        frames.append((i, 0, (0.1 * i, 0.02 * i, -0.05 * i), (-4.0 * i, 2.0, 1.0), 50 - 2 * i))
    frames.append((6, 1, (0.0, 0.0, 0.0), (0.0, -10.0, 0.0), 70.0))
    return frames


def write_path(file):
    with open(file, 'w') as out:
        out.write('# width=%d\n# height=%d\n# fps=%d\n' % (WIDTH, HEIGHT, FPS))
        out.write('frame,time_s,x,y,z,qw,qx,qy,qz,fov_deg,shot\n')
        for frame, shot, c, (pan, tilt, roll), fov in path_frames():
            # world_from_cam = R_y(pan) R_x(tilt) R_z(roll) (docs/formats.md)
            q = quat_mul(quat_mul(axis_quat(1, pan), axis_quat(0, tilt)), axis_quat(2, roll))
            out.write('%d,%.6f,%r,%r,%r,%r,%r,%r,%r,%r,%d\n' %
                      ((frame, frame / FPS) + tuple(c) + tuple(q) + (fov, shot)))


def expected_blender(frame):
    """matrix_world (3x3, location) and lens, with Blender's Z-up world = ours
    turned +90 degrees about X: (x, y, z) -> (x, -z, y)."""
    _, _, c, (pan, tilt, roll), fov = frame
    q = quat_mul(quat_mul(axis_quat(1, pan), axis_quat(0, tilt)), axis_quat(2, roll))
    r = quat_matrix(q)
    rot = [r[0], [-v for v in r[2]], r[1]]
    loc = [c[0], -c[2], c[1]]
    lens = SENSOR_WIDTH_MM / (2 * math.tan(math.radians(fov) / 2))
    return rot, loc, lens


def check_close(what, got, want, tol, failures):
    if abs(got - want) > tol:
        failures.append('%s: got %.9g, expected %.9g' % (what, got, want))


def check_camera(name, sampled, frames, failures):
    """The sampled Blender frames of one camera against the path's frames."""
    if sorted(int(f) for f in sampled) != [f[0] + 1 for f in frames]:
        failures.append('%s: keyed frames %s' % (name, sorted(sampled)))
        return
    for frame in frames:
        got = sampled[str(frame[0] + 1)]
        rot, loc, lens = expected_blender(frame)
        for r in range(3):
            for c in range(3):
                check_close('%s frame %d R[%d][%d]' % (name, frame[0], r, c),
                            got['matrix'][r][c], rot[r][c], 1e-5, failures)
            check_close('%s frame %d location[%d]' % (name, frame[0], r),
                        got['matrix'][r][3], loc[r], 1e-5, failures)
        check_close('%s frame %d lens' % (name, frame[0]), got['lens'], lens, 1e-3, failures)


def check_result(result, failures):
    frames = path_frames()
    shot0 = [f for f in frames if f[1] == 0]
    check_close('fps', result['fps'] / result['fps_base'], FPS, 1e-9, failures)
    if result['resolution'] != [WIDTH, HEIGHT] or result['range'] != [1, 7]:
        failures.append('resolution %s, range %s' % (result['resolution'], result['range']))
    want_markers = [[1, 'shot000', 'hapcine_shot000'], [7, 'shot001', 'hapcine_shot001']]
    if result['markers'] != want_markers or result['scene_camera'] != 'hapcine_shot000':
        failures.append('markers %s, scene camera %s' % (result['markers'], result['scene_camera']))
    if sorted(result.get('objects', [])) != ['hapcine_shot000', 'hapcine_shot001']:
        failures.append('camera objects %s' % result.get('objects'))
    check_camera('hapcine_shot000', result['cameras'].get('hapcine_shot000', {}), shot0, failures)
    check_camera('hapcine_shot001', result['cameras'].get('hapcine_shot001', {}),
                 [f for f in frames if f[1] == 1], failures)
    # A pan right in Blender: the camera turns clockwise seen from above (Euler
    # Z falls) and the view (-Z column) swings towards +X.
    cam = result['cameras'].get('hapcine_shot000', {})
    eulers = [cam[k]['euler_z'] for k in sorted(cam, key=int)]
    if not all(b < a for a, b in zip(eulers, eulers[1:])):
        failures.append('pan right: Euler Z does not fall: %s' % eulers)
    if cam and not -cam['6']['matrix'][0][2] > 0.3:
        failures.append('pan right: view does not turn to +X')
    # The .chan, through Blender's own Nuke importer, lands on the same cameras.
    check_camera('chan', result['chan'], shot0, failures)


def run(cmd):
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        sys.stderr.write(done.stdout)
        raise SystemExit('failed (%d): %s' % (done.returncode, ' '.join(cmd)))
    return done.stdout


def main():
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    blender = shutil.which('blender')
    if blender is None:
        print('skipped: `blender` is not installed (Debian: apt-get install -y blender)')
        return SKIPPED
    with tempfile.TemporaryDirectory() as tmp:
        path_csv = os.path.join(tmp, 'film.camera.csv')
        write_path(path_csv)
        script = os.path.join(tmp, 'film.py')
        run([sys.argv[1], 'convert', path_csv, '--to-blender', script])
        run([sys.argv[1], 'convert', path_csv, '--to-nuke-chan', os.path.join(tmp, 'film.chan')])
        readback = os.path.join(tmp, 'readback.py')
        with open(readback, 'w') as f:
            f.write(READBACK)
        out_json = os.path.join(tmp, 'result.json')
        run([blender, '--background', '--factory-startup', '--python-exit-code', '1',
             # Twice: a second run replaces the cameras and markers.
             '--python', script, '--python', script, '--python', readback, '--', out_json,
             os.path.join(tmp, 'film.shot000.chan')])
        with open(out_json) as f:
            result = json.load(f)
    failures = []
    check_result(result, failures)
    for line in failures:
        print('FAIL ' + line)
    if not failures:
        print('ok: Blender cameras and the imported .chan match the camera path')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
