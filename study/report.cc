#include "study/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/atomic_file.h"

namespace hapcine::study {
using nlohmann::json;

namespace {

std::string Fmt(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

std::string FmtP(double p) {
  if (p < 1e-4) return Fmt("%.2e", p);
  return Fmt("%.4f", p);
}

std::string Stars(double p) { return p < 0.001 ? " ***" : p < 0.01 ? " **" : p < 0.05 ? " *" : ""; }

std::string Pad(std::string s, size_t w) {
  if (s.size() < w) s += std::string(w - s.size(), ' ');
  return s;
}

void FormatTests(const ScoreTable& t, const std::vector<std::string>& conditions, std::ostream& o) {
  if (t.friedman.valid) {
    o << "  Friedman chi-squared = " << Fmt("%.3f", t.friedman.statistic)
      << ", df = " << t.friedman.df << ", p = " << FmtP(t.friedman.p) << Stars(t.friedman.p)
      << "\n";
  } else {
    o << "  Friedman: n/a (" << t.friedman.reason << ")\n";
  }
  o << "  Wilcoxon signed-rank, two-sided, Holm-Bonferroni within this table:\n";
  for (const auto& pt : t.pairwise) {
    o << "    " << Pad(pt.a + " vs " + pt.b, 24);
    if (pt.same_stimulus) {
      o << "one stimulus on this sequence (identical tracks): not tested\n";
      continue;
    }
    if (pt.wilcoxon.n_used == 0) {
      o << "identical scores for every participant (p = 1)\n";
      continue;
    }
    o << "V = " << Pad(Fmt("%.1f", pt.wilcoxon.v), 7)
      << " n = " << Pad(std::to_string(pt.wilcoxon.n_used), 4)
      << (pt.wilcoxon.exact ? "exact " : "normal") << "  p = " << Pad(FmtP(pt.wilcoxon.p), 9)
      << " p_holm = " << FmtP(pt.p_holm) << Stars(pt.p_holm) << "\n";
  }
}

// --- SVG -------------------------------------------------------------------

const char* const kColours[] = {"#1f77b4", "#ff7f0e", "#7f7f7f", "#d62728",
                                "#2ca02c", "#9467bd", "#8c564b", "#e377c2"};

std::string Esc(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '<')
      o += "&lt;";
    else if (c == '>')
      o += "&gt;";
    else if (c == '&')
      o += "&amp;";
    else if (c == '"')
      o += "&quot;";
    else
      o += c;
  }
  return o;
}

// A bar chart: groups along x, one bar per series in each group, y in [0,1].
std::string BarChart(const std::string& title, const std::vector<std::string>& groups,
                     const std::vector<std::string>& series,
                     const std::vector<std::vector<double>>& value,  // [group][series]
                     const std::vector<std::vector<double>>& err, bool legend) {
  const double bar_w = 22, gap = 18, left = 60, right = legend ? 150 : 20, top = 40, plot_h = 260,
               bottom = 60;
  // Wide enough that neither the group labels (about 7 px per character at
  // 12 px) nor the title (about 8 px at 14 px) overlap or get cut.
  size_t longest_group = 0;
  for (const auto& g : groups) longest_group = std::max(longest_group, g.size());
  const double group_w = std::max(series.size() * bar_w + gap, 7.0 * longest_group + 12);
  const double plot_w =
      std::max({200.0, groups.size() * group_w, 8.0 * title.size() + 20 - left - right});
  const double width = left + plot_w + right, height = top + plot_h + bottom;
  auto y_of = [&](double v) { return top + plot_h * (1 - std::clamp(v, 0.0, 1.0)); };
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
    << "\" viewBox=\"0 0 " << width << " " << height
    << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  s << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s << "<text x=\"" << width / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"14\">"
    << Esc(title) << "</text>\n";
  for (int i = 0; i <= 5; ++i) {
    const double v = i / 5.0, y = y_of(v);
    s << "<line x1=\"" << left << "\" y1=\"" << y << "\" x2=\"" << left + plot_w << "\" y2=\"" << y
      << "\" stroke=\"#ddd\"/>\n";
    s << "<text x=\"" << left - 6 << "\" y=\"" << y + 4 << "\" text-anchor=\"end\">"
      << Fmt("%.1f", v) << "</text>\n";
  }
  s << "<text x=\"16\" y=\"" << top + plot_h / 2 << "\" transform=\"rotate(-90 16 "
    << top + plot_h / 2 << ")\" text-anchor=\"middle\">normalised score</text>\n";
  s << "<line x1=\"" << left << "\" y1=\"" << top + plot_h << "\" x2=\"" << left + plot_w
    << "\" y2=\"" << top + plot_h << "\" stroke=\"black\"/>\n";
  s << "<line x1=\"" << left << "\" y1=\"" << top << "\" x2=\"" << left << "\" y2=\""
    << top + plot_h << "\" stroke=\"black\"/>\n";
  for (size_t g = 0; g < groups.size(); ++g) {
    const double x0 = left + g * group_w + (group_w - series.size() * bar_w) / 2;
    for (size_t k = 0; k < series.size(); ++k) {
      const double x = x0 + k * bar_w, v = value[g][k], e = err[g][k];
      s << "<rect x=\"" << x + 2 << "\" y=\"" << y_of(v) << "\" width=\"" << bar_w - 4
        << "\" height=\"" << top + plot_h - y_of(v) << "\" fill=\"" << kColours[k % 8]
        << "\"><title>" << Esc(groups[g]) << " " << Esc(series[k]) << ": " << Fmt("%.3f", v)
        << " &#177; " << Fmt("%.3f", e) << "</title></rect>\n";
      const double xc = x + bar_w / 2, y_lo = y_of(v - e), y_hi = y_of(v + e);
      s << "<path d=\"M" << xc << " " << y_lo << " V" << y_hi << " M" << xc - 4 << " " << y_lo
        << " H" << xc + 4 << " M" << xc - 4 << " " << y_hi << " H" << xc + 4
        << "\" stroke=\"black\" fill=\"none\"/>\n";
    }
    s << "<text x=\"" << x0 + series.size() * bar_w / 2 << "\" y=\"" << top + plot_h + 18
      << "\" text-anchor=\"middle\">" << Esc(groups[g]) << "</text>\n";
  }
  if (legend) {
    for (size_t k = 0; k < series.size(); ++k) {
      const double y = top + 10 + 20 * k, x = left + plot_w + 20;
      s << "<rect x=\"" << x << "\" y=\"" << y - 10 << "\" width=\"12\" height=\"12\" fill=\""
        << kColours[k % 8] << "\"/><text x=\"" << x + 18 << "\" y=\"" << y << "\">"
        << Esc(series[k]) << "</text>\n";
    }
  }
  s << "<text x=\"" << left << "\" y=\"" << height - 12 << "\" font-size=\"10\" fill=\"#555\">"
    << "bars: mean over participants; error bars: &#177;1 SD</text>\n";
  s << "</svg>\n";
  return s.str();
}

// The post-test questionnaire: per question its answers' count and, by
// type, median/mean/IQR (likert), counts per option (choice) or the answers
// themselves (text).
void FormatQuestionnaire(const StudyAnalysis& a, std::ostream& o) {
  if (a.questionnaire.empty()) return;
  o << "\nQuestionnaire (n = answers; likert: median, mean, IQR = Q1-Q3; by training "
       "condition)\n";
  for (const QuestionSummary& s : a.questionnaire) {
    const Question& q = s.question;
    o << "  " << q.id << " (" << q.type;
    if (q.type == "likert") o << " " << q.min << "-" << q.max;
    o << "): " << q.text << "\n";
    for (const LikertSummary& l : s.likert)
      o << "    " << Pad(l.group, 12) << "n=" << Pad(std::to_string(l.n), 4) << "median "
        << Pad(Fmt("%.1f", l.median), 6) << "mean " << Pad(Fmt("%.2f", l.mean), 7) << "IQR "
        << Fmt("%.2f", l.q1) << "-" << Fmt("%.2f", l.q3) << " (" << Fmt("%.2f", l.q3 - l.q1)
        << ")\n";
    if (q.type == "choice") {
      o << "    n=" << s.n << ":";
      for (const auto& [option, count] : s.counts) o << "  " << option << " " << count;
      o << "\n";
    }
    if (q.type == "text") {
      o << "    n=" << s.n << " non-empty answers\n";
      for (const auto& t : s.texts) o << "      - " << t << "\n";
    }
  }
}

json QuestionnaireReportJson(const StudyAnalysis& a) {
  json out = json::array();
  for (const QuestionSummary& s : a.questionnaire) {
    json j = QuestionToJson(s.question);
    j["n"] = s.n;
    if (s.question.type == "likert") {
      j["likert"] = json::array();
      for (const LikertSummary& l : s.likert)
        j["likert"].push_back({{"group", l.group},
                               {"n", l.n},
                               {"median", l.median},
                               {"mean", l.mean},
                               {"q1", l.q1},
                               {"q3", l.q3},
                               {"iqr", l.q3 - l.q1}});
    } else if (s.question.type == "choice") {
      j["counts"] = json::object();
      for (const auto& [option, count] : s.counts) j["counts"][option] = count;
    } else {
      j["answers"] = s.texts;
    }
    out.push_back(j);
  }
  return out;
}

}  // namespace

