#pragma once
// The study plan (paper, section 5.1–5.2): which clips, which haptic
// conditions, and for every participant the training block and the random
// order of the pairwise trials. A plan is made once, before the study, and
// every session and the analysis refer to it by its plan id.
//
// Clips. Each CLIP argument is either
//   * a video file `dir/<stem>.<ext>` with sibling tracks
//     `dir/<stem>.<condition>.haptic.csv` (one per condition), or
//   * a directory `dir/` holding exactly one video (mp4, mkv, avi, mov, webm,
//     m4v) and tracks `dir/<condition>.haptic.csv`.
// The clip's name is the stem (or the directory name).
//
// Pairs. Conditions whose tracks are identical (every sample within 1e-6 m,
// as the paper's Vertigo where Cinematic == None) form one group; each
// unordered pair of groups is tested in both orders. 4 distinct conditions ->
// 6 pairs x 2 = 12 trials per clip; with two identical -> 3 x 2 = 6.
// Choosing a group gives a point to every condition in it.

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "core/haptic_track.h"
#include "study/questionnaire.h"

namespace hapcine::study {

struct TrackRef {
  std::string path;  // absolute
  std::string hash;  // HashFile() of the track file
};

struct StudyClip {
  std::string name;
  std::string video;                       // absolute path
  std::string video_hash;                  // HashFile() of the video
  std::map<std::string, TrackRef> tracks;  // condition -> track
  std::vector<std::vector<std::string>>
      groups;  // conditions with identical tracks, in condition order
};

// One pairwise comparison: the clip played with `first` then with `second`
// (each a group; the track played is that of the group's first condition).
struct Trial {
  int index = 0;  // position in the participant's sequence, 0-based
  std::string clip;
  std::vector<std::string> first;
  std::vector<std::string> second;
};

struct TrainingItem {
  std::string clip;
  std::string condition;
};

struct ParticipantPlan {
  std::string id;     // "P01", "P02", ...
  int number = 0;     // 1-based
  uint64_t seed = 0;  // ParticipantSeed(plan seed, number)
  std::string training_condition;
  std::vector<TrainingItem> training;
  std::vector<Trial> trials;
};

struct StudyPlan {
  std::string plan_id;  // hash of the plan's content (everything but the id)
  uint64_t seed = 0;
  double identical_tolerance_m = 1e-6;
  std::vector<std::string> conditions;
  std::vector<StudyClip> clips;
  std::vector<ParticipantPlan> participants;
  // Asked after the last trial; empty = none (the key is then absent from the
  // file, so plans without a questionnaire keep their plan id).
  std::vector<Question> questionnaire;

  const StudyClip& Clip(const std::string& name) const;  // throws Error if absent
  // Finds "P07", or "7" as the participant number. Throws UsageError.
  const ParticipantPlan& Participant(const std::string& id) const;
};

struct PlanOptions {
  std::vector<std::string> clips;  // video files or clip directories
  int participants = 38;           // the paper had 38
  uint64_t seed = 1;               // recorded in the plan; same seed -> same plan
  std::vector<std::string> conditions = {"cinematic", "semantic", "none", "random"};
  double identical_tolerance_m = 1e-6;  // tracks closer than this everywhere are the same stimulus
  std::vector<Question> questionnaire;  // post-test questions; empty = none
  void Check() const;                   // throws UsageError
};

// Finds the tracks, hashes files, groups identical tracks, and draws every
// participant's training block and trial order. Progress lines go to `log`
// (may be null). Throws Error naming the clip on a missing/bad track.
StudyPlan MakePlan(const PlanOptions& options, std::ostream* log);

// Number of trials per participant implied by the clips' groups.
int TrialsPerParticipant(const std::vector<StudyClip>& clips);

// True if the tracks describe the same motion: same duration (within half a
// sample period) and every sample of each, interpolated in the other, within
// `tol_m` on every axis of every actuator.
bool TracksIdentical(const HapticTrack& a, const HapticTrack& b, double tol_m);

nlohmann::json PlanToJson(const StudyPlan& plan);  // includes plan_id
std::string ComputePlanId(const StudyPlan& plan);
// Parses and validates; recomputes the id and rejects a plan whose content
// does not match its id (edited by hand). Errors name `source`.
StudyPlan PlanFromJson(const nlohmann::json& j, const std::string& source);
void WritePlanFile(const StudyPlan& plan, const std::string& path);  // atomic
StudyPlan ReadPlanFile(const std::string& path);

}  // namespace hapcine::study
