// Turns one benchmark run (runs.tsv + the eval reports, bench/run.sh) into
// the markdown of docs/benchmarks.md's generated part and its PNG figures.
//
//   hapcine_bench_report --runs OUT/runs.tsv --md OUT/generated.md
//       --figures OUT/fig [--figure-link benchmarks] [--loop OUT/loop.txt]
//       [--meta OUT/meta.txt]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_results.h"
#include "bench/peer_video.h"
#include "bench/scatter_plot.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/statistics.h"

namespace {

using hapcine::Median;  // of the finite values, NaN (n/a) when none
using hapcine::bench::RunRow;

const std::set<std::string> kTable1 = {"crane_shot", "dutch_angle", "arcing", "traveling",
                                       "tilting",    "zoom_in",     "vertigo"};
// Clips whose focal length changes (zoom-ratio error means something there).
const std::set<std::string> kZoomClips = {"zoom_in", "vertigo", "telephoto_zoom_pan", "dolly_zoom_parallax"};

std::string Fmt(double v, int digits = 3) {
  if (!std::isfinite(v)) return "–";
  if (std::fabs(v) < 1e-9) return "0";  // e.g. 2.8e-14: the prior FOV equal to the truth
  char buf[32];
  if (v != 0 && std::fabs(v) < 0.001)
    std::snprintf(buf, sizeof(buf), "%.1e", v);
  else
    std::snprintf(buf, sizeof(buf), "%.*g", digits, v);
  return buf;
}

bool RotationOnly(const std::string& tool) { return tool.rfind("opencv", 0) == 0; }
bool IsHapcine(const std::string& tool) { return tool == "hapcine"; }
bool IsDefault(const RunRow& r) { return IsHapcine(r.tool) && r.setting.find("default") != std::string::npos; }

struct Table {
  std::vector<std::string> methods, clips;
  std::map<std::pair<std::string, std::string>, const RunRow*> cell;  // (method, clip)
};

Table BuildTable(const std::vector<RunRow>& rows) {
  Table t;
  for (const auto& r : rows) {
    if (r.group != "accuracy") continue;
    if (std::find(t.methods.begin(), t.methods.end(), r.Method()) == t.methods.end())
      t.methods.push_back(r.Method());
    if (std::find(t.clips.begin(), t.clips.end(), r.clip) == t.clips.end()) t.clips.push_back(r.clip);
    t.cell[{r.Method(), r.clip}] = &r;
  }
  // hapcine's settings first, fastest first, then the peers in run order.
  auto median_ms = [&](const std::string& meth) {
    std::vector<double> ms;
    for (const auto& [key, r] : t.cell)
      if (key.first == meth) ms.push_back(r->MsPerFrame());
    return Median(ms);
  };
  std::stable_sort(t.methods.begin(), t.methods.end(), [&](const std::string& a, const std::string& b) {
    const bool ha = a.rfind("hapcine", 0) == 0, hb = b.rfind("hapcine", 0) == 0;
    if (ha != hb) return ha;
    return ha && median_ms(a) < median_ms(b);
  });
  // Table 1 first, then the hard cases, each in run order.
  std::stable_sort(t.clips.begin(), t.clips.end(),
                   [](const std::string& a, const std::string& b) { return kTable1.count(a) > kTable1.count(b); });
  return t;
}

// A metric of one run; NaN when not applicable.
using Metric = double (*)(const RunRow&);
double Rot(const RunRow& r) { return r.eval->rotation_deg; }
double Fov(const RunRow& r) { return r.eval->fov_percent; }
double Zoom(const RunRow& r) { return r.eval->zoom_ratio_percent; }
double Ate(const RunRow& r) {
  if (RotationOnly(r.tool) || !r.eval->ate_percent) return NAN;
  return *r.eval->ate_percent;
}
double Ms(const RunRow& r) { return r.MsPerFrame(); }

std::string Cell(const RunRow* r, Metric m, bool needs_eval = true) {
  if (!r) return "";
  if (needs_eval && r->Failed()) return "fail";
  if (!needs_eval && r->rc != 0) return "fail (" + Fmt(r->MsPerFrame()) + ")";
  std::string s = Fmt(m(*r));
  if (r->Partial()) s += " †";
  if (RotationOnly(r->tool) && r->eval && !r->eval->gt_static && needs_eval) s += " °";
  return s;
}

void PerClipTable(std::ostream& md, const Table& t, const std::string& title, Metric m, bool needs_eval = true) {
  md << "\n**" << title << "**\n\n| clip |";
  for (const auto& meth : t.methods) md << " " << meth << " |";
  md << "\n|---|";
  for (size_t i = 0; i < t.methods.size(); ++i) md << "---|";
  md << "\n";
  for (const auto& clip : t.clips) {
    md << "| " << clip << (kTable1.count(clip) ? "" : " (hard)") << " |";
    for (const auto& meth : t.methods) {
      auto it = t.cell.find({meth, clip});
      md << " " << Cell(it == t.cell.end() ? nullptr : it->second, m, needs_eval) << " |";
    }
    md << "\n";
  }
}

struct MethodStats {
  int clips = 0, failed = 0, partial = 0;
  double ms = NAN, cpu_ms = NAN, rot = NAN, fov = NAN, zoom = NAN, ate = NAN, rss_mb = NAN;
};

// Over `only` when given, else over every clip.
MethodStats Stats(const Table& t, const std::string& meth, const std::set<std::string>* only = nullptr) {
  MethodStats s;
  std::vector<double> ms, cpu, rot, fov, zoom, ate, rss;
  for (const auto& clip : t.clips) {
    if (only && !only->count(clip)) continue;
    auto it = t.cell.find({meth, clip});
    if (it == t.cell.end()) continue;
    const RunRow& r = *it->second;
    ++s.clips;
    ms.push_back(r.MsPerFrame());
    cpu.push_back(r.CpuMsPerFrame());
    rss.push_back(r.maxrss_kb / 1024);
    if (r.Failed()) { ++s.failed; continue; }
    if (r.Partial()) ++s.partial;
    rot.push_back(Rot(r));
    fov.push_back(Fov(r));
    if (kZoomClips.count(clip)) zoom.push_back(Zoom(r));
    ate.push_back(Ate(r));
  }
  s.ms = Median(ms);
  s.cpu_ms = Median(cpu);
  s.rot = Median(rot);
  s.fov = Median(fov);
  s.zoom = Median(zoom);
  s.ate = Median(ate);
  s.rss_mb = Median(rss);
  return s;
}

// Clips every hapcine setting ran (the sweep).
std::set<std::string> SweepClips(const Table& t) {
  std::set<std::string> common(t.clips.begin(), t.clips.end());
  for (const auto& meth : t.methods)
    if (meth.rfind("hapcine", 0) == 0)
      for (const auto& clip : t.clips)
        if (!t.cell.count({meth, clip})) common.erase(clip);
  return common;
}

void SummaryTable(std::ostream& md, const Table& t, const std::set<std::string>* only) {
  md << "\n| method | clips | failed | partial † | wall ms/frame | CPU ms/frame | rotation err (deg) | "
        "FOV err (%) | zoom-ratio err (%, zoom clips) | ATE (% of path) | peak RSS (MB) |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& meth : t.methods) {
    const MethodStats s = Stats(t, meth, only);
    if (s.clips == 0) continue;
    md << "| " << meth << " | " << s.clips << " | " << s.failed << " | " << s.partial << " | " << Fmt(s.ms) << " | "
       << Fmt(s.cpu_ms) << " | " << Fmt(s.rot) << " | " << Fmt(s.fov) << " | " << Fmt(s.zoom) << " | " << Fmt(s.ate)
       << " | " << Fmt(s.rss_mb) << " |\n";
  }
}

