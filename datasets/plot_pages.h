#pragma once
// Long plots cut into readable pages (`hapcine plot --from/--to`,
// `--page-minutes`, `--page-per-shot`): the time ranges of the pages and the
// file each one is written to.

#include <string>
#include <utility>
#include <vector>

namespace hapcine {

using TimeRange = std::pair<double, double>;  // [first, second] seconds, first < second

// Seconds from "90", "90.5", "1:30", "1:02:03.5" (H:MM:SS, a film's running
// time). Throws UsageError naming `option` on anything else or a negative time.
double ParsePlotTime(const std::string& text, const std::string& option);

// [begin, end] cut into consecutive pages of page_s (the last one shorter);
// page_s <= 0: one page. A remainder under a hundredth of a page joins the
// page before it (no page of a frame or two).
std::vector<TimeRange> PagesByDuration(double begin, double end, double page_s);
// One page per shot: [begin, end] cut at each cut time inside it.
std::vector<TimeRange> PagesByShot(double begin, double end, const std::vector<double>& cut_times);

// The file of page `index` (0-based) of `count`: "fig.png" when count == 1,
// else "fig-001.png", "fig-002.png", ... (`path` is the single-page name).
std::string PagePath(const std::string& path, size_t index, size_t count);

}  // namespace hapcine
