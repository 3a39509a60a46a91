#include "study/plan.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "core/atomic_file.h"
#include "core/error.h"
#include "study/hash.h"
#include "study/json_util.h"
#include "study/shuffle.h"

namespace hapcine::study {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const char* const kFormat = "hapcine-study-plan";
constexpr int kVersion = 1;

bool IsVideoExtension(std::string ext) {
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  return ext == ".mp4" || ext == ".mkv" || ext == ".avi" || ext == ".mov" || ext == ".webm" ||
         ext == ".m4v";
}

std::string ParticipantId(int number, int total) {
  const int width = std::max<int>(2, static_cast<int>(std::to_string(total).size()));
  std::string s = std::to_string(number);
  return "P" + std::string(width - s.size(), '0') + s;
}

// Resolves one CLIP argument to its video and per-condition track paths.
StudyClip LocateClip(const std::string& arg, const std::vector<std::string>& conditions) {
  StudyClip clip;
  std::error_code ec;
  const fs::path p = fs::absolute(arg, ec).lexically_normal();
  if (fs::is_directory(p, ec)) {
    clip.name = p.filename().string();
    if (clip.name.empty()) clip.name = p.parent_path().filename().string();
    std::vector<fs::path> videos;
    for (const auto& e : fs::directory_iterator(p, ec))
      if (e.is_regular_file() && IsVideoExtension(e.path().extension().string()))
        videos.push_back(e.path());
    if (videos.size() != 1)
      throw Error(arg, "a clip directory must hold exactly one video (found " +
                           std::to_string(videos.size()) + ")");
    clip.video = videos[0].string();
    for (const auto& c : conditions) clip.tracks[c].path = (p / (c + ".haptic.csv")).string();
  } else if (fs::is_regular_file(p, ec)) {
    clip.name = p.stem().string();
    clip.video = p.string();
    for (const auto& c : conditions)
      clip.tracks[c].path = (p.parent_path() / (clip.name + "." + c + ".haptic.csv")).string();
  } else {
    throw Error(arg, "no such video file or clip directory");
  }
  for (const auto& [c, t] : clip.tracks)
    if (!fs::is_regular_file(t.path, ec))
      throw Error(arg, "missing haptic track for condition '" + c + "' (expected " + t.path + ")");
  return clip;
}

}  // namespace

void PlanOptions::Check() const {
  if (clips.empty()) throw UsageError("at least one clip is needed");
  if (participants < 1 || participants > 100000)
    throw UsageError("--participants must be in 1..100000");
  if (conditions.size() < 2) throw UsageError("at least two conditions are needed");
  std::set<std::string> seen;
  for (const auto& c : conditions) {
    if (c.empty() || c.find_first_of("/\\. ,") != std::string::npos)
      throw UsageError("bad condition name '" + c + "' (no spaces, dots, commas or slashes)");
    if (!seen.insert(c).second) throw UsageError("condition '" + c + "' given twice");
  }
  if (!(identical_tolerance_m >= 0) || !std::isfinite(identical_tolerance_m))
    throw UsageError("identical-track tolerance must be >= 0");
}

const StudyClip& StudyPlan::Clip(const std::string& name) const {
  for (const auto& c : clips)
    if (c.name == name) return c;
  throw Error("plan " + plan_id, "no clip named '" + name + "'");
}

const ParticipantPlan& StudyPlan::Participant(const std::string& id) const {
  for (const auto& p : participants)
    if (p.id == id || std::to_string(p.number) == id) return p;
  throw UsageError("participant '" + id + "' is not in the plan (it has " +
                   (participants.empty()
                        ? std::string("none")
                        : participants.front().id + ".." + participants.back().id) +
                   ")");
}

bool TracksIdentical(const HapticTrack& a, const HapticTrack& b, double tol_m) {
  if (a.samples.empty() || b.samples.empty()) return a.samples.empty() && b.samples.empty();
  const double half_period = 0.5 / std::max(1e-9, std::min(a.rate_hz, b.rate_hz));
  if (std::fabs(a.samples.front().time_s - b.samples.front().time_s) > half_period ||
      std::fabs(a.samples.back().time_s - b.samples.back().time_s) > half_period)
    return false;
  auto covered = [tol_m](const HapticTrack& from, const HapticTrack& in) {
    Eigen::Vector3d pos[kNumActuators];
    size_t hint = 0;
    for (const auto& s : from.samples) {
      in.Sample(s.time_s, pos, &hint);
      for (int k = 0; k < kNumActuators; ++k)
        if ((s.pos_m[k] - pos[k]).cwiseAbs().maxCoeff() > tol_m) return false;
    }
    return true;
  };
  return covered(a, b) && covered(b, a);
}

