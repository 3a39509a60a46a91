#include "estimate/estimator_records.h"

namespace hapcine {
namespace {

void Renumber(const std::vector<int>& frame_of_position, const std::map<int, int>& shot_numbers,
              nlohmann::json* j) {
  if (j->is_array()) {
    for (nlohmann::json& e : *j) Renumber(frame_of_position, shot_numbers, &e);
    return;
  }
  if (!j->is_object()) return;
  for (auto it = j->begin(); it != j->end(); ++it) {
    const std::string& key = it.key();
    nlohmann::json& v = it.value();
    if (!v.is_number_integer()) {
      Renumber(frame_of_position, shot_numbers, &v);
      continue;
    }
    const int n = v.get<int>();
    if (key == "frame" || key == "first_frame" || key == "last_frame") {
      if (n >= 0 && n < static_cast<int>(frame_of_position.size())) v = frame_of_position[n];
    } else if (key == "shot") {
      if (const auto s = shot_numbers.find(n); s != shot_numbers.end()) v = s->second;
    }
  }
}

}  // namespace

void EstimatorRecords::Record(const std::string& kind, nlohmann::json fields) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (holding_)
    held_.emplace_back(kind, std::move(fields));
  else
    hapcine::Record(sink_, kind, std::move(fields));
}

void EstimatorRecords::Release(const std::vector<int>& frame_of_position,
                               const std::map<int, int>& shot_numbers) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto& [kind, fields] : held_) {
    Renumber(frame_of_position, shot_numbers, &fields);
    hapcine::Record(sink_, kind, std::move(fields));
  }
  held_.clear();
  holding_ = false;
}

std::map<int, int> ShotOfFrame(const CameraPath& path) {
  std::map<int, int> shots;
  for (const CameraFrame& f : path.frames)
    if (f.shot.has_value()) shots[f.frame] = *f.shot;
  return shots;
}

std::map<int, int> ShotNumbers(const std::map<int, int>& shot_of_frame_before,
                               const std::map<int, int>& shot_of_frame_after) {
  std::map<int, int> numbers;
  for (const auto& [frame, before] : shot_of_frame_before)
    if (const auto after = shot_of_frame_after.find(frame); after != shot_of_frame_after.end())
      numbers.emplace(before, after->second);
  return numbers;
}

}  // namespace hapcine
