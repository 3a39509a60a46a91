// SolveWindow (window_solver.h): one window's bundle adjustment, from the
// keyframes' two-view labels to the solved keyframes and points (model
// choice, track rejection). docs/estimate.md, "Algorithm", step 4.
//
// The candidate solves that run on other threads get their inputs by value
// or const reference and write only their own result: the same arithmetic,
// in the same order, as one after the other.

#include "estimate/window/window_solver.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <future>
#include <utility>

#include "core/diagnostics.h"
#include "core/rotation.h"
#include "core/statistics.h"
#include "estimate/window/axial_ambiguity.h"
#include "estimate/window/dolly_or_zoom.h"
#include "estimate/window/focal_profile.h"
#include "estimate/window/focal_search.h"
#include "estimate/window/jump_resection.h"
#include "estimate/window/occlusion_order.h"
#include "estimate/window/plane_prior.h"
#include "estimate/window/track_drift.h"
#include "estimate/geometry/reference_width.h"
#include "estimate/bundle/robust_bundle.h"
#include "estimate/geometry/two_view_geometry.h"
#include "estimate/window/window_freedoms.h"

namespace hapcine {
namespace {

// Tracks the plane prior searches a floor among.
constexpr int kMaxPlanePoints = 2000;

// The scale gauge's weight in a shot of stills: a sigma of the whole
// interval's length (BaOptions::scale_weight). Stills are whole steps apart,
// and under a long lens a pair's two-view step is ambiguous against the
// depth relief (bas-relief): its length, held tight, held the window in that
// wrong basin. Loose, the gauge still removes the scale freedom (the solve
// stays well posed) and the interval's length follows the rest of the window.
constexpr double kStillsScaleWeight = 1.0;

// Everything the window's candidate solves share, derived once from the input.
struct WindowProblem {
  const WindowInput* in = nullptr;
  const WindowOptions* opt = nullptr;
  int n = 0;
  std::vector<WindowKeyframe> keyframes;  // labels promoted, focal initialised
  bool has_translation = false, has_general = false;
  bool focal_observable = false;
  // The shot's focal observable for the first time after frames that could
  // not observe it: the held lead-in's focal is freed and calibrated with
  // the window, and the frames already written take the same change.
  bool recalibrate_lead_in = false;
  double lead_in_log_focal = 0;
  double chain_focal_shift = 0;  // the chain rebuilt at the prior focal x exp(this) (focal_search.h)
  int held = 0;                 // the last held keyframe (the lead-in): the motion before it is decided
  bool scale_pinned = false;    // two held keyframes with distinct centres fix the scale
  bool mostly_translating = false;
  std::vector<const KeyframeTracks*> tracks_at;
  WindowTracks window_tracks;
  std::vector<BaCamera> cams;   // the constant-focal start
  std::vector<BaPoint> points;  // point k is the track order[k] in every candidate
  std::vector<BaObservation> obs;
  BaOptions ba;
};

struct Candidate {
  std::vector<BaCamera> cams;
  std::vector<BaPoint> pts;
  std::vector<BaObservation> ob;
  BaSummary summary;
};

bool FocalObservable(const WindowInput& in, double min_rotation_for_focal_deg) {
  double max_turn = 0;
  for (const auto& k : in.keyframes)
    max_turn = std::max(max_turn, OpticalAxisAngleDeg(k.cam.world_from_cam, in.keyframes[0].cam.world_from_cam));
  return in.focal_observed || max_turn >= min_rotation_for_focal_deg;
}

// Points: tracks seen by >= 2 keyframes (window_points.h), spread over the
// image only where the camera translates and not along the optical axis:
// without parallax an occlusion edge does not slide (every track is rigid,
// the longest are best), and along the axis the tracks in front of the
// subject decide the dolly/zoom branch (DropBadTracks is off there). Where
// the grid spreads them, the whole-track cut also drops the occlusion-edge
// corners and the good tracks the first, bent solve puts far: take more
// there, so that about `max_points` rigid ones remain.
void ChooseWindowPoints(WindowProblem* p) {
  const WindowOptions& opt = *p->opt;
  std::vector<BaCamera> initial(p->n);
  for (int i = 0; i < p->n; ++i) initial[i] = p->keyframes[i].cam;
  const bool spread_points = p->has_translation && !IsAxialMotion(initial, p->held);
  const int window_points = spread_points ? static_cast<int>(std::lround(opt.max_points * opt.spread_points_factor))
                                          : opt.max_points;
  p->tracks_at.resize(p->n);
  for (int i = 0; i < p->n; ++i) p->tracks_at[i] = p->keyframes[i].tracks;
  p->window_tracks = SelectWindowPoints(p->tracks_at, p->in->outlier_tracks, window_points,
                                        spread_points ? opt.point_grid_cells : 0);
}

// A jump keyframe's two-view pose rests on the few tracks its link shares
// with the keyframe before; where it continues tracks that earlier keyframes
// triangulate, resection measures it better (jump_resection.h).
void PlaceJumpKeyframes(WindowProblem* p) {
  std::vector<BaCamera> cams(p->n);
  std::vector<const KeyframeTracks*> tracks(p->n);
  for (int i = 0; i < p->n; ++i) {
    cams[i] = p->keyframes[i].cam;
    tracks[i] = p->keyframes[i].tracks;
  }
  for (int i = p->held + 1; i < p->n; ++i) {
    if (!p->keyframes[i].jump || p->keyframes[i].fixed) continue;
    if (const auto placed = ResectKeyframe(cams, tracks, i)) MoveChainFrom(i, *placed, &cams);
  }
  for (int i = 0; i < p->n; ++i) p->keyframes[i].cam = cams[i];
}

void InitPoints(const WindowProblem& p, const std::vector<BaCamera>& c, std::vector<BaPoint>* pts,
                std::vector<BaObservation>* ob) {
  InitWindowPoints(c, p.window_tracks, p.tracks_at, p.has_translation, 0.2 / p.in->scene_depth, pts, ob);
}

// Solve options; the scale gauge unless two held keyframes pin it.
void SetSolveOptions(WindowProblem* p) {
  const WindowOptions& opt = *p->opt;
  BaOptions& ba = p->ba;
  ba.huber_scale = 1.0 / kReferenceWidthPx;
  ba.focal_prior_log = p->in->prior_log_focal;
  ba.fix_first_focal = !p->focal_observable;
  ba.use_depth = p->has_translation;
  ba.max_iterations = opt.ba_iterations;
  ba.num_threads = opt.num_threads;
  if (p->in->stills) ba.scale_weight = kStillsScaleWeight;
  const auto& kf = p->keyframes;
  const auto& cams = p->cams;
  p->scale_pinned =
      p->n >= 2 && kf[0].fixed && kf[1].fixed && (cams[1].center - cams[0].center).norm() > 1e-9;
  if (!p->has_translation || p->scale_pinned) return;
  for (int i = 1; i < p->n; ++i) {
    if (!HasTranslation(kf[i].model)) continue;
    const double d = (cams[i].center - cams[i - 1].center).norm();
    if (d > 1e-9) {
      ba.scale_a = i - 1;
      ba.scale_b = i;
      ba.scale_distance = d;
    }
    break;
  }
}

// The shot's first window, and it calibrates the focal. Not a later window
// that calibrates it for the first time: its held lead-in was solved at the
// old focal and stays, so a chain rebuilt at another focal would contradict it.
bool FirstWindowCalibratesFocal(const WindowInput& in, bool focal_observable) {
  const auto& kf = in.keyframes;
  if (in.focal_observed || !focal_observable || kf.size() < 2) return false;
  return kf[0].pos == 0 && !kf[1].fixed;
}

bool StartAtBestFocal(WindowProblem* p);

WindowProblem SetUpWindow(const WindowInput& in, const WindowOptions& opt) {
  WindowProblem p;
  p.in = &in;
  p.opt = &opt;
  p.n = static_cast<int>(in.keyframes.size());
  p.keyframes = in.keyframes;
  const std::vector<MotionModel> labels = PromoteShortRuns(in.keyframes);
  for (int i = 0; i < p.n; ++i) p.keyframes[i].model = labels[i];
  for (int i = 1; i < p.n; ++i) {
    p.has_translation |= HasTranslation(p.keyframes[i].model);
    p.has_general |= p.keyframes[i].model == MotionModel::kGeneral && !p.keyframes[i].fixed;
  }
  p.focal_observable = FocalObservable(in, opt.min_rotation_for_focal_deg);
  p.recalibrate_lead_in = p.focal_observable && !in.focal_observed && in.frames_written;
  p.lead_in_log_focal = in.keyframes[0].cam.log_focal;
  const std::optional<double> shift = InitialFocalShift(in, p.recalibrate_lead_in);
  if (shift)
    for (auto& k : p.keyframes) k.cam.log_focal += *shift;
  while (p.held + 1 < p.n && p.keyframes[p.held + 1].fixed) ++p.held;
  PlaceJumpKeyframes(&p);
  ChooseWindowPoints(&p);
  p.cams = WindowCameras(p.keyframes, false, p.recalibrate_lead_in);
  InitPoints(p, p.cams, &p.points, &p.obs);
  SetSolveOptions(&p);
  // The tight track cut is for windows with parallax throughout: where a
  // few intervals among rotation read as general (the blur of a whip pan),
  // the tracks' RMS is mostly tracking noise, as without translation.
  int translating = 0, free_keyframes = 0;
  for (int i = 1; i < p.n; ++i) {
    if (p.keyframes[i].fixed) continue;
    ++free_keyframes;
    translating += HasTranslation(p.keyframes[i].model);
  }
  p.mostly_translating = p.has_translation && 2 * translating >= free_keyframes;
  // Not again in the re-solve with revised labels: it starts from the first
  // solve's keyframes. Not where few intervals translate: there a pair read
  // as translating is most often blur among a pan, the freedom test's to
  // judge, and the rotation pairs calibrate the focal.
  if (p.mostly_translating && !in.labels_revised && FirstWindowCalibratesFocal(in, p.focal_observable) &&
      StartAtBestFocal(&p)) {
    p.cams = WindowCameras(p.keyframes, false, p.recalibrate_lead_in);
    InitPoints(p, p.cams, &p.points, &p.obs);
    SetSolveOptions(&p);
  }
  return p;
}

std::vector<BaCamera> CamerasOf(const WindowProblem& p, bool zoom_in_general,
                                const std::vector<MotionModel>* labels = nullptr) {
  return WindowCameras(p.keyframes, zoom_in_general, p.recalibrate_lead_in, labels);
}

// Every solve drops what the fit cannot explain and polishes (robust_bundle.h).
Candidate SolveFromWith(const WindowProblem& p, const BaOptions& ba, std::vector<BaCamera> init) {
  Candidate c;
  c.cams = std::move(init);
  InitPoints(p, c.cams, &c.pts, &c.ob);
  c.summary = SolveDroppingOutliers(ba, &c.cams, &c.pts, &c.ob);
  return c;
}

Candidate SolveFrom(const WindowProblem& p, std::vector<BaCamera> init) { return SolveFromWith(p, p.ba, std::move(init)); }

// The shot's first calibrating window with translation: the constant-focal
// solve from the two-view chain rebuilt at a few focal lengths, on their own
// threads (focal_search.h); the keyframes start from the best solve (the
// chain rebuilt at the prior too: its least-squares fits on every match
// start the solve better than the two-view selection's). Also
// where rotation pairs gave a focal: among translating intervals a pair read
// as a rotation is often a short move whose parallax biased that fit.
// Returns whether a start was solved.
bool StartAtBestFocal(WindowProblem* p) {
  const std::vector<double> shifts = FocalStartShifts();
  // Half the iterations: the basin a start falls in shows early, and the
  // start taken is solved in full after.
  BaOptions ba = p->ba;
  ba.max_iterations = std::max(1, ba.max_iterations / 2);
  std::vector<std::future<Candidate>> solves;
  for (double shift : shifts) {
    std::vector<WindowKeyframe> kf = p->keyframes;
    const std::vector<BaCamera> chain = ChainAtFocal(kf, shift, p->in->outlier_tracks, p->in->scene_depth);
    for (int i = 0; i < p->n; ++i) kf[i].cam = chain[i];
    solves.push_back(std::async(std::launch::async, SolveFromWith, std::cref(*p), std::cref(ba),
                                WindowCameras(kf, false, p->recalibrate_lead_in)));
  }
  std::vector<Candidate> solved;
  std::vector<std::vector<double>> errors;
  for (auto& f : solves) {
    solved.push_back(f.get());
    const Candidate& c = solved.back();
    errors.push_back(c.summary.success ? ObservationErrors(c.cams, c.pts, p->obs, true)
                                       : std::vector<double>(p->obs.size(), HUGE_VAL));
  }
  const int best = BestFocalStart(errors, p->opt->noise_floor);
  if (!solved[best].summary.success) return false;
  p->chain_focal_shift = shifts[best];
  for (int i = 0; i < p->n; ++i) {
    p->keyframes[i].cam.world_from_cam = solved[best].cams[i].world_from_cam;
    p->keyframes[i].cam.center = solved[best].cams[i].center;
    p->keyframes[i].cam.log_focal = solved[best].cams[i].log_focal;
  }
  return true;
}

// The window without the freedoms under test: bearings (the solve ignores
// the points' inverse depth), no scale gauge.
Candidate SolveWithoutFreedoms(const WindowProblem& p, std::vector<BaCamera> cams) {
  Candidate r;
  r.cams = std::move(cams);
  r.pts = p.points;
  r.ob = p.obs;
  BaOptions bearings = p.ba;
  bearings.use_depth = false;
  bearings.scale_a = bearings.scale_b = -1;
  r.summary = SolveDroppingOutliers(bearings, &r.cams, &r.pts, &r.ob);
  return r;
}

std::vector<double> BlurSigmasOf(const WindowProblem& p) {
  std::vector<int> frame_of_camera(p.n);
  for (int i = 0; i < p.n; ++i) frame_of_camera[i] = p.keyframes[i].pos;
  return BlurSigmas(p.obs, frame_of_camera, p.opt->blur_noise_per_speed);
}

WindowCandidate CandidateReport(const std::string& test, const std::string& name, const BaSummary& s,
                                double score, bool chosen) {
  WindowCandidate c;
  c.test = test;
  c.name = name;
  c.solved = s.success;
  c.score = score;
  c.chosen = chosen;
  c.ba = s;
  return c;
}

// The freedom test (window_freedoms.h): true when the freedoms pay for
// themselves (or the test could not run).
bool FreedomsPayOff(const WindowProblem& p, const Candidate& with, const Candidate& without,
                    const FreedomTestPlan& plan, WindowReport* report) {
  if (!with.summary.success || !without.summary.success) return true;
  const FreedomEvidence ev = CompareFreedoms(with.cams, with.pts, without.cams, without.pts, p.obs,
                                             plan.drop_translation, plan.drop_zoom, p.opt->noise_floor,
                                             BlurSigmasOf(p));
  bool pays_off = ev.PaysOff();
  if (ev.translation_dropped == 0 && ev.zoom_dropped > 0) {  // a test of the zoom alone
    ZoomDecision d{"freedoms", ev.chi2_without - ev.chi2_with, ev.penalty, pays_off, ev.zoom_change};
    if (PreferNoZoom(d)) pays_off = d.zoom_taken = false;
    report->zoom_decisions.push_back(d);
  }
  report->candidates.push_back(
      CandidateReport("freedoms", "with", with.summary, ev.chi2_with + ev.penalty, pays_off));
  report->candidates.push_back(CandidateReport("freedoms", "without", without.summary, ev.chi2_without, !pays_off));
  return pays_off;
}

// The other way (window_freedoms.h): intervals labelled as a zoom without
// translation in a window with translation (the slow start of a forward
// dolly read as a zoom by a pair of frames) become general if that pays for
// itself over the window. Not `rotation` ones: next to a whip pan's blur
// read as translation they would take that translation too. Returns the
// promoted labels when it pays, else an empty vector.
std::vector<MotionModel> PromotionPaysOff(const WindowProblem& p, const Candidate& current, WindowReport* report) {
  int promoted = 0;
  std::vector<MotionModel> labels = PromotionLabels(p.keyframes, &promoted);
  if (promoted == 0) return {};
  const Candidate c = SolveFrom(p, CamerasOf(p, false, &labels));
  if (!c.summary.success) return {};
  const PromotionEvidence ev = ComparePromotion(c.cams, c.pts, current.cams, current.pts, p.obs, promoted,
                                                p.opt->noise_floor, BlurSigmasOf(p));
  std::vector<char> promoted_intervals(labels.size());
  for (size_t i = 0; i < labels.size(); ++i) promoted_intervals[i] = labels[i] != p.keyframes[i].model;
  const ZoomDecision d{"promotion", ev.chi2_current - ev.chi2_promoted, ev.penalty, !ev.PaysOff(),
                       TotalLogZoom(current.cams, promoted_intervals)};
  report->zoom_decisions.push_back(d);
  report->candidates.push_back(
      CandidateReport("promotion", "current", current.summary, ev.chi2_current, d.zoom_taken));
  report->candidates.push_back(
      CandidateReport("promotion", "promoted", c.summary, ev.chi2_promoted + ev.penalty, !d.zoom_taken));
  if (d.zoom_taken) return {};
  return labels;
}

// A window labelled without translation whose intervals zoom, solved again
// as a dolly at a fixed lens (dolly_or_zoom.h): a slow push-in reads as a
// zoom between two keyframes, its parallax adds up over the window. The
// dolly is solved from the zoom solution turned into forward moves.
Candidate SolveAsDolly(const WindowProblem& p, const Candidate& zoom, const std::vector<MotionModel>& labels) {
  BaOptions ba = p.ba;
  ba.use_depth = true;
  ba.scale_a = ba.scale_b = -1;
  // Half the iterations, as the focal starts: the test needs the basin,
  // and a dolly taken is solved in full from there.
  ba.max_iterations = std::max(1, ba.max_iterations / 2);
  Candidate c;
  c.cams = DollyStart(CamerasOf(p, false, &labels), zoom.cams, p.held, p.in->scene_depth);
  for (int i = p.held + 1; i < p.n; ++i) {
    const double d = (c.cams[i].center - c.cams[i - 1].center).norm();
    if (!HasTranslation(labels[i]) || !(d > 1e-9)) continue;
    ba.scale_a = i - 1;  // the scale gauge, as in a translating window's first solve
    ba.scale_b = i;
    ba.scale_distance = d;
    break;
  }
  if (ba.scale_a < 0) return c;  // nothing moves: no dolly to fit
  InitWindowPoints(c.cams, p.window_tracks, p.tracks_at, true, 0.2 / p.in->scene_depth, &c.pts, &c.ob);
  c.summary = SolveDroppingOutliers(ba, &c.cams, &c.pts, &c.ob);
  return c;
}

// The dolly-or-zoom test: the dolly's labels and solve when the dolly pays
// for itself by BIC, else nothing (the zoom stays).
std::optional<std::pair<std::vector<MotionModel>, Candidate>> DollyPaysOff(const WindowProblem& p,
                                                                         const Candidate& zoom,
                                                                         WindowReport* report) {
  std::vector<MotionModel> labels = DollyLabels(p.keyframes);
  if (labels.empty()) return std::nullopt;
  Candidate dolly = SolveAsDolly(p, zoom, labels);
  if (!dolly.summary.success) return std::nullopt;
  std::vector<MotionModel> zoom_labels;
  for (const auto& k : p.keyframes) zoom_labels.push_back(k.model);
  const BicComparison b = CompareByBic(ObservationErrors(dolly.cams, dolly.pts, p.obs, true),
                                       ObservationErrors(zoom.cams, zoom.pts, p.obs, false),
                                       DollyExtraParameters(zoom_labels, labels, p.obs), p.opt->noise_floor,
                                       BlurSigmasOf(p));
  const std::vector<char> every_point(dolly.pts.size(), 1);
  const double relief = DepthRelief(InverseDepthsIn(dolly.cams[p.held], dolly.pts, every_point));
  const bool dolly_pays_off = b.GeneralPaysOff() && relief >= kMinDollyRelief;
  report->zoom_decisions.push_back(
      {"dolly_or_zoom", b.chi2_simpler - b.chi2_general, b.penalty, !dolly_pays_off, TotalLogZoom(zoom.cams), relief});
  const bool is_dolly = dolly_pays_off;
  report->candidates.push_back(CandidateReport("dolly_or_zoom", "zoom", zoom.summary, b.chi2_simpler, !is_dolly));
  report->candidates.push_back(
      CandidateReport("dolly_or_zoom", "dolly", dolly.summary, b.chi2_general + b.penalty, is_dolly));
  report->candidates.back().depth_relief = relief;
  if (!is_dolly) return std::nullopt;
  return std::make_pair(std::move(labels), std::move(dolly));
}

// Occlusion-order votes (occlusion_order.h) of candidate reconstructions:
// the window's frames give the events, each candidate's cameras the depths.
std::vector<OcclusionVotes> OcclusionVotesOf(const WindowProblem& p,
                                             const std::vector<const std::vector<BaCamera>*>& candidates) {
  const int n = p.n;
  std::vector<OcclusionVotes> votes(candidates.size());
  if (n < 2) return votes;
  // Every frame of the window, each with the last keyframe at or before it
  // as depth reference.
  std::vector<const KeyframeTracks*> frames;
  std::vector<int> frame_keyframe;
  int k = 0;
  const int first = p.keyframes.front().pos;
  for (int pos = first; pos <= p.keyframes.back().pos; ++pos) {
    while (k + 1 < n && p.keyframes[k + 1].pos <= pos) ++k;
    frames.push_back(p.in->frames[pos - first]);
    frame_keyframe.push_back(k);
  }
  const OcclusionOptions opt;
  const std::vector<OcclusionEvent> events = FindOcclusionEvents(
      frames, frame_keyframe, Eigen::Vector2d(0.5, 0.5 * p.in->height / p.in->width), opt);
  std::map<long, KeyframeTrack> tracks;
  for (int i = 0; i < n; ++i)
    for (const auto& [id, u] : *p.keyframes[i].tracks) tracks[id].push_back({i, u});
  for (size_t c = 0; c < candidates.size(); ++c) votes[c] = CountOcclusionVotes(*candidates[c], tracks, events, opt);
  return votes;
}

// The points the plane prior searches a floor among, under a solution:
// every track seen by >= 2 keyframes, triangulated and kept where it
// explains them to 1.5 px (the window's points are mostly its longest
// tracks, and a floor's leave the view soonest).
PlanePointsFn PlanePointsOf(const WindowProblem& p) {
  const WindowTracks every_track =
      SelectWindowPoints(p.tracks_at, p.in->outlier_tracks, kMaxPlanePoints, p.opt->point_grid_cells);
  const double cut = 1.5 * p.ba.huber_scale;
  const std::vector<const KeyframeTracks*> tracks_at = p.tracks_at;
  const int held = p.held;
  return [=](const std::vector<BaCamera>& c) {
    std::vector<BaPoint> pts;
    std::vector<BaObservation> o;
    InitWindowPoints(c, every_track, tracks_at, true, 0.0, &pts, &o);
    std::vector<char> rigid(pts.size(), 1);
    const std::vector<double> e = ObservationErrors(c, pts, o, true);
    for (size_t i = 0; i < o.size(); ++i)
      if (!(e[i] <= cut)) rigid[o[i].point] = 0;
    return InverseDepthsIn(c[held], pts, rigid);
  };
}

// Points of the plane prior's support under each candidate (0: no plane
// parallel to the move).
std::vector<int> PlaneSupportOf(const WindowProblem& p, const std::vector<const std::vector<BaCamera>*>& candidates) {
  const PlanePointsFn plane_points = PlanePointsOf(p);
  std::vector<int> support;
  for (const auto* c : candidates) {
    const std::optional<PlaneShift> s = ShiftForMotionPlane(*c, p.held, plane_points(*c));
    support.push_back(s ? s->inliers : 0);
  }
  return support;
}

// Along the optical axis the fit cannot tell the dolly/zoom branches apart:
// the occlusion order can (occlusion_order.h), or without occlusion events
// the floor (plane_prior.h: on the wrong branch it cannot be parallel to the
// move). Either rules out a branch, never a candidate on the branch it
// supports (RuledOutOtherBranch): there the window's BIC decides whether the
// focal changes. [0]: the constant-focal solve, [c + 1]: zoomed[c]. Returns
// whether the occlusion order decided.
bool RuleOutBranches(const WindowProblem& p, const Candidate& constant, const std::vector<Candidate>& zoomed,
                     std::vector<char>* ruled_out, std::vector<WindowCandidate>* reports) {
  std::vector<const std::vector<BaCamera>*> candidate_cams{&constant.cams};
  for (const Candidate& c : zoomed) candidate_cams.push_back(&c.cams);
  const std::vector<OcclusionVotes> votes = OcclusionVotesOf(p, candidate_cams);
  std::vector<int> direction;
  for (const auto* c : candidate_cams) direction.push_back(AxialDirection(*c, p.held));
  std::vector<double> z;
  for (const auto& v : votes) z.push_back(v.Z());
  *ruled_out = RuledOutOtherBranch(ContradictedByOcclusion(votes), direction, z);
  bool by_occlusion = false;
  for (char r : *ruled_out) by_occlusion |= r;
  for (size_t c = 0; c < reports->size() && c < votes.size(); ++c) {
    (*reports)[c].occlusion_agree = votes[c].agree;
    (*reports)[c].occlusion_disagree = votes[c].disagree;
  }
  if (!by_occlusion && p.opt->motion_plane_prior) {
    const std::vector<int> support = PlaneSupportOf(p, candidate_cams);
    *ruled_out = RuledOutOtherBranch(ContradictedByPlane(support), direction,
                                     std::vector<double>(support.begin(), support.end()));
    for (size_t c = 0; c < reports->size() && c < support.size(); ++c) (*reports)[c].plane_support = support[c];
  }
  return by_occlusion;
}

// The first and last keyframe's focal of a candidate, for the report.
void RecordFocal(const WindowProblem& p, const std::vector<BaCamera>& cams, WindowCandidate* report) {
  report->focal_first_px = std::exp(cams.front().log_focal) * p.in->width;
  report->focal_last_px = std::exp(cams.back().log_focal) * p.in->width;
}

// The other branch of the axial dolly/zoom ambiguity (axial_ambiguity.h),
// from the constant-focal solution with the zoom variant's sharing.
Candidate SolveMirroredBranch(const WindowProblem& p, const Candidate& constant,
                              const std::vector<BaCamera>& zoom_cams) {
  std::vector<BaCamera> solved = zoom_cams;
  for (int i = 0; i < p.n; ++i) {
    solved[i].world_from_cam = constant.cams[i].world_from_cam;
    solved[i].center = constant.cams[i].center;
    solved[i].log_focal = constant.cams[i].log_focal;
  }
  std::vector<std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>> matches(p.n);
  for (int k = p.held + 1; k < p.n; ++k) {
    const KeyframeTracks& before = *p.keyframes[k - 1].tracks;
    for (const auto& [id, u] : *p.keyframes[k].tracks) {
      auto it = before.find(id);
      if (it != before.end()) matches[k].push_back({it->second, u});
    }
  }
  return SolveFrom(p, MirroredAxialBranch(solved, p.held, matches));
}

// The focal choice's zoom decision (zoom_evidence.h): the constant focal
// against the best candidate not ruled out, the zoom it adds in the general
// intervals; a zoom taken without deciding it clearly is given up
// (scores->best = -1). None when every candidate is ruled out.
void RecordFocalDecision(const WindowProblem& p, FocalCandidateScores* scores, const std::vector<char>& ruled_out,
                         const std::vector<Candidate>& zoomed, WindowReport* report) {
  const FocalCandidateScores& s = *scores;
  int best = -1;
  for (size_t c = 0; c < s.chi2.size() && c < zoomed.size(); ++c)
    if (!(c + 1 < ruled_out.size() && ruled_out[c + 1]) && (best < 0 || s.chi2[c] < s.chi2[best]))
      best = static_cast<int>(c);
  if (best < 0) return;
  std::vector<char> general(p.n, 0);
  for (int i = 1; i < p.n; ++i) general[i] = p.keyframes[i].model == MotionModel::kGeneral && !p.keyframes[i].fixed;
  ZoomDecision d{"focal", s.chi2_constant - s.chi2[best], s.penalty, s.best >= 0,
                 TotalLogZoom(zoomed[best].cams, general)};
  d.decided_by_cue = !ruled_out.empty() && ruled_out[0];
  if (PreferNoZoom(d)) {
    scores->best = -1;
    d.zoom_taken = false;
  }
  report->zoom_decisions.push_back(d);
}

// Along the axis, where no cue ruled a branch out, the fit chose the branch:
// how clearly (ZoomDecision "branch") against the best reading of the other
// branch, and where it cannot tell, the reading with less zoom
// (PreferOtherBranch). `constant_cams`: candidate 0, zoomed[c]: c + 1;
// `votes[c]`: candidate c's report with its occlusion votes.
void RecordBranchDecision(const WindowProblem& p, FocalCandidateScores* scores, const std::vector<char>& ruled_out,
                          const std::vector<BaCamera>& constant_cams, const std::vector<Candidate>& zoomed,
                          const std::vector<const std::vector<double>*>& errors,
                          const std::vector<WindowCandidate*>& votes, WindowReport* report) {
  FocalCandidateScores& s = *scores;
  std::vector<char> general(p.n, 0);
  for (int i = 1; i < p.n; ++i) general[i] = p.keyframes[i].model == MotionModel::kGeneral && !p.keyframes[i].fixed;
  auto cams_of = [&](int c) -> const std::vector<BaCamera>& { return c == 0 ? constant_cams : zoomed[c - 1].cams; };
  auto score_of = [&](int c) { return c == 0 ? s.chi2_constant : s.chi2[c - 1] + s.penalty; };
  auto zoom_of = [&](int c) { return c == 0 ? 0.0 : TotalLogZoom(zoomed[c - 1].cams, general); };
  const int taken = s.best + 1;
  const int direction = AxialDirection(cams_of(taken), p.held);
  int other = -1;
  for (int c = 0; c <= static_cast<int>(zoomed.size()) && c <= static_cast<int>(s.chi2.size()); ++c) {
    const bool out = c < static_cast<int>(ruled_out.size()) && ruled_out[c];
    const int d = AxialDirection(cams_of(c), p.held);
    if (!out && d != 0 && d != direction && (other < 0 || score_of(c) < score_of(other))) other = c;
  }
  if (direction == 0 || other < 0) return;
  ZoomDecision d{"branch", score_of(other) - score_of(taken), s.penalty, taken > 0, zoom_of(taken)};
  std::vector<int> point_of_obs;
  for (const BaObservation& o : p.obs) point_of_obs.push_back(o.point);
  d.fit_z = TrackPairedZ(*errors[taken], *errors[other], point_of_obs, s.sigma);
  auto count = [&](int c, bool agree) {  // -1: not counted
    if (c >= static_cast<int>(votes.size())) return 0;
    return std::max(0, agree ? votes[c]->occlusion_agree : votes[c]->occlusion_disagree);
  };
  const double z = PairedBranchZ(count(taken, true), count(taken, false), count(other, true), count(other, false));
  auto floor_of = [&](int c) { return c < static_cast<int>(votes.size()) ? votes[c]->plane_support : 0; };
  if (PreferOtherBranch(d, zoom_of(other), z, floor_of(taken), floor_of(other))) {
    s.best = other - 1;
    d.zoom_taken = other > 0;
  }
  report->zoom_decisions.push_back(d);
}

// BIC: does a per-keyframe focal in the general intervals pay for itself?
// Candidates: the per-keyframe-focal solve from the two-view chain (solving
// on another thread) and, along the optical axis, from the other branch of
// the dolly/zoom ambiguity. Replaces `chosen` (the constant-focal solve) by
// the winner.
void ChooseWindowFocal(const WindowProblem& p, std::future<Candidate>* from_chain,
                       const std::vector<BaCamera>& zoom_cams, Candidate* chosen, WindowReport* report) {
  const bool axial = IsAxialMotion(chosen->cams, p.held);
  Candidate mirrored;  // solved here while the chain's candidate may still be solving
  if (axial) mirrored = SolveMirroredBranch(p, *chosen, zoom_cams);
  std::vector<Candidate> zoomed;
  std::vector<WindowCandidate> reports{CandidateReport("focal", "constant_focal", chosen->summary, 0, false)};
  Candidate chain = from_chain->get();
  reports.push_back(CandidateReport("focal", "per_keyframe_focal", chain.summary, 0, false));
  if (chain.summary.success) zoomed.push_back(std::move(chain));
  if (axial) {
    reports.push_back(CandidateReport("focal", "mirrored_branch", mirrored.summary, 0, false));
    if (mirrored.summary.success) zoomed.push_back(std::move(mirrored));
  }
  std::vector<WindowCandidate*> solved_reports{&reports[0]};  // [c + 1]: zoomed[c]'s
  for (size_t r = 1; r < reports.size(); ++r)
    if (reports[r].solved) solved_reports.push_back(&reports[r]);
  for (size_t c = 0; c < solved_reports.size(); ++c)
    RecordFocal(p, c == 0 ? chosen->cams : zoomed[c - 1].cams, solved_reports[c]);
  std::vector<char> ruled_out(zoomed.size() + 1, 0);
  if (axial) {
    std::vector<WindowCandidate> branch(solved_reports.size());
    report->branch_by_occlusion = RuleOutBranches(p, *chosen, zoomed, &ruled_out, &branch);
    for (size_t c = 0; c < branch.size(); ++c) {
      solved_reports[c]->occlusion_agree = branch[c].occlusion_agree;
      solved_reports[c]->occlusion_disagree = branch[c].occlusion_disagree;
      solved_reports[c]->plane_support = branch[c].plane_support;
    }
  }
  // Every candidate is scored on all observations (capped), with one sigma.
  std::vector<std::vector<double>> ez;
  for (const Candidate& c : zoomed) ez.push_back(ObservationErrors(c.cams, c.pts, p.obs, true));
  int extra = 0;
  for (int i = 1; i < p.n; ++i) extra += p.keyframes[i].model == MotionModel::kGeneral && !p.keyframes[i].fixed;
  const std::vector<double> e_constant = ObservationErrors(chosen->cams, chosen->pts, p.obs, true);
  FocalCandidateScores s = ScoreFocalCandidates(e_constant, ez, ruled_out, extra, p.opt->noise_floor);
  RecordFocalDecision(p, &s, ruled_out, zoomed, report);  // may give up an undecided zoom
  std::vector<const std::vector<double>*> errors{&e_constant};  // [c + 1]: zoomed[c]'s
  for (const auto& e : ez) errors.push_back(&e);
  if (axial) RecordBranchDecision(p, &s, ruled_out, chosen->cams, zoomed, errors, solved_reports, report);
  for (size_t c = 0; c < solved_reports.size(); ++c) {
    solved_reports[c]->ruled_out = c < ruled_out.size() && ruled_out[c];
    solved_reports[c]->score = c == 0 ? s.chi2_constant : s.chi2[c - 1] + s.penalty;
    solved_reports[c]->chosen = static_cast<int>(c) == s.best + 1;
  }
  if (s.best >= 0) {
    *chosen = std::move(zoomed[s.best]);
    report->zoom_by_bic = true;
    report->model = solved_reports[s.best + 1]->name;
  }
  for (auto& r : reports) report->candidates.push_back(std::move(r));
}

// Every point's RMS over all its observations after the cut, and whether it
// was kept ("track_rms" records, for diagnostics).
void RecordTrackRms(const WindowProblem& p, const Candidate& c, Diagnostics* diagnostics) {
  const auto errs = ObservationErrors(c.cams, c.pts, p.obs, p.ba.use_depth);
  std::vector<double> sq(c.pts.size(), 0);
  std::vector<int> cnt(c.pts.size(), 0), kept(c.pts.size(), 0);
  for (size_t i = 0; i < p.obs.size(); ++i) {
    sq[p.obs[i].point] += errs[i] * errs[i];
    ++cnt[p.obs[i].point];
  }
  for (const auto& ob : c.ob) kept[ob.point] = 1;
  nlohmann::json tracks = nlohmann::json::array();
  for (const auto& [id, k] : p.window_tracks.point_of_track)
    if (cnt[k]) tracks.push_back({{"track", id}, {"rms_px", std::sqrt(sq[k] / cnt[k]) * kReferenceWidthPx}, {"kept", kept[k] != 0}});
  Record(diagnostics, "track_rms", {{"first_frame", p.in->first_frame}, {"tracks", std::move(tracks)}});
}

// After the model choice (the comparison needs the same tracks in every
// candidate, and the tracks in front of a dolly-zoom subject are the cue).
// About a quarter of the KLT tracks near silhouettes are corners formed by
// a silhouette against the background (occlusion edges): they move
// smoothly, pass every frame-to-frame check and stay within a pixel or two
// of *some* rigid point, and they are the longest tracks, so they make up
// half of the points a window picks. Their shared bias bends the window
// along the rotation/translation ambiguity. Residuals of a track are
// systematic, so a track's RMS is the test, not single observations.
void RejectTracks(const WindowProblem& p, Candidate* c, Diagnostics* diagnostics) {
  const WindowOptions& opt = *p.opt;
  const double cut_px = p.mostly_translating ? opt.track_rms_cut_px : opt.track_rms_cut_rotation_px;
  DropBadTracks(p.ba, cut_px, &c->cams, &c->pts, p.obs, &c->ob, &c->summary);
  if (Wants(diagnostics, "track_rms")) RecordTrackRms(p, *c, diagnostics);
}

// Each observation's age in frames since its point's first observation in
// the window (track_drift.h).
std::vector<int> AgesOf(const WindowProblem& p, const std::vector<BaObservation>& ob) {
  std::vector<int> pos(p.n);
  for (int i = 0; i < p.n; ++i) pos[i] = p.keyframes[i].pos;
  return ObservationAges(ob, pos);
}

// A KLT track's drift grows with the frames it has been followed
// (track_drift.h). Measured on the solve before the whole-track cut: the
// cut keeps the tracks a rigid point explains to 0.2 px, and whatever drift
// they share the fit has absorbed (in the focal, too), so their residuals
// no longer show it.
DriftFit MeasureDrift(const WindowProblem& p, const Candidate& c) {
  return FitDrift(ObservationErrors(c.cams, c.pts, c.ob, p.ba.use_depth), AgesOf(p, c.ob));
}

// With `apply`, where the drift measured grows with the age, the solution is
// polished with each observation weighted by its expected drift (after the
// model choice and the track cut, which compare and cut at one noise level).
// Off by default: on kitti07 it moves the focal the wrong way
// (docs/estimate.md, "Track drift weights"). The fit is recorded either way.
void WeightByDrift(const WindowProblem& p, const DriftFit& fit, bool apply, Candidate* c, Diagnostics* diagnostics) {
  const bool weighted = apply && ApplyDriftWeights(fit, AgesOf(p, c->ob), &c->ob);
  const double focal_before = c->cams.front().log_focal;
  if (weighted) PolishBundle(p.ba, &c->cams, &c->pts, c->ob, &c->summary);
  const double px = kReferenceWidthPx;  // the figures in px at 960 px width
  Record(diagnostics, "track_drift",
         {{"first_frame", p.in->first_frame}, {"observations", fit.observations},
          {"s0_px", std::sqrt(std::max(0.0, fit.s0_sq)) * px},
          {"q_px_per_sqrt_frame", std::sqrt(std::max(0.0, fit.q_sq)) * px},
          {"t_slope", fit.t_slope}, {"weighted", weighted},
          {"focal_change_pct", 100 * (c->cams.front().log_focal - focal_before)}});
}

// Along the axis the fit leaves every inverse depth open by one shift
// (axial_ambiguity.h) unless the lead-in's own move pins the depths: take
// the shift that makes a floor or wall parallel to the move (plane_prior.h).
void ApplyPlanePriorToWindow(const WindowProblem& p, Candidate* c, WindowReport* report) {
  const PlanePriorResult r = ApplyPlanePrior(p.ba, p.held, p.opt->noise_floor, PlanePointsOf(p), &c->cams,
                                             &c->pts, c->ob, &c->summary);
  report->plane_prior = r.taken;
  if (r.found)
    report->candidates.push_back(CandidateReport("plane_prior", "shifted", c->summary, r.rms_after * p.in->width,
                                                 r.taken));
}

// Per track of a profiled window ("focal_pull" records): its pull on the
// focal, the change of its squared residuals (over the window's mean square)
// from the -1 % to the +1 % shift (positive: it wants a shorter focal), where
// it starts and ends in the image and over how many frames.
nlohmann::json FocalPullOfTracks(const WindowProblem& p, const Candidate& c, const FocalProfile& prof) {
  nlohmann::json tracks = nlohmann::json::array();
  const auto& s = prof.log_shifts;
  const auto lo = std::find(s.begin(), s.end(), -0.01), hi = std::find(s.begin(), s.end(), 0.01),
             zero = std::find(s.begin(), s.end(), 0.0);
  if (lo == s.end() || hi == s.end() || zero == s.end()) return tracks;
  const auto& e_lo = prof.errors[lo - s.begin()];
  const auto& e_hi = prof.errors[hi - s.begin()];
  const auto& e0 = prof.errors[zero - s.begin()];
  const double mean_sq = SumOfFiniteSquares(e0) / std::max<size_t>(1, e0.size());
  std::map<int, long> track_of_point;
  for (const auto& [id, k] : p.window_tracks.point_of_track) track_of_point[k] = id;
  struct Pull { double d = 0; int n = 0; Eigen::Vector2d first, last; int first_cam = 1 << 30, last_cam = -1; };
  std::map<int, Pull> pulls;
  for (size_t i = 0; i < c.ob.size(); ++i) {
    if (!std::isfinite(e_lo[i]) || !std::isfinite(e_hi[i]) || !(mean_sq > 0)) continue;
    Pull& q = pulls[c.ob[i].point];
    q.d += (e_hi[i] * e_hi[i] - e_lo[i] * e_lo[i]) / mean_sq;
    ++q.n;
    if (c.ob[i].camera < q.first_cam) q.first_cam = c.ob[i].camera, q.first = c.ob[i].u;
    if (c.ob[i].camera > q.last_cam) q.last_cam = c.ob[i].camera, q.last = c.ob[i].u;
  }
  for (const auto& [k, q] : pulls)
    tracks.push_back({{"track", track_of_point[k]}, {"pull", q.d}, {"observations", q.n},
                      {"first", {q.first.x(), q.first.y()}}, {"last", {q.last.x(), q.last.y()}},
                      {"frames", p.keyframes[q.last_cam].pos - p.keyframes[q.first_cam].pos}});
  return tracks;
}

// How well the solution pins its focal ("focal_profile" records, on request:
// one solve per shift, focal_profile.h); also where the focal is held (not
// observable, or held at the prior): the profile says what the tracks want.
void RecordFocalProfile(const WindowProblem& p, const Candidate& c, Diagnostics* diagnostics) {
  const FocalProfile prof = ProfileFocal(p.ba, c.cams, c.pts, c.ob, DefaultFocalProfileShifts());
  nlohmann::json chi2 = nlohmann::json::array();
  for (double v : prof.chi2) chi2.push_back(std::isfinite(v) ? nlohmann::json(v) : nlohmann::json());
  const bool pinned = std::isfinite(prof.sigma_log_focal);
  if (Wants(diagnostics, "focal_pull"))
    Record(diagnostics, "focal_pull", {{"first_frame", p.in->first_frame}, {"tracks", FocalPullOfTracks(p, c, prof)}});
  Record(diagnostics, "focal_profile",
         {{"first_frame", p.in->first_frame},
          {"last_frame", p.keyframes.back().pos + p.in->first_frame - p.keyframes.front().pos},
          {"held_keyframes", p.held + (p.keyframes.front().fixed ? 1 : 0)},
          {"focal_px", std::exp(c.cams.front().log_focal) * p.in->width},
          {"focal_observable", p.focal_observable},
          {"observations", c.ob.size()},
          {"log_shifts", prof.log_shifts},
          {"chi2", std::move(chi2)},
          {"sigma_pct", pinned ? nlohmann::json(100 * prof.sigma_log_focal) : nlohmann::json()},
          {"minimum_pct", pinned ? nlohmann::json(100 * prof.minimum_log_shift) : nlohmann::json()}});
}

// The window's result for the caller, from the solution taken.
void FillOutcome(const WindowProblem& p, Candidate&& c, WindowOutcome* out) {
  const bool success = c.summary.success;
  out->success = success;
  out->translating = p.has_translation;
  out->focal_observable = p.focal_observable;
  out->focal_calibrated = success && p.focal_observable;
  out->keyframe_cams.resize(p.n);
  out->labels.resize(p.n);
  for (int i = 0; i < p.n; ++i) {
    out->keyframe_cams[i] = p.keyframes[i].cam;
    out->labels[i] = p.keyframes[i].model;
    if (out->report.zoom_by_bic && i > 0 && out->labels[i] == MotionModel::kGeneral && !p.keyframes[i].fixed)
      out->labels[i] = MotionModel::kGeneralZoom;
    if (!success) continue;
    out->keyframe_cams[i].world_from_cam = c.cams[i].world_from_cam;
    out->keyframe_cams[i].center = c.cams[i].center;
    out->keyframe_cams[i].log_focal = c.cams[i].log_focal;
  }
  if (success && p.recalibrate_lead_in) out->written_log_focal_shift = c.cams[0].log_focal - p.lead_in_log_focal;
  out->points = success ? std::move(c.pts) : p.points;
  // Points whose track the BA kept: the only ones the in-between frames may use.
  out->point_kept.assign(out->points.size(), success ? 0 : 1);
  if (success)
    for (const auto& o : c.ob) out->point_kept[o.point] = 1;
  out->point_of_track = p.window_tracks.point_of_track;
  out->pose_options = p.ba;
  out->rms_px = c.summary.rms_after * p.in->width;
  WindowReport& report = out->report;
  report.points = static_cast<int>(out->points.size());
  report.observations = c.summary.num_observations;
  report.rms_px = out->rms_px;
  report.ba = c.summary;
  report.labels = out->labels;
  report.points_kept = 0;
  for (char k : out->point_kept) report.points_kept += k != 0;
}

// The outcome that asks for a second solve with `labels`.
WindowOutcome Revised(const WindowProblem& p, std::vector<MotionModel> labels, WindowReport&& report) {
  WindowOutcome out;
  out.revised_labels = std::move(labels);
  for (const auto& k : p.keyframes) out.keyframe_cams.push_back(k.cam);
  out.report = std::move(report);
  return out;
}

// The same, the second solve starting from `start`'s keyframes.
WindowOutcome RevisedFrom(const WindowProblem& p, std::vector<MotionModel> labels, const Candidate& start,
                          WindowReport&& report) {
  WindowOutcome out = Revised(p, std::move(labels), std::move(report));
  for (int i = 0; i < p.n; ++i) {
    out.keyframe_cams[i].world_from_cam = start.cams[i].world_from_cam;
    out.keyframe_cams[i].center = start.cams[i].center;
    out.keyframe_cams[i].log_focal = start.cams[i].log_focal;
  }
  return out;
}

}  // namespace

std::vector<MotionModel> PromoteShortRuns(const std::vector<WindowKeyframe>& keyframes) {
  const int n = static_cast<int>(keyframes.size());
  std::vector<MotionModel> m(n);
  for (int i = 0; i < n; ++i) m[i] = keyframes[i].model;
  for (int i = 1; i < n; ++i) {
    if (keyframes[i].fixed) continue;
    for (int len = 1; len <= 2 && i + len < n; ++len) {
      const MotionModel left = m[i - 1], right = m[i + len];
      if (keyframes[i - 1].chain_start) break;  // it has no interval of its own
      bool run_same = true;
      for (int j = i; j < i + len; ++j) run_same &= m[j] == m[i];
      if (run_same && left == right && left != m[i] && IsAtLeastAsGeneral(left, m[i])) {
        for (int j = i; j < i + len; ++j) m[j] = left;
        break;
      }
    }
  }
  return m;
}

std::optional<double> InitialFocalShift(const WindowInput& in, bool recalibrate_lead_in) {
  const auto& kf = in.keyframes;
  const int n = static_cast<int>(kf.size());
  if (in.focal_observed || in.focal_samples.empty() || n == 0) return std::nullopt;
  if (!((kf[0].pos == 0 && !kf[1 < n ? 1 : 0].fixed) || recalibrate_lead_in)) return std::nullopt;
  return Median(in.focal_samples) - kf[0].cam.log_focal;
}

std::vector<BaCamera> WindowCameras(const std::vector<WindowKeyframe>& keyframes, bool zoom_in_general,
                                    bool free_lead_in_focal, const std::vector<MotionModel>* labels) {
  const int n = static_cast<int>(keyframes.size());
  std::vector<BaCamera> cams(n);
  for (int i = 0; i < n; ++i) {
    cams[i] = keyframes[i].cam;
    cams[i].fixed = keyframes[i].fixed;
    cams[i].fixed_focal = keyframes[i].fixed_focal && !free_lead_in_focal;
    cams[i].rotation_source = cams[i].center_source = cams[i].focal_source = -1;
    if (i == 0 || keyframes[i].fixed) continue;
    MotionModel m = labels ? (*labels)[i] : keyframes[i].model;
    if (zoom_in_general && m == MotionModel::kGeneral) m = MotionModel::kGeneralZoom;
    if (!HasRotation(m)) cams[i].rotation_source = i - 1;
    if (!HasTranslation(m)) cams[i].center_source = i - 1;
    if (!HasZoom(m)) cams[i].focal_source = i - 1;
  }
  // Shared blocks start from the source's value.
  for (int i = 1; i < n; ++i) {
    if (cams[i].rotation_source >= 0) cams[i].world_from_cam = cams[i - 1].world_from_cam;
    if (cams[i].center_source >= 0) cams[i].center = cams[i - 1].center;
    if (cams[i].focal_source >= 0) cams[i].log_focal = cams[i - 1].log_focal;
  }
  return cams;
}

// "Few": by frames (a fast whip makes a keyframe of every frame, a still
// part one every keyframe_max_gap frames). A pair of frames reads motion
// blur or a fade as translation, a tilt as a zoom; one depth per point
// across the window does not fit it.
FreedomTestPlan FreedomTestLabels(const std::vector<WindowKeyframe>& keyframes) {
  const int n = static_cast<int>(keyframes.size());
  FreedomTestPlan plan;
  plan.drop_translation.assign(n, 0);
  plan.drop_zoom.assign(n, 0);
  plan.labels.resize(n);
  bool has_translation = false;
  int translating_frames = 0, zooming_frames = 0, free_frames = 0;
  for (int i = 1; i < n; ++i) {
    has_translation |= HasTranslation(keyframes[i].model);
    if (keyframes[i].fixed) continue;
    const int span = keyframes[i].pos - keyframes[i - 1].pos;
    free_frames += span;
    if (HasTranslation(keyframes[i].model)) translating_frames += span;
    if (HasZoom(keyframes[i].model)) zooming_frames += span;
  }
  const bool few_translating = has_translation && 2 * translating_frames < free_frames;
  const bool few_zooming = zooming_frames > 0 && 2 * zooming_frames < free_frames;
  if (few_translating || (!has_translation && few_zooming)) {
    for (int i = 0; i < n; ++i) {
      if (keyframes[i].fixed) continue;
      plan.drop_translation[i] = HasTranslation(keyframes[i].model);
      plan.drop_zoom[i] = few_zooming && HasZoom(keyframes[i].model);
      plan.any |= plan.drop_translation[i] || plan.drop_zoom[i];
    }
  }
  for (int i = 0; i < n; ++i)
    plan.labels[i] = ReducedModel(keyframes[i].model, plan.drop_translation[i], plan.drop_zoom[i]);
  return plan;
}

std::vector<MotionModel> PromotionLabels(const std::vector<WindowKeyframe>& keyframes, int* promoted) {
  const int n = static_cast<int>(keyframes.size());
  std::vector<MotionModel> labels(n);
  *promoted = 0;
  for (int i = 0; i < n; ++i) {
    const MotionModel m = keyframes[i].model;
    const bool promote = i > 0 && !keyframes[i].fixed && HasZoom(m) && !HasTranslation(m);
    labels[i] = promote ? MotionModel::kGeneral : m;
    *promoted += promote;
  }
  return labels;
}

// The cut tightens in rounds (robust_bundle.h): cutting tight at once also
// drops the good tracks the first, bent solution puts far.
void DropBadTracks(const BaOptions& ba, double cut_px, std::vector<BaCamera>* cams, std::vector<BaPoint>* points,
                   const std::vector<BaObservation>& all, std::vector<BaObservation>* kept, BaSummary* summary) {
  DropInconsistentTracks(ba, cut_px / kReferenceWidthPx, cams, points, all, kept, summary);  // normalised units
}

WindowOutcome SolveWindow(const WindowInput& in, const WindowOptions& opt, Diagnostics* diagnostics) {
  StageClock clock;
  WindowReport report;
  report.shot = in.shot;
  report.keyframes = static_cast<int>(in.keyframes.size());
  report.first_frame = in.first_frame;
  report.labels_revised = in.labels_revised;
  const WindowProblem p = SetUpWindow(in, opt);
  report.focal_observable = p.focal_observable;
  report.chain_focal_shift = p.chain_focal_shift;
  report.timings_s.emplace_back("setup", clock.Lap());
  const bool test_labels = opt.freedom_test && !in.labels_revised;
  const FreedomTestPlan plan = test_labels ? FreedomTestLabels(p.keyframes) : FreedomTestPlan{};
  std::future<Candidate> without_freedoms;
  if (plan.any)
    without_freedoms = std::async(std::launch::async, SolveWithoutFreedoms, std::cref(p), CamerasOf(p, false, &plan.labels));
  // General windows: the per-keyframe-focal solve from the two-view chain
  // does not depend on the constant-focal one, so it runs beside it (after
  // tracking has ended the last window is the whole critical path).
  const std::vector<BaCamera> zoom_cams = p.has_general ? CamerasOf(p, true) : std::vector<BaCamera>{};
  std::future<Candidate> zoom_from_chain;
  if (p.has_general) zoom_from_chain = std::async(std::launch::async, SolveFrom, std::cref(p), zoom_cams);
  Candidate chosen{p.cams, p.points, p.obs, {}};
  chosen.summary = SolveDroppingOutliers(p.ba, &chosen.cams, &chosen.pts, &chosen.ob);
  report.timings_s.emplace_back("constant_focal_solve", clock.Lap());
  if (without_freedoms.valid() && !FreedomsPayOff(p, chosen, without_freedoms.get(), plan, &report)) {
    if (zoom_from_chain.valid()) zoom_from_chain.get();  // wait, discard
    return Revised(p, plan.labels, std::move(report));
  }
  if (test_labels && !p.has_translation && chosen.summary.success) {
    auto dolly = DollyPaysOff(p, chosen, &report);
    report.timings_s.emplace_back("dolly_or_zoom", clock.Lap());
    if (dolly) return RevisedFrom(p, std::move(dolly->first), dolly->second, std::move(report));
  }
  if (test_labels && p.has_translation && chosen.summary.success) {
    std::vector<MotionModel> promoted = PromotionPaysOff(p, chosen, &report);
    report.timings_s.emplace_back("label_tests", clock.Lap());
    if (!promoted.empty()) {
      if (zoom_from_chain.valid()) zoom_from_chain.get();  // wait, discard
      return Revised(p, std::move(promoted), std::move(report));
    }
  }
  if (zoom_from_chain.valid() && !chosen.summary.success) zoom_from_chain.get();  // wait, discard
  if (chosen.summary.success && p.has_general) ChooseWindowFocal(p, &zoom_from_chain, zoom_cams, &chosen, &report);
  report.timings_s.emplace_back("model_choice", clock.Lap());
  // Not along the optical axis: there the tracks in front of the subject are
  // the only cue between the two branches of the dolly/zoom ambiguity, and
  // the branch not taken leaves them with the largest residuals. Unless the
  // occlusion order chose the branch: then the residuals are not the cue.
  // Not in a shot of stills: its links are descriptor matches, which do not
  // accumulate drift.
  const bool drift_measured = chosen.summary.success && !in.stills &&
                              (opt.drift_weights || Wants(diagnostics, "track_drift"));
  const DriftFit drift = drift_measured ? MeasureDrift(p, chosen) : DriftFit{};
  if (chosen.summary.success &&
      (report.branch_by_occlusion || !(p.has_translation && IsAxialMotion(chosen.cams, p.held))))
    RejectTracks(p, &chosen, diagnostics);
  if (drift_measured) WeightByDrift(p, drift, opt.drift_weights, &chosen, diagnostics);
  report.timings_s.emplace_back("track_rejection", clock.Lap());
  // After every other polish: the focal smoothness prior, the only term
  // that is not flat along the shift, would pull the solve back towards
  // where it started.
  if (chosen.summary.success && report.zoom_by_bic && !p.scale_pinned && opt.motion_plane_prior &&
      IsAxialMotion(chosen.cams, p.held))
    ApplyPlanePriorToWindow(p, &chosen, &report);
  if (chosen.summary.success && Wants(diagnostics, "focal_profile"))
    RecordFocalProfile(p, chosen, diagnostics);
  WindowOutcome out;
  out.report = std::move(report);
  FillOutcome(p, std::move(chosen), &out);
  out.report.timings_s.emplace_back("plane_prior", clock.Lap());
  return out;
}

}  // namespace hapcine