int TrialsPerParticipant(const std::vector<StudyClip>& clips) {
  int n = 0;
  for (const auto& c : clips) {
    const int g = static_cast<int>(c.groups.size());
    n += g * (g - 1);
  }
  return n;
}

namespace {

// Conditions whose tracks are identical form one group: each condition joins
// the first earlier group whose representative track it matches.
std::vector<std::vector<std::string>> GroupIdenticalTracks(
    const std::vector<std::string>& conditions, const std::vector<HapticTrack>& tracks,
    double tolerance_m) {
  std::vector<std::vector<std::string>> groups;
  std::vector<size_t> rep;  // index of each group's representative condition
  for (size_t i = 0; i < conditions.size(); ++i) {
    size_t g = 0;
    while (g < rep.size() && !TracksIdentical(tracks[rep[g]], tracks[i], tolerance_m)) ++g;
    if (g == rep.size()) {
      rep.push_back(i);
      groups.emplace_back();
    }
    groups[g].push_back(conditions[i]);
  }
  return groups;
}

// Hashes a located clip's files and groups its conditions by identical tracks.
void HashAndGroup(const std::string& clip_path, const PlanOptions& options, std::ostream* log,
                  StudyClip* out) {
  StudyClip& clip = *out;
  clip.video_hash = HashFile(clip.video);
  std::vector<HapticTrack> tracks;
  for (const auto& c : options.conditions) {
    clip.tracks[c].hash = HashFile(clip.tracks[c].path);
    tracks.push_back(ReadHapticTrackFile(clip.tracks[c].path));
  }
  clip.groups = GroupIdenticalTracks(options.conditions, tracks, options.identical_tolerance_m);
  if (log)
    for (const auto& g : clip.groups)
      if (g.size() > 1) {
        *log << "  " << clip.name << ": identical tracks for";
        for (const auto& c : g) *log << " " << c;
        *log << " (tested once, a choice scores for all)\n";
      }
  if (clip.groups.size() < 2)
    throw Error(clip_path, "all condition tracks are identical: nothing to compare");
}

// One participant's training clips and trials, shuffled by their own seed.
ParticipantPlan PlanParticipant(int number, const PlanOptions& options,
                                const std::vector<StudyClip>& clips) {
  ParticipantPlan p;
  p.number = number;
  p.id = ParticipantId(number, options.participants);
  p.seed = ParticipantSeed(options.seed, number);
  StudyRng rng(p.seed);
  // Training (section 5.2): every clip once, with one condition drawn at
  // random for this participant, in random order.
  p.training_condition = options.conditions[rng.Below(options.conditions.size())];
  for (const auto& c : clips) p.training.push_back({c.name, p.training_condition});
  rng.Shuffle(p.training);
  // Trials: every ordered pair of distinct groups (a pair and its inverse).
  for (const auto& c : clips)
    for (size_t i = 0; i < c.groups.size(); ++i)
      for (size_t j = 0; j < c.groups.size(); ++j)
        if (i != j) p.trials.push_back({0, c.name, c.groups[i], c.groups[j]});
  rng.Shuffle(p.trials);
  for (size_t k = 0; k < p.trials.size(); ++k) p.trials[k].index = static_cast<int>(k);
  return p;
}

}  // namespace

StudyPlan MakePlan(const PlanOptions& options, std::ostream* log) {
  options.Check();
  StudyPlan plan;
  plan.seed = options.seed;
  plan.conditions = options.conditions;
  plan.identical_tolerance_m = options.identical_tolerance_m;
  std::set<std::string> names;
  for (size_t ci = 0; ci < options.clips.size(); ++ci) {
    StudyClip clip = LocateClip(options.clips[ci], options.conditions);
    if (!names.insert(clip.name).second)
      throw Error(options.clips[ci], "two clips are named '" + clip.name + "'");
    if (log)
      *log << "[" << ci + 1 << "/" << options.clips.size() << "] " << clip.name << ": hashing and "
           << "comparing tracks\n";
    HashAndGroup(options.clips[ci], options, log, &clip);
    plan.clips.push_back(std::move(clip));
  }
  for (int number = 1; number <= options.participants; ++number)
    plan.participants.push_back(PlanParticipant(number, options, plan.clips));
  plan.questionnaire = options.questionnaire;
  plan.plan_id = ComputePlanId(plan);
  return plan;
}

