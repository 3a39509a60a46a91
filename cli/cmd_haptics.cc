// `hapcine haptics`: camera path (or video) -> haptic track (+ optional .hjif).
// A thin mapping of flags onto HapticOptions; the work is in haptics/.


#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/cmd_haptics_platform.h"
#include "cli/command.h"
#include "cli/option_checks.h"
#include "core/atomic_file.h"
#include "core/camera_path.h"
#include "core/error.h"
#include "core/output_files.h"
#include "core/progress.h"
#include "core/haptic_track.h"
#include "core/input_file.h"
#include "estimate/camera_estimator.h"
#include "haptics/confidence.h"
#include "haptics/haptic_models.h"
#include "haptics/camera_signals.h"
#include "haptics/effect_classifier.h"
#include "haptics/hjif_export.h"
#include "haptics/keyframes.h"
#include "haptics/seat_geometry.h"
#include "platform/platform_config.h"

namespace hapcine::cli {
namespace {

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

namespace {

// The washout options (docs/haptics.md, "Washout and film safety").
void AddWashoutOptions(CLI::App& app, WashoutOptions* w, std::string* washout, bool* no_washout) {
  app.add_option("--washout", *washout,
                 "cinematic: adaptive (no false cue: the paper's Equations 2-6 with per-shot\n"
                 "scaling, plus a slow return to centre in still moments for shots too long to\n"
                 "fit by scaling alone), highpass (the classical washout: the camera signals\n"
                 "high-passed, which moves back while the camera keeps moving), off")
      ->capture_default_str()
      ->check(CLI::IsMember({"adaptive", "highpass", "off"}));
  app.add_flag("--no-washout", *no_washout,
               "same as --washout off (the paper's plain Equations 2-6; cut crossfades, speed\n"
               "limit and clamp still apply)");
  app.add_option("--return-accel", w->return_accel_m_s2,
                 "adaptive washout: largest acceleration of a return to centre, m/s^2 (below\n"
                 "the vestibular threshold: docs/haptics.md)")
      ->default_val(w->return_accel_m_s2)
      ->check(FiniteRange(0.0001, 100));
  app.add_option("--washout-window", w->window_s,
                 "adaptive washout: a shot whose whole motion is under twice its largest motion\n"
                 "within this many seconds is fitted by scaling alone, s")
      ->default_val(w->window_s)
      ->check(FiniteRange(0.1, 3600));
  app.add_option("--washout-tau", w->tau_s, "highpass washout: time constant, s")
      ->default_val(w->tau_s)
      ->check(FiniteRange(0.05, 600));
  app.add_option("--washout-order", w->order, "highpass washout: order (1 or 2)")
      ->default_val(w->order)
      ->check(FiniteRange(1, 2));
  app.add_option("--cut-ramp", w->cut_ramp_s, "crossfade at a shot cut, s")
      ->default_val(w->cut_ramp_s)
      ->check(FiniteRange(0, 10));
  app.add_option("--max-speed", w->max_speed_m_s,
                 "largest actuator speed per axis, m/s (bounds every step)")
      ->default_val(w->max_speed_m_s)
      ->check(FiniteRange(0, 10));
}

// The cinematic model's scaling options (docs/haptics.md, "Scaling").
void AddCinematicOptions(CLI::App& app, CinematicOptions* c) {
  app.add_option("--reference-depth", c->reference_depth_u,
                 "distance of the subject defining the zoom's equivalent forward distance,\n"
                 "in path units; 0 = per shot: a dolly zoom's own subject distance, else\n"
                 "metadata subject_distance_m, else 1 (the median depth of estimated paths)")
      ->default_val(c->reference_depth_u)
      ->check(FiniteRange(0, 1e6));
  app.add_option("--max-translation-gain", c->max_translation_gain,
                 "cinematic: cap on the translation/zoom scale, metres per path unit")
      ->default_val(c->max_translation_gain)
      ->check(FiniteRange(0, 100));
  app.add_option("--max-rotation-gain", c->max_rotation_gain,
                 "cinematic: cap on the rotation scale (1 = the camera's own angles)")
      ->default_val(c->max_rotation_gain)
      ->check(FiniteRange(0, 10));
  app.add_flag("--per-film-scaling", c->per_film_scaling,
               "cinematic: one scaling for the whole film instead of one per shot");
}

// Everything the command line sets besides HapticOptions and HjifOptions.
struct HapticsArgs {
  std::string input, output, hjif, seat_file, model = "cinematic", keyframes, effects_out, edits;
  double rate = 0;
  std::string washout = "adaptive";
  bool no_washout = false, print_seat = false;
  uint64_t seed = 0;
  CLI::Option* seed_option = nullptr;  // counted: no --seed keeps the path's hash
};

// The input, the outputs, the model, the seat and the stored rate.
void AddFileOptions(CLI::App& app, HapticsArgs* a) {
  app.add_option("INPUT", a->input,
                 "camera path (*.camera.csv / *.csv), or a video: its camera path is then\n"
                 "estimated first with the default settings of `hapcine estimate`");
  app.add_option("-o,--output", a->output, "output haptic track (*.haptic.csv), written atomically");
  app.add_option("--model", a->model, "cinematic, semantic, random or none")
      ->default_val(a->model)
      ->check(CLI::IsMember({"cinematic", "semantic", "random", "none"}));
  app.add_option("--hjif", a->hjif,
                 "also write an MPEG-I Haptics interchange file (.hjif, ISO/IEC 23090-31)");
  app.add_option("--seat", a->seat_file,
                 "HapSeat geometry JSON overriding the built-in defaults (see --print-seat), or\n"
                 "a motion platform (\"type\": \"platform\", e.g. haptics/platform_3dof.json):\n"
                 "then -o writes a platform track (*.platform.csv: pose and Stewart legs)");
  app.add_flag("--print-seat", a->print_seat, "print the seat geometry in use as JSON and exit");
  app.add_option("--rate", a->rate, "stored rate in Hz; default: the seat's rate_hz (100; the player interpolates to 1 kHz)")
      ->default_val(0)
      ->check(FiniteRange(0, 10000));
}

// The random model's noise, the semantic model's effects and the edits.
void AddRandomAndSemanticOptions(CLI::App& app, HapticsArgs* a, HapticOptions* opt) {
  a->seed_option =
      app.add_option("--seed", a->seed,
                     "random model: seed of the noise (default: a hash of the camera path, so each\n"
                     "film gets its own noise and the same film always the same)")
          ->check(FiniteRange(0, 4294967295));
  app.add_option("--cutoff", opt->random_cutoff_hz, "random model: low-pass cutoff, Hz")
      ->default_val(opt->random_cutoff_hz)
      ->check(FiniteRange(0, 50));
  app.add_option("--keyframes", a->keyframes,
                 "semantic model: hand-placed effects, CSV 'start_s,end_s,effect,intensity'\n"
                 "(default: effects found automatically by the classifier)");
  app.add_option("--effects-out", a->effects_out,
                 "also write the effect segments (the classifier's, or --keyframes, or the\n"
                 "edits' keyframes) as a keyframe file: edit it and pass it back with --keyframes");
  app.add_option("--edits", a->edits,
                 "a designer's edits file (*.edits.json, docs/formats.md \"Edits file\"): per\n"
                 "shot model, gain, mute and washout, and keyframes replacing the classifier's;\n"
                 "applied before the film-level safety (cut crossfades, speed limit, clamp)");
}

void AddGapAndHjifOptions(CLI::App& app, HapticOptions* opt, HjifOptions* hjif_opt) {
  app.add_option("--max-gap", opt->max_gap_s, "reject time gaps longer than this inside a shot, s")
      ->default_val(opt->max_gap_s)
      ->check(FiniteRange(0.001, 600));
  app.add_option("--hjif-rate", hjif_opt->keyframe_rate_hz, "keyframes per second in the .hjif")
      ->default_val(hjif_opt->keyframe_rate_hz)
      ->check(FiniteRange(0, 10000));
}

// The command line's choices into `opt` and `hjif_opt`, then their checks.
void CompleteOptions(const HapticsArgs& a, HapticOptions* opt, HjifOptions* hjif_opt) {
  opt->model = HapticModelFromName(a.model);
  opt->rate_hz = a.rate;
  opt->keyframes_file = a.keyframes;
  if (!a.edits.empty()) opt->edits = ReadHapticEditsFile(a.edits);
  if (a.seed_option->count() > 0) opt->seed = a.seed;
  opt->washout.mode = WashoutModeFromName(a.no_washout ? "off" : a.washout);
  opt->source = a.input;
  opt->Check();
  hjif_opt->gain_m = opt->seat.workspace_half_m;
  // A short description: the file's stem, not its path (8-bit length in .hmpg).
  hjif_opt->description = std::filesystem::path(a.hjif).stem().string();
  hjif_opt->Check();
}

// INPUT's camera path: read and checked, or estimated when INPUT is a video.
CameraPath InputCameraPath(const std::string& input, double max_gap_s) {
  if (EndsWith(input, ".csv")) {
    CameraPath path = ReadCameraPathFile(input);
    // The haptic checks (gaps, absurd positions) with file line numbers.
    const std::vector<int> lines = CsvDataRowLines(input);
    ValidatePathForHaptics(path, input, max_gap_s, &lines);
    return path;
  }
  // A video: estimate its camera path first (default estimator settings;
  // run `hapcine estimate` yourself to choose them and keep the path).
  Progress progress(std::cerr, ProgressModeFor(false), "haptics: estimating camera path", "frames");
  CameraPath path = EstimateCameraPathFromFile(input, EstimatorOptions{},
                                               [&](long done, long total) { progress.Update(done, total); });
  progress.Close();
  if (const auto w = path.metadata.find("warning"); w != path.metadata.end())
    std::cerr << "hapcine haptics: " << input << ": warning: " << w->second << "\n";
  return path;
}

// The track, the .hjif and the effects file. They go to temporary files
// first; nothing is renamed into place until all are complete.
void WriteOutputs(const HapticsArgs& a, const CameraPath& path, const HapticTrack& track,
                  const HapticOptions& opt, const HjifOptions& hjif_opt) {
  AtomicFile csv(a.output);
  WriteHapticTrack(track, csv.stream());
  std::unique_ptr<AtomicFile> hj;
  if (!a.hjif.empty()) {
    hj = std::make_unique<AtomicFile>(a.hjif);
    WriteHjif(track, hjif_opt, hj->stream());
  }
  std::unique_ptr<AtomicFile> fx;
  if (!a.effects_out.empty()) {
    fx = std::make_unique<AtomicFile>(a.effects_out);
    WriteKeyframes(EffectiveEffectSegments(path, opt), fx->stream());
  }
  csv.Commit();
  if (hj) hj->Commit();
  if (fx) fx->Commit();
}

// The low-quality shots' warnings and the closing line.
void PrintSummary(const HapticsArgs& a, const CameraPath& path, const HapticTrack& track) {
  for (const ShotConfidence& c : AssessShotConfidence(path, SplitShots(path))) {
    if (c.low) std::cerr << "hapcine haptics: " << a.input << ": warning: " << LowQualityShotLine(c) << "\n";
  }
  if (!a.edits.empty()) std::cerr << "haptics: edits from " << a.edits << "\n";
  std::cerr << "haptics: " << a.model << " track of " << track.samples.size() << " samples ("
            << track.duration_s() << " s at " << track.rate_hz << " Hz) -> " << a.output
            << (a.hjif.empty() ? "" : " + " + a.hjif)
            << (a.effects_out.empty() ? "" : " + " + a.effects_out)
            << "; clamped samples: " << track.metadata.at("clamped_samples")
            << "; low-quality shots: " << track.metadata.at("low_quality_shots") << "\n";
}

// INPUT -> the HapSeat's track (and .hjif, effects file), atomically.
int MakeSeatTrack(const HapticsArgs& a, HapticOptions opt, HjifOptions hjif_opt) {
  if (a.input.empty()) throw UsageError("INPUT is required");
  if (a.output.empty()) throw UsageError("-o OUT.haptic.csv is required");
  OutputSet outputs({{a.input, "INPUT"}, {a.seat_file, "--seat"}, {a.keyframes, "--keyframes"},
                     {a.edits, "--edits"}},
                    {{a.output, "-o"}, {a.hjif, "--hjif"}, {a.effects_out, "--effects-out"}});
  CompleteOptions(a, &opt, &hjif_opt);
  const CameraPath path = InputCameraPath(a.input, opt.max_gap_s);
  const InputScope making(a.input);  // "INPUT: out of memory" if it comes to that
  const HapticTrack track = MakeHapticTrack(path, opt);
  WriteOutputs(a, path, track, opt, hjif_opt);
  outputs.CommitAll();
  PrintSummary(a, path, track);
  return kExitOk;
}

}  // namespace

int RunHaptics(int argc, char** argv) {
  CLI::App app{
      "Turn a camera path (*.camera.csv) into a haptic track (*.haptic.csv) for the HapSeat:\n"
      "the target displacement of the head, left-hand and right-hand actuators at a fixed rate,\n"
      "on the media clock of the video. Models (the paper's four feedback conditions):\n"
      "  cinematic  feel the camera's movement (Equations 2-6; a zoom-in is a forward move)\n"
      "  semantic   feel a metaphor of the camera effect (Table 2), on effects found by the\n"
      "             classifier or placed by hand with --keyframes\n"
      "  random     white noise low-passed at 0.5 Hz (-3 dB), seeded by the film (--seed)\n"
      "  none       actuators stay centred\n"
      "Films are processed per shot (`shot` column) with a washout so no actuator leaves its\n"
      "workspace. Details and file formats: docs/haptics.md.",
      "hapcine haptics"};
  HapticsArgs a;
  HapticOptions opt;
  HjifOptions hjif_opt;
  AddFileOptions(app, &a);
  AddRandomAndSemanticOptions(app, &a, &opt);
  AddWashoutOptions(app, &opt.washout, &a.washout, &a.no_washout);
  AddCinematicOptions(app, &opt.cinematic);
  AddGapAndHjifOptions(app, &opt, &hjif_opt);

  return RunApp(app, argc, argv, [&]() -> int {
    if (!a.seat_file.empty() && IsPlatformFile(a.seat_file)) {
      if (!a.edits.empty()) throw UsageError("--edits applies to the HapSeat, not to a platform");
      return RunPlatformHaptics({a.seat_file, a.input, a.output, a.model, a.print_seat, a.rate,
                                 opt.cinematic.reference_depth_u, opt.max_gap_s,
                                 !a.hjif.empty() || !a.effects_out.empty()});
    }
    if (!a.seat_file.empty()) opt.seat = LoadSeatGeometryFile(a.seat_file);
    if (a.print_seat) {
      std::cout << SeatGeometryToJson(opt.seat);
      return kExitOk;
    }
    return MakeSeatTrack(a, opt, hjif_opt);
  });
}

}  // namespace hapcine::cli
