#pragma once
// The results of one benchmark run (bench/run.sh): one row per timed command
// in runs.tsv, joined with the `hapcine eval --json` report of its output.
//
// runs.tsv columns (tab-separated, one header row):
//   group tool setting clip rc wall_s user_s sys_s maxrss_kb frames eval_json note
// group: accuracy (an estimator on a synth clip), decode (the decoding floor),
// memory (peak RSS against clip length). `frames` is the number of frames of
// the clip (not of the subsample a peer looked at), so time per frame is the
// cost of one second of video / fps for every method alike.

#include <optional>
#include <string>
#include <vector>

namespace hapcine::bench {

struct EvalSummary {
  double rotation_deg = 0;        // mean over frames
  double fov_percent = 0;         // mean
  double zoom_ratio_percent = 0;  // mean
  std::optional<double> ate_percent;  // n/a when the ground truth does not move
  bool gt_static = false;
  int matched = 0, gt_frames = 0;
};

struct RunRow {
  std::string group, tool, setting, clip;
  int rc = 0;
  double wall_s = 0, user_s = 0, sys_s = 0;
  double maxrss_kb = 0;
  int frames = 0;
  std::string eval_json, note;
  std::optional<EvalSummary> eval;  // when eval_json exists and parses

  std::string Method() const { return tool + (setting.empty() ? "" : " " + setting); }
  bool Failed() const { return rc != 0 || !eval; }
  // Under 90 % of the ground-truth frames estimated.
  bool Partial() const { return eval && eval->matched < 0.9 * eval->gt_frames; }
  double MsPerFrame() const { return frames > 0 ? 1000 * wall_s / frames : 0; }
  double CpuMsPerFrame() const { return frames > 0 ? 1000 * (user_s + sys_s) / frames : 0; }
};

// Reads runs.tsv; eval_json paths are relative to the file's folder unless
// absolute. Throws hapcine::Error("<file>:<line>", reason) on a malformed row.
std::vector<RunRow> ReadRuns(const std::string& file);
EvalSummary ReadEvalSummary(const std::string& json_file);

}  // namespace hapcine::bench