namespace {

json PlanContentToJson(const StudyPlan& plan) {
  json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["seed"] = plan.seed;
  j["identical_tolerance_m"] = plan.identical_tolerance_m;
  j["conditions"] = plan.conditions;
  j["clips"] = json::array();
  for (const auto& c : plan.clips) {
    json jc;
    jc["name"] = c.name;
    jc["video"] = c.video;
    jc["video_hash"] = c.video_hash;
    jc["tracks"] = json::object();
    for (const auto& [cond, t] : c.tracks)
      jc["tracks"][cond] = {{"path", t.path}, {"hash", t.hash}};
    jc["groups"] = c.groups;
    j["clips"].push_back(jc);
  }
  j["participants"] = json::array();
  for (const auto& p : plan.participants) {
    json jp;
    jp["id"] = p.id;
    jp["number"] = p.number;
    jp["seed"] = p.seed;
    jp["training_condition"] = p.training_condition;
    jp["training"] = json::array();
    for (const auto& t : p.training)
      jp["training"].push_back({{"clip", t.clip}, {"condition", t.condition}});
    jp["trials"] = json::array();
    for (const auto& t : p.trials)
      jp["trials"].push_back(
          {{"index", t.index}, {"clip", t.clip}, {"first", t.first}, {"second", t.second}});
    j["participants"].push_back(jp);
  }
  if (!plan.questionnaire.empty()) j["questionnaire"] = QuestionnaireToJson(plan.questionnaire);
  return j;
}

}  // namespace

std::string ComputePlanId(const StudyPlan& plan) {
  return HashString(PlanContentToJson(plan).dump());
}

json PlanToJson(const StudyPlan& plan) {
  json j = PlanContentToJson(plan);
  j["plan_id"] = plan.plan_id;
  return j;
}

namespace {

// Whether `group` is one of the clip's groups.
bool IsGroupOf(const StudyClip& clip, const std::vector<std::string>& group) {
  return std::find(clip.groups.begin(), clip.groups.end(), group) != clip.groups.end();
}

// The conditions and each clip's groups: every condition named once, in
// exactly one group of every clip, at least two groups to compare.
void ValidateClips(const StudyPlan& plan, const std::string& src) {
  const std::set<std::string> conds(plan.conditions.begin(), plan.conditions.end());
  if (conds.size() != plan.conditions.size() || conds.size() < 2 || conds.count(""))
    throw Error(src, "conditions must be at least two distinct names");
  if (!(plan.identical_tolerance_m >= 0)) throw Error(src, "identical_tolerance_m must be >= 0");
  if (plan.clips.empty()) throw Error(src, "no clips");
  std::set<std::string> names;
  for (const StudyClip& c : plan.clips) {
    const std::string where = "clip '" + c.name + "'";
    if (!names.insert(c.name).second) throw Error(src, where + " listed twice");
    std::set<std::string> covered;
    for (const auto& g : c.groups) {
      if (g.empty()) throw Error(src, where + ": empty group");
      for (const auto& cond : g)
        if (!covered.insert(cond).second)
          throw Error(src, where + ": condition '" + cond + "' in two groups");
    }
    if (covered.size() != conds.size())
      throw Error(src, where + ": groups do not cover every condition");
    if (c.groups.size() < 2) throw Error(src, where + ": fewer than two groups to compare");
  }
}

// One trial: a known clip, two different groups of that clip.
void ValidateTrial(const StudyPlan& plan, const Trial& t, const std::string& src,
                   const std::string& where) {
  const auto clip = std::find_if(plan.clips.begin(), plan.clips.end(),
                                 [&](const StudyClip& c) { return c.name == t.clip; });
  if (clip == plan.clips.end()) throw Error(src, where + ": unknown clip '" + t.clip + "'");
  for (const auto* group : {&t.first, &t.second}) {
    const char* which = group == &t.first ? "first" : "second";
    if (group->empty()) throw Error(src, where + ": " + which + " group is empty");
    for (const auto& cond : *group)
      if (!clip->tracks.count(cond))
        throw Error(src, where + ": unknown condition '" + cond + "' in " + which + " group");
    if (!IsGroupOf(*clip, *group))
      throw Error(src, where + ": " + which + " group is not a group of clip '" + t.clip + "'");
  }
  if (t.first == t.second) throw Error(src, where + ": both groups are the same");
}

// Everything a session relies on, so that a plan edited by hand fails here
// with its file and trial instead of crashing `study run`.
void ValidatePlan(const StudyPlan& plan, const std::string& src) {
  ValidateClips(plan, src);
  const std::set<std::string> conds(plan.conditions.begin(), plan.conditions.end());
  std::set<std::string> ids;
  for (const ParticipantPlan& p : plan.participants) {
    const std::string who = "participant " + p.id;
    if (p.id.empty() || !ids.insert(p.id).second)
      throw Error(src, who + ": empty or repeated participant id");
    if (!conds.count(p.training_condition))
      throw Error(src, who + ": unknown training condition '" + p.training_condition + "'");
    for (const TrainingItem& t : p.training) {
      if (!conds.count(t.condition))
        throw Error(src, who + " training: unknown condition '" + t.condition + "'");
      if (std::none_of(plan.clips.begin(), plan.clips.end(),
                       [&](const StudyClip& c) { return c.name == t.clip; }))
        throw Error(src, who + " training: unknown clip '" + t.clip + "'");
    }
    for (const Trial& t : p.trials)
      ValidateTrial(plan, t, src, who + " trial " + std::to_string(t.index));
  }
  if (plan.participants.empty()) throw Error(src, "no participants");
}

}  // namespace

