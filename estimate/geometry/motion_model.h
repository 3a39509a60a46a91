#pragma once
// The motion models a shot segment can have, from the simplest up. The model
// decides which per-frame parameters the bundle adjustment may change:
//   static         nothing moves (pose and focal held)
//   zoom           focal only
//   rotation       rotation only, constant focal (a pan/tilt/roll on a tripod)
//   rotation+zoom  rotation and focal
//   general        rotation and translation, constant focal
//   general+zoom   rotation, translation and focal (e.g. a dolly zoom)
// Models without translation keep the camera centre *exactly* constant (the
// bundle adjustment shares one centre block), so a pan never gains spurious
// translation.

#include <string>

namespace hapcine {

enum class MotionModel { kStatic = 0, kZoom, kRotation, kRotationZoom, kGeneral, kGeneralZoom };

inline bool HasRotation(MotionModel m) {
  return m == MotionModel::kRotation || m == MotionModel::kRotationZoom ||
         m == MotionModel::kGeneral || m == MotionModel::kGeneralZoom;
}
inline bool HasTranslation(MotionModel m) {
  return m == MotionModel::kGeneral || m == MotionModel::kGeneralZoom;
}
inline bool HasZoom(MotionModel m) {
  return m == MotionModel::kZoom || m == MotionModel::kRotationZoom ||
         m == MotionModel::kGeneralZoom;
}
// True when every freedom of `b` is also a freedom of `a`.
inline bool IsAtLeastAsGeneral(MotionModel a, MotionModel b) {
  return (HasRotation(a) || !HasRotation(b)) && (HasTranslation(a) || !HasTranslation(b)) &&
         (HasZoom(a) || !HasZoom(b));
}
inline MotionModel CombineModels(bool rotation, bool translation, bool zoom) {
  if (translation) return zoom ? MotionModel::kGeneralZoom : MotionModel::kGeneral;
  if (rotation) return zoom ? MotionModel::kRotationZoom : MotionModel::kRotation;
  return zoom ? MotionModel::kZoom : MotionModel::kStatic;
}
// `m` without its translation and/or zoom (general+zoom -> rotation+zoom ...).
inline MotionModel ReducedModel(MotionModel m, bool drop_translation, bool drop_zoom) {
  return CombineModels(HasRotation(m), HasTranslation(m) && !drop_translation, HasZoom(m) && !drop_zoom);
}

// Names written in the camera path's `model` column.
inline std::string MotionModelName(MotionModel m) {
  switch (m) {
    case MotionModel::kStatic: return "static";
    case MotionModel::kZoom: return "zoom";
    case MotionModel::kRotation: return "rotation";
    case MotionModel::kRotationZoom: return "rotation+zoom";
    case MotionModel::kGeneral: return "general";
    case MotionModel::kGeneralZoom: return "general+zoom";
  }
  return "static";
}

}  // namespace hapcine
