#pragma once
// Presenting a StudyAnalysis: a plain-text table (what the terminal shows),
// a JSON dump of every number, and two bar charts drawn as SVG by hand, like
// the paper's Figure 6 (mean score per condition over all sequences) and
// Figure 7 (mean score per condition for each sequence), error bars +-1 SD
// across participants. SVG only: this library links no image codec.

#include <nlohmann/json.hpp>
#include <string>

#include "study/analysis.h"

namespace hapcine::study {

std::string FormatReport(const StudyAnalysis& a);
nlohmann::json ReportToJson(const StudyAnalysis& a);
std::string OverallSvg(const StudyAnalysis& a);    // Figure 6
std::string SequencesSvg(const StudyAnalysis& a);  // Figure 7
// Writes <prefix>.txt, <prefix>.json, <prefix>.overall.svg and
// <prefix>.sequences.svg, each atomically. Returns the paths written.
std::vector<std::string> WriteReport(const StudyAnalysis& a, const std::string& prefix);

}  // namespace hapcine::study