std::string FormatReport(const StudyAnalysis& a) {
  std::ostringstream o;
  o << "Study plan " << a.plan_id << ": " << a.participants.size() << " participants, "
    << a.clips.size() << " sequences, conditions:";
  for (const auto& c : a.conditions) o << " " << c;
  o << "\nScore = points / maximum possible, in [0,1]; mean and SD across participants.\n\n";
  o << "All sequences\n  " << Pad("condition", 12) << Pad("mean", 8) << Pad("sd", 8)
    << "Shapiro-Wilk W, p\n";
  for (size_t c = 0; c < a.conditions.size(); ++c) {
    const auto& sw = a.overall.normality[c];
    o << "  " << Pad(a.conditions[c], 12) << Pad(Fmt("%.3f", a.overall.mean[c]), 8)
      << Pad(Fmt("%.3f", a.overall.sd[c]), 8)
      << (sw.valid ? Fmt("%.4f", sw.w) + ", " + FmtP(sw.p) + (sw.p < 0.05 ? " (not normal)" : "")
                   : "n/a (" + sw.reason + ")")
      << "\n";
  }
  FormatTests(a.overall, a.conditions, o);
  o << "\nPer sequence (mean score)\n  " << Pad("sequence", 14);
  for (const auto& c : a.conditions) o << Pad(c, 11);
  o << "Friedman p\n";
  for (const auto& t : a.per_clip) {
    o << "  " << Pad(t.label, 14);
    for (size_t c = 0; c < a.conditions.size(); ++c) o << Pad(Fmt("%.3f", t.mean[c]), 11);
    o << (t.friedman.valid ? FmtP(t.friedman.p) + Stars(t.friedman.p) : "n/a") << "\n";
  }
  for (const auto& t : a.per_clip) {
    o << "\nSequence " << t.label << "\n";
    FormatTests(t, a.conditions, o);
  }
  o << "\n* p < 0.05, ** p < 0.01, *** p < 0.001\n";
  FormatQuestionnaire(a, o);
  return o.str();
}