// "Where a peer wins": clips where a peer is better than hapcine's default.
void PeerWins(std::ostream& md, const Table& t) {
  std::string def;
  for (const auto& [key, r] : t.cell)
    if (IsDefault(*r)) def = key.first;
  if (def.empty()) { md << "\n(no hapcine default run to compare with)\n"; return; }
  md << "\nComputed from the tables above, against **" << def << "** (lower is better; "
        "a tie within 10 % or 0.005 deg / 0.05 % is not counted):\n\n";
  for (const auto& meth : t.methods) {
    const RunRow* any = nullptr;
    for (const auto& clip : t.clips)
      if (auto it = t.cell.find({meth, clip}); it != t.cell.end()) any = it->second;
    if (!any || IsHapcine(any->tool)) continue;
    struct Win { std::string what; std::vector<std::string> clips; };
    std::vector<Win> wins = {{"rotation error", {}}, {"zoom-ratio error", {}}, {"ATE", {}},
                             {"time per frame", {}}, {"succeeded where hapcine failed", {}}};
    int both = 0;
    for (const auto& clip : t.clips) {
      auto p = t.cell.find({meth, clip}), h = t.cell.find({def, clip});
      if (p == t.cell.end() || h == t.cell.end()) continue;
      const RunRow &pr = *p->second, &hr = *h->second;
      if (pr.rc == 0 && pr.MsPerFrame() < 0.9 * hr.MsPerFrame())
        wins[3].clips.push_back(clip + " (" + Fmt(pr.MsPerFrame()) + " vs " + Fmt(hr.MsPerFrame()) + " ms)");
      if (pr.Failed() || pr.Partial()) continue;
      if (hr.Failed()) { wins[4].clips.push_back(clip); continue; }
      ++both;
      auto better = [](double a, double b, double abs_tol) { return a < 0.9 * b && b - a > abs_tol; };
      if (better(Rot(pr), Rot(hr), 0.005))
        wins[0].clips.push_back(clip + " (" + Fmt(Rot(pr)) + " vs " + Fmt(Rot(hr)) + " deg)");
      if (kZoomClips.count(clip) && better(Zoom(pr), Zoom(hr), 0.05))
        wins[1].clips.push_back(clip + " (" + Fmt(Zoom(pr)) + " vs " + Fmt(Zoom(hr)) + " %)");
      if (std::isfinite(Ate(pr)) && std::isfinite(Ate(hr)) && better(Ate(pr), Ate(hr), 0.05))
        wins[2].clips.push_back(clip + " (" + Fmt(Ate(pr)) + " vs " + Fmt(Ate(hr)) + " %)");
    }
    md << "- **" << meth << "** (" << both << " clips where both succeeded):";
    bool none = true;
    for (const auto& w : wins) {
      if (w.clips.empty()) continue;
      none = false;
      md << "\n  - " << w.what << " on " << w.clips.size() << ": ";
      for (size_t i = 0; i < w.clips.size(); ++i) md << (i ? ", " : "") << w.clips[i];
    }
    if (none) md << " nowhere.";
    md << "\n";
  }
}

