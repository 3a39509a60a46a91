#include "datasets/camera_exports.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>

#include "core/csv.h"
#include "core/error.h"
#include "core/rotation.h"
#include "datasets/tum_format.h"

namespace hapcine {
namespace {

// OpenGL camera axes (+Y up, -Z forward) <-> OpenCV/KITTI ones (+Y down,
// +Z forward): a half turn about the camera X axis; its own inverse.
const Eigen::Matrix3d kGlFromCv = Eigen::Vector3d(1, -1, -1).asDiagonal();

// Our Y-up world to Blender's Z-up world: +90 degrees about X.
Eigen::Matrix3d BlenderFromOurWorld() {
  return Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
}

// Reads every non-blank line as exactly `count` numbers.
std::vector<std::vector<double>> ReadNumberRows(std::istream& in, const std::string& source,
                                                size_t count, const char* layout) {
  std::vector<std::vector<double>> rows;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string where = source + ":" + std::to_string(line_no);
    std::vector<double> v = ParseNumberFields(line, where);
    if (v.empty()) continue;
    if (v.size() != count) {
      throw Error(where, "expected " + std::to_string(count) + " values (" + layout + "), got " +
                             std::to_string(v.size()));
    }
    rows.push_back(std::move(v));
  }
  if (rows.empty()) throw Error(source, "no rows");
  return rows;
}

// `angle` plus the multiple of 360 that brings it nearest to `previous`.
double UnwrapDeg(double angle, double previous) {
  return angle - 360.0 * std::round((angle - previous) / 360.0);
}

// A Python string literal of `text` (UTF-8 kept; quotes, backslashes and
// control bytes escaped), so that any file name stays on one line.
std::string PythonStringLiteral(const std::string& text) {
  std::string out = "'";
  for (unsigned char ch : text) {
    if (ch == '\\' || ch == '\'') {
      out += '\\';
      out += static_cast<char>(ch);
    } else if (ch < 0x20 || ch == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", ch);
      out += buf;
    } else {
      out += static_cast<char>(ch);
    }
  }
  return out + "'";
}

void CheckFrame(const CameraFrame& f) {
  const std::string bad = ValidateCameraFrame(f);
  if (!bad.empty()) throw Error("camera path", "frame " + std::to_string(f.frame) + ": " + bad);
}

}  // namespace

std::vector<ShotFrames> SelectShots(const CameraPath& path, std::optional<int> only_shot,
                                    const std::string& source) {
  if (path.frames.empty()) throw Error(source, "the camera path has no frames");
  std::vector<ShotFrames> shots;
  std::map<int, size_t> index_of_shot;
  for (const CameraFrame& f : path.frames) {
    const int shot = f.shot.value_or(0);
    if (only_shot && shot != *only_shot) continue;
    auto it = index_of_shot.find(shot);
    if (it == index_of_shot.end()) {
      it = index_of_shot.emplace(shot, shots.size()).first;
      shots.push_back(ShotFrames{shot, {}});
    }
    shots[it->second].frames.push_back(f);
  }
  if (shots.empty()) {
    const int first = path.frames.front().shot.value_or(0);
    const int last = path.frames.back().shot.value_or(0);
    throw Error(source, "no frame of shot " + std::to_string(*only_shot) + " (shots " +
                            std::to_string(first) + " to " + std::to_string(last) + ")");
  }
  return shots;
}

std::string PerShotFileName(const std::string& file, int shot) {
  char tag[32];
  std::snprintf(tag, sizeof tag, ".shot%03d", shot);
  const size_t slash = file.find_last_of('/');
  const size_t dot = file.find_last_of('.');
  const bool has_extension =
      dot != std::string::npos && dot > 0 && (slash == std::string::npos || dot > slash + 1);
  if (!has_extension) return file + tag;
  return file.substr(0, dot) + tag + file.substr(dot);
}

double ExportFps(const CameraPath& path) {
  if (path.fps() > 0) return path.fps();
  std::vector<double> steps;
  for (size_t i = 1; i < path.frames.size(); ++i) {
    steps.push_back(path.frames[i].time_s - path.frames[i - 1].time_s);
  }
  if (steps.empty()) return 24;
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  const double step = steps[steps.size() / 2];
  return step > 0 ? 1.0 / step : 24;
}

BlenderPose BlenderPoseFromFrame(const CameraFrame& frame) {
  const Eigen::Matrix3d blender_from_ours = BlenderFromOurWorld();
  BlenderPose pose;
  pose.location = blender_from_ours * frame.center;
  pose.rotation = CanonicalQuaternion(
      Eigen::Quaterniond(blender_from_ours * frame.world_from_cam.normalized().toRotationMatrix()));
  return pose;
}

double LensMmFromFovDeg(double fov_deg, double sensor_width_mm) {
  return sensor_width_mm / (2 * std::tan(DegToRad(fov_deg) / 2));
}

