#include "core/camera_path.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/error.h"
#include "core/header_value.h"
#include "core/input_file.h"
#include "core/line_count.h"
#include "core/rotation.h"

namespace hapcine {
namespace {

const std::vector<std::string> kRequired = {"frame", "time_s", "x",  "y",  "z",
                                            "qw",    "qx",     "qy", "qz", "fov_deg"};

int MetaInt(const std::map<std::string, std::string>& m, const char* key) {
  auto it = m.find(key);
  return it == m.end() ? 0 : std::atoi(it->second.c_str());
}

}  // namespace

int CameraPath::width() const { return MetaInt(metadata, "width"); }
int CameraPath::height() const { return MetaInt(metadata, "height"); }
double CameraPath::fps() const {
  auto it = metadata.find("fps");
  return it == metadata.end() ? 0 : std::atof(it->second.c_str());
}

std::string ValidateCameraFrame(const CameraFrame& f) {
  if (!f.center.allFinite()) return "non-finite camera centre";
  if (!f.world_from_cam.coeffs().allFinite()) return "non-finite quaternion";
  if (std::abs(f.world_from_cam.norm() - 1.0) > 1e-3) {
    return "quaternion is not unit length (|q| = " +
           FormatDouble(f.world_from_cam.norm()) + ")";
  }
  if (!std::isfinite(f.time_s)) return "non-finite time";
  if (!(f.fov_deg > 0 && f.fov_deg < 180)) {
    return "fov_deg " + FormatDouble(f.fov_deg) + " outside (0, 180)";
  }
  if (f.focal_px && !(std::isfinite(*f.focal_px) && *f.focal_px > 0)) {
    return "focal_px must be positive and finite";
  }
  if (f.confidence && !(*f.confidence >= 0 && *f.confidence <= 1)) {
    return "confidence outside [0, 1]";
  }
  if (f.frame < 0) return "negative frame index";
  return "";
}

CameraPath ReadCameraPath(std::istream& in, const std::string& source_name) {
  // The shortest row: ten one-digit fields.
  const size_t rows = CountLinesAhead(in, 19);
  CsvReader csv(in, source_name);
  csv.ReadPreamble();
  csv.RequireLeadingColumns(kRequired);
  const int c_focal = csv.Column("focal_px");
  const int c_shot = csv.Column("shot");
  const int c_model = csv.Column("model");
  const int c_conf = csv.Column("confidence");
  const int c_source = csv.Column("source_frame");

  CameraPath path;
  path.metadata = csv.metadata();
  TryReserve(&path.frames, rows);
  if (c_source >= 0) TryReserve(&path.source_frames, rows);
  RecentName models;
  std::vector<std::string> f;
  while (csv.NextRow(&f)) {
    CameraFrame fr;
    fr.frame = csv.Int(f, 0, "frame");
    fr.time_s = csv.Double(f, 1, "time_s");
    fr.center = {csv.Double(f, 2, "x"), csv.Double(f, 3, "y"), csv.Double(f, 4, "z")};
    fr.world_from_cam = Eigen::Quaterniond(csv.Double(f, 5, "qw"), csv.Double(f, 6, "qx"),
                                           csv.Double(f, 7, "qy"), csv.Double(f, 8, "qz"));
    fr.fov_deg = csv.Double(f, 9, "fov_deg");
    if (c_focal >= 0 && !f[c_focal].empty()) fr.focal_px = csv.Double(f, c_focal, "focal_px");
    if (c_shot >= 0 && !f[c_shot].empty()) fr.shot = csv.Int(f, c_shot, "shot");
    if (c_model >= 0 && !f[c_model].empty() && !models.Make(f[c_model], &fr.model)) {
      csv.Fail("too many distinct values in column 'model'");
    }
    if (c_conf >= 0 && !f[c_conf].empty()) fr.confidence = csv.Double(f, c_conf, "confidence");
    if (c_source >= 0)
      path.source_frames.push_back(f[c_source].empty() ? OptionalInt()
                                                       : OptionalInt(csv.Int(f, c_source, "source_frame")));
    const std::string bad = ValidateCameraFrame(fr);
    if (!bad.empty()) csv.Fail(bad);
    if (!path.frames.empty()) {
      if (fr.time_s <= path.frames.back().time_s) csv.Fail("time_s is not increasing");
      if (fr.frame <= path.frames.back().frame) csv.Fail("frame is not increasing");
    }
    path.frames.push_back(std::move(fr));
  }
  if (path.frames.empty()) csv.Fail("no data rows");
  return path;
}

CameraPath ReadCameraPathFile(const std::string& file) {
  InputFile in(file);
  return ReadCameraPath(in.stream(), file);
}

void WriteCameraPath(const CameraPath& path, std::ostream& out) {
  if (!path.source_frames.empty() && path.source_frames.size() != path.frames.size()) {
    throw Error("camera path", std::to_string(path.source_frames.size()) + " source frame numbers for " +
                                   std::to_string(path.frames.size()) + " frames");
  }
  bool any_focal = false, any_shot = false, any_model = false, any_conf = false, any_source = false;
  for (const OptionalInt& n : path.source_frames) any_source |= n.has_value();
  for (const auto& fr : path.frames) {
    const std::string bad = ValidateCameraFrame(fr);
    if (!bad.empty()) {
      throw Error("camera path", "frame " + std::to_string(fr.frame) + ": " + bad);
    }
    any_focal |= fr.focal_px.has_value();
    any_shot |= fr.shot.has_value();
    any_model |= fr.model.has_value();
    any_conf |= fr.confidence.has_value();
  }
  for (const auto& [key, value] : path.metadata) WriteHeaderLine(out, key, value);
  out << "frame,time_s,x,y,z,qw,qx,qy,qz,fov_deg";
  if (any_focal) out << ",focal_px";
  out << ",pan_deg,tilt_deg,roll_deg";
  if (any_shot) out << ",shot";
  if (any_model) out << ",model";
  if (any_conf) out << ",confidence";
  if (any_source) out << ",source_frame";
  out << "\n";
  for (size_t i = 0; i < path.frames.size(); ++i) {
    const CameraFrame& fr = path.frames[i];
    const Eigen::Quaterniond q = fr.world_from_cam;  // unit, qw >= 0 as stored
    const PanTiltRoll a = PanTiltRollFromQuaternion(q);
    out << fr.frame << ',' << FormatFixed(fr.time_s, 6) << ',' << FormatDouble(fr.center.x())
        << ',' << FormatDouble(fr.center.y()) << ',' << FormatDouble(fr.center.z()) << ','
        << FormatDouble(q.w()) << ',' << FormatDouble(q.x()) << ',' << FormatDouble(q.y())
        << ',' << FormatDouble(q.z()) << ',' << FormatFloat(fr.fov_deg.raw());
    if (any_focal) out << ',' << (fr.focal_px ? FormatFloat((*fr.focal_px).raw()) : "");
    out << ',' << FormatFixed(a.pan_deg, 6) << ',' << FormatFixed(a.tilt_deg, 6) << ','
        << FormatFixed(a.roll_deg, 6);
    if (any_shot) out << ',' << (fr.shot ? std::to_string(*fr.shot) : "");
    if (any_model) out << ',' << fr.model.value_or("");
    if (any_conf) out << ',' << (fr.confidence ? FormatFixed(*fr.confidence, 4) : "");
    if (any_source) out << ',' << (path.source_frames[i] ? std::to_string(*path.source_frames[i]) : "");
    out << '\n';
  }
}

void WriteCameraPathFile(const CameraPath& path, const std::string& file) {
  AtomicFile out(file);
  WriteCameraPath(path, out.stream());
  out.Commit();
}

}  // namespace hapcine