hapcine::bench::ScatterChart SpeedChart(const Table& t, const std::string& title, const std::string& y_label,
                                        double MethodStats::*field) {
  hapcine::bench::ScatterChart c;
  c.title = title;
  c.x_label = "wall time per video frame (ms, log)";
  c.y_label = y_label;
  c.log_x = c.log_y = true;
  hapcine::bench::ScatterSeries line;
  line.name = "hapcine settings";
  line.line = true;
  int color = 1;
  // Only the clips every hapcine setting ran (the sweep), so that the points
  // are medians over the same clips.
  const std::set<std::string> common = SweepClips(t);
  std::vector<std::pair<double, std::pair<double, std::string>>> pts;
  for (const auto& meth : t.methods) {
    const MethodStats s = Stats(t, meth, &common);
    if (s.clips == 0) continue;
    const std::string label = std::to_string(s.clips - s.failed) + "/" + std::to_string(s.clips) + " ok";
    if (meth.rfind("hapcine", 0) == 0) {
      pts.push_back({s.ms, {s.*field, meth.substr(8) + ", " + label}});
    } else {
      hapcine::bench::ScatterSeries p;
      p.name = meth;
      p.x = {s.ms};
      p.y = {s.*field};
      p.labels = {label};
      p.color_index = color;
      p.marker = color % 4;
      ++color;
      c.series.push_back(p);
    }
  }
  std::sort(pts.begin(), pts.end());
  for (const auto& [x, yl] : pts) {
    line.x.push_back(x);
    line.y.push_back(yl.first);
    line.labels.push_back(yl.second);
  }
  c.series.insert(c.series.begin(), line);
  return c;
}

void TryWritePng(const hapcine::bench::ScatterChart& c, const std::string& file, std::ostream& md,
                 const std::string& link, const std::string& caption) {
  try {
    hapcine::bench::WriteScatterPng(c, file);
    md << "\n![" << caption << "](" << link << ")\n";
  } catch (const hapcine::Error& e) {
    md << "\n(figure not drawn: " << e.what() << ")\n";
  }
}

// Sections of the report, in order.
struct ReportArgs {
  std::string runs, md_file, fig_dir, fig_link, loop_file, meta_file;
};

void MetaSection(std::ostream& md, const std::string& meta_file) {
  if (meta_file.empty()) return;
  std::ifstream in(meta_file);
  std::string line;
  md << "Run:\n\n";
  while (std::getline(in, line))
    if (!line.empty()) md << "- " << line << "\n";
}