std::vector<NukeChanRow> NukeChanRows(const ShotFrames& shot, double height_over_width,
                                      int start_frame) {
  std::vector<NukeChanRow> rows;
  for (const CameraFrame& f : shot.frames) {
    CheckFrame(f);
    // Nuke's ZXY order applies Z, then X, then Y: R = R_y(ry) R_x(rx) R_z(rz),
    // exactly our pan/tilt/roll split, so rotate = (tilt, pan, roll).
    const PanTiltRoll angles = PanTiltRollFromQuaternion(f.world_from_cam.normalized());
    NukeChanRow row;
    row.frame = f.frame + start_frame;
    row.translate = f.center;
    row.rotate_deg = {angles.tilt_deg, angles.pan_deg, angles.roll_deg};
    if (!rows.empty()) {
      for (int i = 0; i < 3; ++i) {
        row.rotate_deg[i] = UnwrapDeg(row.rotate_deg[i], rows.back().rotate_deg[i]);
      }
    }
    row.vertical_fov_deg =
        RadToDeg(2 * std::atan(std::tan(DegToRad(f.fov_deg) / 2) * height_over_width));
    rows.push_back(row);
  }
  return rows;
}

void WriteNukeChan(const std::vector<NukeChanRow>& rows, std::ostream& out) {
  for (const NukeChanRow& r : rows) {
    out << r.frame;
    for (int i = 0; i < 3; ++i) out << '\t' << FormatDouble(r.translate[i]);
    for (int i = 0; i < 3; ++i) out << '\t' << FormatDouble(r.rotate_deg[i]);
    out << '\t' << FormatDouble(r.vertical_fov_deg) << '\n';
  }
}

std::vector<NukeChanRow> ReadNukeChan(std::istream& in, const std::string& source) {
  std::vector<NukeChanRow> rows;
  for (const auto& v : ReadNumberRows(in, source, 8, "frame tx ty tz rx ry rz vfov")) {
    NukeChanRow r;
    r.frame = static_cast<int>(std::lround(v[0]));
    r.translate = {v[1], v[2], v[3]};
    r.rotate_deg = {v[4], v[5], v[6]};
    r.vertical_fov_deg = v[7];
    rows.push_back(r);
  }
  return rows;
}

Eigen::Quaterniond NukeRotation(const Eigen::Vector3d& rotate_deg) {
  return QuaternionFromPanTiltRoll({rotate_deg.y(), rotate_deg.x(), rotate_deg.z()});
}

std::vector<KittiPose> KittiPoses(const ShotFrames& shot) {
  if (shot.frames.empty()) throw Error("camera path", "shot " + std::to_string(shot.shot) + " has no frames");
  const CameraFrame& first = shot.frames.front();
  CheckFrame(first);
  // KITTI's world is the first camera's frame (CV axes): the pose of frame i
  // is F R_0^T R_i F and F R_0^T (c_i - c_0), with F the axis flip.
  const Eigen::Matrix3d first_from_world =
      kGlFromCv * first.world_from_cam.normalized().toRotationMatrix().transpose();
  std::vector<KittiPose> poses;
  for (const CameraFrame& f : shot.frames) {
    CheckFrame(f);
    KittiPose pose;
    pose.leftCols<3>() =
        first_from_world * f.world_from_cam.normalized().toRotationMatrix() * kGlFromCv;
    pose.col(3) = first_from_world * (f.center - first.center);
    poses.push_back(pose);
  }
  return poses;
}

void WriteKittiPoses(const std::vector<KittiPose>& poses, std::ostream& out) {
  for (const KittiPose& pose : poses) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) {
        // An exact zero stays "0" (not "-0") for tools that compare text.
        out << (r + c ? " " : "") << FormatDouble(pose(r, c) == 0 ? 0.0 : pose(r, c));
      }
    }
    out << '\n';
  }
}

std::vector<KittiPose> ReadKittiPoses(std::istream& in, const std::string& source) {
  std::vector<KittiPose> poses;
  for (const auto& v : ReadNumberRows(in, source, 12, "3x4 row-major")) {
    KittiPose pose;
    for (int i = 0; i < 12; ++i) pose(i / 4, i % 4) = v[i];
    poses.push_back(pose);
  }
  return poses;
}

// ---- Blender script

