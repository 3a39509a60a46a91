#include "estimate/stills_groups.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <unordered_set>

namespace hapcine {
namespace {

struct Link {
  int later = 0, earlier = 0;            // shots
  int later_frame = 0, earlier_frame = 0;  // the views linked
  int verified = 0;
};

int Find(std::map<int, int>* parent, int s) {
  while ((*parent)[s] != s) s = (*parent)[s] = (*parent)[(*parent)[s]];
  return s;
}

// Position of `frame` among its shot's frames (tracker order).
int PositionInShot(const std::map<int, std::vector<int>>& frames_of_shot, int shot, int frame) {
  const std::vector<int>& f = frames_of_shot.at(shot);
  return static_cast<int>(std::find(f.begin(), f.end(), frame) - f.begin());
}

// Puts `shot` before or after `order` by its strongest link into it: before
// its head when the link joins the shot's end to the head's start (the
// views linked are the last of one and the first of the other), else last.
void PlaceShot(int shot, const std::vector<Link>& links, const std::map<int, std::vector<int>>& frames_of_shot,
               std::deque<int>* order) {
  const Link* best = nullptr;
  for (const Link& l : links)
    if (l.later == shot && std::count(order->begin(), order->end(), l.earlier) &&
        (!best || l.verified > best->verified))
      best = &l;
  if (best && best->earlier == order->front()) {
    const int later_size = static_cast<int>(frames_of_shot.at(shot).size());
    const int earlier_size = static_cast<int>(frames_of_shot.at(best->earlier).size());
    const int p_later = PositionInShot(frames_of_shot, shot, best->later_frame);
    const int p_earlier = PositionInShot(frames_of_shot, best->earlier, best->earlier_frame);
    const int gap_before = (later_size - 1 - p_later) + p_earlier;  // this shot, then the head
    const int gap_after = (earlier_size - 1 - p_earlier) + p_later;  // the head, then this shot
    if (gap_before < gap_after) {
      order->push_front(shot);
      return;
    }
  }
  order->push_back(shot);
}

// The group's chain starts at its first view: that first interval sets the
// start every later view is placed from, and a weak link (few verified
// matches; under a long lens the bas-relief ambiguity) puts the whole
// group in a wrong basin. Leading views whose link to the next is weak
// (FrameTracks::weak_link) are left out of the chain, as views linked to
// nothing: taken from the front of `sequence` and returned.
std::vector<size_t> WeakLeadIn(const std::vector<FrameTracks>& frames, std::vector<size_t>* sequence) {
  size_t lead = 0;
  while (lead + 1 < sequence->size() && frames[(*sequence)[lead + 1]].weak_link &&
         frames[(*sequence)[lead + 1]].shot == frames[(*sequence)[lead]].shot)
    ++lead;
  std::vector<size_t> lead_in(sequence->begin(), sequence->begin() + static_cast<long>(lead));
  sequence->erase(sequence->begin(), sequence->begin() + static_cast<long>(lead));
  return lead_in;
}

// Appends `frames[sequence]` to `out` as the stream's next shot.
void AppendShot(const std::vector<size_t>& sequence, std::vector<FrameTracks>* frames,
                std::vector<FrameTracks>* out) {
  const int shot = out->empty() ? 0 : out->back().shot + 1;
  for (size_t k = 0; k < sequence.size(); ++k) {
    FrameTracks& t = (*frames)[sequence[k]];
    // The estimator's own rule still splits where the next frame shares
    // too few tracks with the last keyframe.
    t.boundary = k > 0 ? ShotBoundary::kNone : (out->empty() ? ShotBoundary::kStart : ShotBoundary::kCut);
    t.shot = shot;
    out->push_back(std::move(t));
  }
}

}  // namespace

std::vector<std::vector<int>> StillsShotGroups(const std::vector<FrameTracks>& frames) {
  std::map<int, std::vector<int>> frames_of_shot;
  std::map<int, int> parent;
  std::vector<Link> links;
  for (const FrameTracks& t : frames) {
    frames_of_shot[t.shot].push_back(t.index);
    parent[t.shot] = t.shot;
  }
  for (const FrameTracks& t : frames)
    for (const FrameTracks::ShotLink& l : t.earlier_shot_links)
      if (l.shot < t.shot && parent.count(l.shot)) {
        links.push_back({t.shot, l.shot, t.index, l.frame, l.verified});
        parent[Find(&parent, t.shot)] = Find(&parent, l.shot);
      }
  std::map<int, std::deque<int>> group_of_root;  // by the root: the group's first shot
  for (const auto& [shot, unused] : frames_of_shot) {
    std::deque<int>& order = group_of_root[Find(&parent, shot)];
    if (order.empty())
      order.push_back(shot);
    else
      PlaceShot(shot, links, frames_of_shot, &order);
  }
  std::vector<std::vector<int>> groups;
  for (auto& [root, order] : group_of_root) groups.emplace_back(order.begin(), order.end());
  std::sort(groups.begin(), groups.end(), [](const std::vector<int>& a, const std::vector<int>& b) {
    return *std::min_element(a.begin(), a.end()) < *std::min_element(b.begin(), b.end());
  });
  return groups;
}

std::vector<FrameTracks> StillsRegrouper::Add(FrameTracks tracks) {
  // The first frame of a video found to be stills is tracked before the
  // evidence: it does not decide.
  if (holding_ && (held_.empty() || tracks.still)) {
    held_.push_back(std::move(tracks));
    return {};
  }
  holding_ = false;
  std::vector<FrameTracks> ready = std::move(held_);
  held_.clear();
  ready.push_back(std::move(tracks));
  return ready;
}

std::vector<FrameTracks> StillsRegrouper::Add(std::vector<FrameTracks> frames) {
  std::vector<FrameTracks> ready;
  for (FrameTracks& t : frames)
    for (FrameTracks& r : Add(std::move(t))) ready.push_back(std::move(r));
  return ready;
}

std::vector<FrameTracks> StillsRegrouper::Finish() {
  std::vector<FrameTracks> frames = std::move(held_);
  held_.clear();
  const std::vector<std::vector<int>> groups = StillsShotGroups(frames);
  const bool any_group = std::any_of(groups.begin(), groups.end(), [](const auto& g) { return g.size() > 1; });
  if (!any_group) return frames;
  regrouped_ = true;
  std::vector<int> original_shot;
  for (const FrameTracks& t : frames) original_shot.push_back(t.shot);
  std::vector<FrameTracks> out;
  for (size_t g = 0; g < groups.size(); ++g) {
    std::vector<size_t> sequence;  // the group's frames, indices into `frames`
    for (int shot : groups[g])
      for (size_t i = 0; i < frames.size(); ++i)
        if (original_shot[i] == shot) sequence.push_back(i);
    // Views left out of the chain follow it, each a shot of one view that
    // takes the focal the chain calibrated (track_estimator.h).
    const std::vector<size_t> lead_in = groups[g].size() > 1 ? WeakLeadIn(frames, &sequence) : std::vector<size_t>{};
    AppendShot(sequence, &frames, &out);
    for (size_t i : lead_in) AppendShot({i}, &frames, &out);
  }
  return out;
}

std::vector<WindowReport> StillsRegrouper::Restore(CameraPath* path, std::vector<WindowReport> reports) const {
  if (regrouped_) RestoreFrameOrder(path, &reports);
  return reports;
}

void RestoreFrameOrder(CameraPath* path, std::vector<WindowReport>* reports) {
  std::stable_sort(path->frames.begin(), path->frames.end(),
                   [](const CameraFrame& a, const CameraFrame& b) { return a.frame < b.frame; });
  std::map<int, int> renumbered;
  for (CameraFrame& f : path->frames) {
    if (!f.shot.has_value()) continue;
    const auto it = renumbered.emplace(*f.shot, static_cast<int>(renumbered.size())).first;
    f.shot = it->second;
  }
  if (!reports) return;
  for (WindowReport& w : *reports)
    if (const auto it = renumbered.find(w.shot); it != renumbered.end()) w.shot = it->second;
}

}  // namespace hapcine