void SummarySection(std::ostream& md, const Table& t) {
  md << "\n### Summary: median over the clips each method ran\n";
  SummaryTable(md, t, nullptr);
  const std::set<std::string> sweep = SweepClips(t);
  if (!sweep.empty() && sweep.size() < t.clips.size()) {
    md << "\nThe same on the " << sweep.size() << " clips every hapcine setting ran (";
    bool first = true;
    for (const auto& c : t.clips)
      if (sweep.count(c)) md << (first ? "" : ", ") << c, first = false;
    md << "):\n";
    SummaryTable(md, t, &sweep);
  }
  md << "\nErrors are the per-clip means of `hapcine eval --json` (rotation relative to the first frame, "
        "horizontal FOV, zoom ratio, ATE after Sim(3) alignment as % of the ground-truth path length), "
        "then the median over the clips where the method did not fail. † = under 90 % of the frames "
        "estimated; ° = the clip's camera translates, which a rotation-only peer cannot represent "
        "(its translation shows up as rotation); ATE is not given for the rotation-only peers.\n";
  md << "\n### Per clip\n";
  PerClipTable(md, t, "Rotation error, mean over frames (deg)", Rot);
  PerClipTable(md, t, "Horizontal FOV error, mean (%)", Fov);
  PerClipTable(md, t, "Zoom-ratio error, mean (%)", Zoom);
  PerClipTable(md, t, "ATE, RMSE as % of the ground-truth path (– = camera does not move, or rotation-only peer)", Ate);
  PerClipTable(md, t, "Wall time per video frame (ms)", Ms, false);
  md << "\n### Where a peer wins\n";
  PeerWins(md, t);
}

hapcine::bench::ScatterChart PerClipRotationChart(const Table& t) {
  hapcine::bench::ScatterChart c;
  c.title = "Rotation error per clip (an exact 0 is drawn at 1e-4)";
  c.x_label = "clip";
  c.y_label = "rotation err (deg, log)";
  c.x_categories = t.clips;
  c.log_y = true;
  c.width_px = 1300;
  int idx = 0;
  for (const auto& meth : t.methods) {
    hapcine::bench::ScatterSeries s;
    s.name = meth;
    s.color_index = idx;
    s.marker = idx % 4;
    ++idx;
    for (size_t k = 0; k < t.clips.size(); ++k) {
      auto it = t.cell.find({meth, t.clips[k]});
      if (it == t.cell.end() || it->second->Failed()) continue;
      s.x.push_back(k + 1 + 0.06 * (idx - 0.5 * t.methods.size()));
      s.y.push_back(std::max(Rot(*it->second), 1e-4));
    }
    c.series.push_back(s);
  }
  return c;
}

void SpeedSection(std::ostream& md, const Table& t, const ReportArgs& a) {
  md << "\n### Speed against error\n";
  md << "\nEach point: the median over the clips of the hapcine sweep (those every hapcine setting ran) that "
        "the method ran, failures left out (\"n/m ok\" counts those clips); time is the median wall time per frame. "
        "The zoom chart uses only the zoom clips among them (zoom_in and vertigo in the full run), so its median "
        "is the mean of a small and a large error; methods without a zoom clip are not drawn.\n";
  TryWritePng(SpeedChart(t, "Rotation error against time per frame (sweep clips)", "rotation err (deg, median over clips, log)",
                         &MethodStats::rot),
              a.fig_dir + "/speed_rotation.png", md, a.fig_link + "/speed_rotation.png", "rotation error against time");
  TryWritePng(SpeedChart(t, "Zoom-ratio error against time per frame (zoom clips of the sweep)",
                         "zoom-ratio err (%, median over zoom clips, log)", &MethodStats::zoom),
              a.fig_dir + "/speed_zoom.png", md, a.fig_link + "/speed_zoom.png", "zoom-ratio error against time");
  TryWritePng(PerClipRotationChart(t), a.fig_dir + "/per_clip_rotation.png", md,
              a.fig_link + "/per_clip_rotation.png", "rotation error per clip");
}