namespace {

const char* const kBlenderScriptBody = R"PY(

def set_frame_rate(scene, fps):
    # Blender stores a rate as an integer over a base: 23.976 = 24 / 1.001.
    whole = max(1, round(fps))
    scene.render.fps = whole
    scene.render.fps_base = whole / fps


def add_keys(action, data_path, index, frames, values, group):
    curve = action.fcurves.new(data_path, index=index, action_group=group)
    curve.keyframe_points.add(len(frames))
    co = [0.0] * (2 * len(frames))
    co[0::2] = frames
    co[1::2] = values
    curve.keyframe_points.foreach_set('co', co)
    for key in curve.keyframe_points:
        key.interpolation = 'LINEAR'  # one key per frame: no overshoot between them
    curve.update()


def parse_rows(text):
    rows = []
    for line in text.split('\n'):
        v = line.split()
        if v:
            rows.append((int(v[0]),) + tuple(float(x) for x in v[1:]))
    return rows


def make_camera(scene, shot, rows):
    name = 'hapcine_shot%03d' % shot
    old = bpy.data.objects.get(name)
    if old is not None:
        bpy.data.objects.remove(old, do_unlink=True)
    data = bpy.data.cameras.new(name)
    data.sensor_fit = 'HORIZONTAL'
    data.sensor_width = SENSOR_WIDTH_MM
    if WIDTH > 0 and HEIGHT > 0:
        data.sensor_height = SENSOR_WIDTH_MM * HEIGHT / WIDTH
    camera = bpy.data.objects.new(name, data)
    scene.collection.objects.link(camera)
    camera.rotation_mode = 'XYZ'
    frames = [row[0] for row in rows]
    eulers = []
    for row in rows:
        q = Quaternion(row[4:8])
        # Each Euler triple nearest the previous one: no 360-degree flips.
        eulers.append(q.to_euler('XYZ', eulers[-1]) if eulers else q.to_euler('XYZ'))
    camera.location = rows[0][1:4]
    camera.rotation_euler = eulers[0]
    data.lens = rows[0][8]
    action = bpy.data.actions.new(name)
    camera.animation_data_create().action = action
    for i in range(3):
        add_keys(action, 'location', i, frames, [row[1 + i] for row in rows], 'Object Transforms')
        add_keys(action, 'rotation_euler', i, frames, [e[i] for e in eulers], 'Object Transforms')
    lens_action = bpy.data.actions.new(name + '_lens')
    data.animation_data_create().action = lens_action
    add_keys(lens_action, 'lens', 0, frames, [row[8] for row in rows], 'Lens')
    return camera


def main():
    scene = bpy.context.scene
    set_frame_rate(scene, FPS)
    if WIDTH > 0 and HEIGHT > 0:
        scene.render.resolution_x = WIDTH
        scene.render.resolution_y = HEIGHT
        scene.render.resolution_percentage = 100
    first_frames = []
    last_frame = None
    for shot, text in SHOTS:
        rows = parse_rows(text)
        camera = make_camera(scene, shot, rows)
        # A marker bound to a camera makes it the scene camera from that frame on.
        old = scene.timeline_markers.get('shot%03d' % shot)
        if old is not None:
            scene.timeline_markers.remove(old)
        marker = scene.timeline_markers.new('shot%03d' % shot, frame=rows[0][0])
        marker.camera = camera
        if not first_frames:
            scene.camera = camera
        first_frames.append(rows[0][0])
        last_frame = rows[-1][0] if last_frame is None else max(last_frame, rows[-1][0])
    scene.frame_start = min(first_frames)
    scene.frame_end = last_frame
    scene.frame_set(scene.frame_start)
    args = sys.argv[sys.argv.index('--') + 1:] if '--' in sys.argv else []
    if '--save' in args:
        bpy.ops.wm.save_as_mainfile(filepath=args[args.index('--save') + 1])


main()
)PY";

}  // namespace

void WriteBlenderScript(const CameraPath& path, const std::vector<ShotFrames>& shots,
                        const BlenderExportOptions& options, std::ostream& out) {
  if (shots.empty()) throw Error("camera path", "no shots to export");
  out << "# A hapcine camera path as Blender cameras, one per shot "
         "(written by `hapcine convert --to-blender`).\n"
         "# Run: blender --background --python THIS.py -- --save OUT.blend\n"
         "#   or open it in Blender's Text Editor and press Run Script.\n"
         "# Conventions: hapcine docs/formats.md, \"Blender script\".\n"
         "import sys\n\nimport bpy\nfrom mathutils import Quaternion\n\n";
  out << "SOURCE = " << PythonStringLiteral(options.source) << "\n";
  out << "FPS = " << FormatDouble(ExportFps(path)) << "\n";
  out << "WIDTH = " << path.width() << "\nHEIGHT = " << path.height() << "\n";
  out << "SENSOR_WIDTH_MM = " << FormatDouble(options.sensor_width_mm) << "\n";
  // Rows as text, parsed when the script runs: a literal of tuples would
  // make Python build a syntax tree of every number (gigabytes for a film).
  out << "# Per shot: (shot, rows), one row per frame: frame x y z qw qx qy qz lens_mm, with\n"
         "# location and rotation (matrix_world) in Blender's Z-up world, lens in mm for\n"
         "# SENSOR_WIDTH_MM.\n"
         "SHOTS = [\n";
  for (const ShotFrames& shot : shots) {
    out << "(" << shot.shot << ", '''\n";
    for (const CameraFrame& f : shot.frames) {
      CheckFrame(f);
      const BlenderPose pose = BlenderPoseFromFrame(f);
      const Eigen::Quaterniond& q = pose.rotation;
      out << f.frame + options.start_frame;
      for (double v : {pose.location.x(), pose.location.y(), pose.location.z(), q.w(), q.x(),
                       q.y(), q.z(), LensMmFromFovDeg(f.fov_deg, options.sensor_width_mm)}) {
        out << ' ' << FormatDouble(v);
      }
      out << '\n';
    }
    out << "'''),\n";
  }
  out << "]\n" << kBlenderScriptBody;
}

}  // namespace hapcine