StudyPlan PlanFromJson(const json& j, const std::string& src) {
  if (!j.is_object() || !j.contains("format") || j["format"] != kFormat)
    throw Error(src,
                "not a hapcine study plan (format field is not '" + std::string(kFormat) + "')");
  if (IntField(j, "version", src, "plan") != kVersion)
    throw Error(src, "unsupported plan version " + j["version"].dump());
  StudyPlan plan;
  plan.plan_id = StringField(j, "plan_id", src, "plan");
  plan.seed = Uint64Field(j, "seed", src, "plan");
  plan.identical_tolerance_m = NumberField(j, "identical_tolerance_m", src, "plan");
  plan.conditions = StringArray(ArrayField(j, "conditions", src, "plan"), src, "conditions");
  const std::set<std::string> conds(plan.conditions.begin(), plan.conditions.end());
  for (const auto& jc : ArrayField(j, "clips", src, "plan")) {
    StudyClip c;
    c.name = StringField(jc, "name", src, "clip");
    const std::string where = "clip '" + c.name + "'";
    c.video = StringField(jc, "video", src, where);
    c.video_hash = StringField(jc, "video_hash", src, where);
    const json& jt = Field(jc, "tracks", src, where);
    for (const auto& cond : plan.conditions) {
      const json& t = Field(jt, cond, src, where + " tracks");
      c.tracks[cond] = {StringField(t, "path", src, where), StringField(t, "hash", src, where)};
    }
    for (const auto& g : ArrayField(jc, "groups", src, where)) {
      c.groups.push_back(StringArray(g, src, where + " groups"));
      for (const auto& cond : c.groups.back())
        if (!conds.count(cond)) throw Error(src, where + ": unknown condition '" + cond + "'");
    }
    plan.clips.push_back(std::move(c));
  }
  for (const auto& jp : ArrayField(j, "participants", src, "plan")) {
    ParticipantPlan p;
    p.id = StringField(jp, "id", src, "participant");
    const std::string where = "participant " + p.id;
    p.number = IntField(jp, "number", src, where);
    p.seed = Uint64Field(jp, "seed", src, where);
    p.training_condition = StringField(jp, "training_condition", src, where);
    for (const auto& t : ArrayField(jp, "training", src, where))
      p.training.push_back(
          {StringField(t, "clip", src, where), StringField(t, "condition", src, where)});
    for (const auto& t : ArrayField(jp, "trials", src, where)) {
      Trial tr;
      tr.index = IntField(t, "index", src, where);
      tr.clip = StringField(t, "clip", src, where);
      tr.first = StringArray(Field(t, "first", src, where), src, where);
      tr.second = StringArray(Field(t, "second", src, where), src, where);
      if (tr.index != static_cast<int>(p.trials.size()))
        throw Error(src, where + ": trials out of order");
      p.trials.push_back(std::move(tr));
    }
    plan.participants.push_back(std::move(p));
  }
  if (j.contains("questionnaire"))
    plan.questionnaire = QuestionnaireFromJson(j["questionnaire"], src);
  ValidatePlan(plan, src);
  const std::string id = ComputePlanId(plan);
  if (id != plan.plan_id)
    throw Error(src, "plan content does not match its plan_id (" + plan.plan_id + " recorded, " +
                         id + " computed): the plan was edited");
  return plan;
}

void WritePlanFile(const StudyPlan& plan, const std::string& path) {
  AtomicFile out(path);
  out.stream() << PlanToJson(plan).dump(1) << "\n";
  out.Commit();
}

StudyPlan ReadPlanFile(const std::string& path) { return PlanFromJson(ReadJsonFile(path), path); }

}  // namespace hapcine::study