void DecodingSection(std::ostream& md, const std::vector<RunRow>& rows) {
  md << "\n### Decoding floor\n\n| video | frames | ffmpeg decode wall (s) | ffmpeg CPU (s) | "
        "hapcine estimate wall (s) | estimate CPU (s) | wall ratio | CPU ratio |\n|---|---|---|---|---|---|---|---|\n";
  // ffmpeg's row is the video's ("1080p"); hapcine's settings start with
  // it ("1080p", "1080p --draft") and are each set against it.
  std::map<std::string, const RunRow*> decoder_of;
  for (const auto& r : rows)
    if (r.group == "decode" && r.tool == "ffmpeg") decoder_of[r.setting] = &r;
  for (const auto& r : rows) {
    if (r.group != "decode" || r.tool == "ffmpeg") continue;
    const auto it = decoder_of.find(r.setting.substr(0, r.setting.find(' ')));
    if (it == decoder_of.end()) continue;
    const RunRow* f = it->second;
    const RunRow* h = &r;
    const double fc = f->user_s + f->sys_s, hc = h->user_s + h->sys_s;
    md << "| " << h->setting << " (" << h->clip << ") | " << h->frames << " | " << Fmt(f->wall_s) << " | "
       << Fmt(fc) << " | " << (h->rc ? "fail " : "") << Fmt(h->wall_s) << " | " << Fmt(hc) << " | "
       << Fmt(h->wall_s / f->wall_s) << " | " << Fmt(hc / fc) << " |\n";
  }
}

void MemorySection(std::ostream& md, const std::vector<RunRow>& rows, const ReportArgs& a) {
  md << "\n### Memory against clip length\n\n| clip length (min) | frames | settings | wall (s) | "
        "ms/frame | peak RSS (MB) | exit |\n|---|---|---|---|---|---|---|\n";
  hapcine::bench::ScatterChart mem;
  mem.title = "Peak RSS of hapcine estimate against clip length";
  mem.x_label = "clip length (minutes)";
  mem.y_label = "peak RSS (MB)";
  hapcine::bench::ScatterSeries ms;
  ms.name = "hapcine estimate";
  ms.line = true;
  for (const auto& r : rows) {
    if (r.group != "memory") continue;
    md << "| " << r.clip << " | " << r.frames << " | " << r.setting << " | " << Fmt(r.wall_s) << " | "
       << Fmt(r.MsPerFrame()) << " | " << Fmt(r.maxrss_kb / 1024) << " | " << r.rc << " |\n";
    if (r.rc == 0) {
      ms.x.push_back(std::atof(r.clip.c_str()));
      ms.y.push_back(r.maxrss_kb / 1024);
      ms.labels.push_back(Fmt(r.maxrss_kb / 1024) + " MB");
    }
  }
  if (ms.x.empty()) return;
  mem.y_from_zero = true;  // a flat line should look flat
  mem.series = {ms};
  TryWritePng(mem, a.fig_dir + "/memory.png", md, a.fig_link + "/memory.png", "peak RSS against clip length");
}

void WriteReport(const ReportArgs& a) {
  const std::vector<RunRow> rows = hapcine::bench::ReadRuns(a.runs);
  const Table t = BuildTable(rows);
  std::ostringstream md;
  MetaSection(md, a.meta_file);
  SummarySection(md, t);
  SpeedSection(md, t, a);
  DecodingSection(md, rows);
  MemorySection(md, rows, a);
  if (!a.loop_file.empty()) {
    std::ifstream in(a.loop_file);
    md << "\n### Haptic loop on the simulated HapSeat\n\n```\n" << in.rdbuf() << "```\n";
  }
  hapcine::AtomicFile out(a.md_file);
  out.stream() << md.str();
  out.Commit();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace hapcine;
  ReportArgs a;
  a.runs = bench::ArgValue(argc, argv, "--runs", "");
  a.md_file = bench::ArgValue(argc, argv, "--md", "");
  a.fig_dir = bench::ArgValue(argc, argv, "--figures", "");
  a.fig_link = bench::ArgValue(argc, argv, "--figure-link", a.fig_dir);
  a.loop_file = bench::ArgValue(argc, argv, "--loop", "");
  a.meta_file = bench::ArgValue(argc, argv, "--meta", "");
  if (a.runs.empty() || a.md_file.empty() || a.fig_dir.empty()) {
    std::fprintf(stderr, "usage: %s --runs runs.tsv --md out.md --figures DIR [--figure-link PREFIX] "
                         "[--loop loop.txt] [--meta meta.txt]\n", argv[0]);
    return 2;
  }
  try {
    WriteReport(a);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hapcine_bench_report: %s\n", e.what());
    return 1;
  }
  return 0;
}