json ReportToJson(const StudyAnalysis& a) {
  auto table = [&](const ScoreTable& t) {
    json j;
    j["label"] = t.label;
    j["scores"] = t.score;
    j["mean"] = t.mean;
    j["sd"] = t.sd;
    j["shapiro_wilk"] = json::array();
    for (const auto& sw : t.normality)
      j["shapiro_wilk"].push_back(sw.valid ? json{{"w", sw.w}, {"p", sw.p}, {"n", sw.n}}
                                           : json{{"invalid", sw.reason}});
    j["friedman"] = t.friedman.valid ? json{{"chi_squared", t.friedman.statistic},
                                            {"df", t.friedman.df},
                                            {"p", t.friedman.p}}
                                     : json{{"invalid", t.friedman.reason}};
    j["pairwise"] = json::array();
    for (const auto& pt : t.pairwise)
      j["pairwise"].push_back({{"a", pt.a},
                               {"b", pt.b},
                               {"v", pt.wilcoxon.v},
                               {"n_used", pt.wilcoxon.n_used},
                               {"exact", pt.wilcoxon.exact},
                               {"p", pt.wilcoxon.p},
                               {"p_holm", pt.p_holm},
                               {"same_stimulus", pt.same_stimulus}});
    return j;
  };
  json j;
  j["plan_id"] = a.plan_id;
  j["conditions"] = a.conditions;
  j["participants"] = a.participants;
  j["overall"] = table(a.overall);
  j["per_sequence"] = json::array();
  for (const auto& t : a.per_clip) j["per_sequence"].push_back(table(t));
  j["questionnaire"] = QuestionnaireReportJson(a);
  return j;
}

std::string OverallSvg(const StudyAnalysis& a) {
  std::vector<std::vector<double>> v, e;
  for (size_t c = 0; c < a.conditions.size(); ++c) {
    v.push_back({a.overall.mean[c]});
    e.push_back({a.overall.sd[c]});
  }
  return BarChart("Average score over all sequences (" + std::to_string(a.participants.size()) +
                      " participants)",
                  a.conditions, {""}, v, e, false);
}

std::string SequencesSvg(const StudyAnalysis& a) {
  std::vector<std::vector<double>> v, e;
  for (const auto& t : a.per_clip) {
    v.push_back(t.mean);
    e.push_back(t.sd);
  }
  return BarChart("Score per sequence and condition", a.clips, a.conditions, v, e, true);
}

std::vector<std::string> WriteReport(const StudyAnalysis& a, const std::string& prefix) {
  const std::vector<std::pair<std::string, std::string>> files = {
      {prefix + ".txt", FormatReport(a)},
      {prefix + ".json", ReportToJson(a).dump(1) + "\n"},
      {prefix + ".overall.svg", OverallSvg(a)},
      {prefix + ".sequences.svg", SequencesSvg(a)}};
  std::vector<std::string> written;
  for (const auto& [path, text] : files) {
    AtomicFile f(path);
    f.stream() << text;
    f.Commit();
    written.push_back(path);
  }
  return written;
}

}  // namespace hapcine::study
