#include "bench/bench_results.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.h"

namespace hapcine::bench {
namespace {

std::vector<std::string> SplitTabs(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, '\t')) out.push_back(cell);
  if (!line.empty() && line.back() == '\t') out.emplace_back();
  return out;
}

double ToDouble(const std::string& s, const std::string& where) {
  try {
    size_t used = 0;
    const double v = std::stod(s, &used);
    if (used != s.size()) throw std::invalid_argument(s);
    return v;
  } catch (const std::exception&) {
    throw Error(where, "not a number: '" + s + "'");
  }
}

}  // namespace

EvalSummary ReadEvalSummary(const std::string& json_file) {
  std::ifstream in(json_file);
  if (!in) throw Error(json_file, "cannot open");
  nlohmann::json j;
  try {
    in >> j;
    const auto& o = j.at("overall");
    EvalSummary s;
    s.rotation_deg = o.at("rotation_deg").at("mean").get<double>();
    s.fov_percent = o.at("fov_percent").at("mean").get<double>();
    s.zoom_ratio_percent = o.at("zoom_ratio_percent").at("mean").get<double>();
    if (!o.at("ate_percent").is_null()) s.ate_percent = o.at("ate_percent").get<double>();
    s.gt_static = o.at("gt_static").get<bool>();
    s.matched = j.at("frames").at("matched").get<int>();
    s.gt_frames = j.at("frames").at("gt").get<int>();
    return s;
  } catch (const nlohmann::json::exception& e) {
    throw Error(json_file, std::string("not an eval report: ") + e.what());
  }
}

std::vector<RunRow> ReadRuns(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw Error(file, "cannot open");
  const std::filesystem::path dir = std::filesystem::path(file).parent_path();
  std::vector<RunRow> rows;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line_no == 1 || line.empty()) continue;  // header
    const std::string where = file + ":" + std::to_string(line_no);
    const auto c = SplitTabs(line);
    if (c.size() != 12) throw Error(where, "expected 12 tab-separated columns, got " + std::to_string(c.size()));
    RunRow r;
    r.group = c[0];
    r.tool = c[1];
    r.setting = c[2];
    r.clip = c[3];
    r.rc = static_cast<int>(ToDouble(c[4], where));
    r.wall_s = ToDouble(c[5], where);
    r.user_s = ToDouble(c[6], where);
    r.sys_s = ToDouble(c[7], where);
    r.maxrss_kb = ToDouble(c[8], where);
    r.frames = static_cast<int>(ToDouble(c[9], where));
    r.eval_json = c[10];
    r.note = c[11];
    if (!r.eval_json.empty()) {
      std::filesystem::path p(r.eval_json);
      if (p.is_relative()) p = dir / p;
      if (std::filesystem::exists(p)) r.eval = ReadEvalSummary(p.string());
    }
    rows.push_back(r);
  }
  return rows;
}

}  // namespace hapcine::bench
