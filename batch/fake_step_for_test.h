#pragma once
// Test helpers: a stand-in for `hapcine estimate` / `hapcine haptics` (a
// shell script the batch runs via --hapcine-exe) and a test library with
// every kind of input a real library holds. Header-only, used by *_test.cc.
//
// The stand-in mimics the real steps' contract: it writes exactly the files
// named by -o/--hjif, exits 1 with a one-line "hapcine <cmd>: <file>:
// <reason>" for a file that is not a (fake) video or is "corrupt", and dies
// by SIGSEGV for a file containing "segv". Its outputs depend only on the
// input bytes and extra arguments, so runs can be compared byte for byte.
// Each finished estimate appends "estimate <input path>" to a call log. A
// haptics step given --edits FILE appends "edits:" and FILE's bytes to its
// track; `plot` and `preview` write their input's bytes under their output names.

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace hapcine::batch::testutil {

namespace fs = std::filesystem;

class TempDir {
 public:
  explicit TempDir(const std::string& tag = "batch") {
    std::string tmpl = "/tmp/hapcine_" + tag + "_XXXXXX";
    path_ = ::mkdtemp(tmpl.data());
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

inline std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

inline void WriteFile(const std::string& path, const std::string& content) {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream(path, std::ios::binary | std::ios::trunc) << content;
}

// Writes the stand-in step program into dir; returns its path.
inline std::string WriteFakeStep(const std::string& dir, const std::string& call_log,
                                 double estimate_delay_s = 0.0) {
  const std::string path = dir + "/fake-hapcine";
  WriteFile(path, R"SH(#!/bin/bash
# Stand-in for `hapcine estimate|haptics` (batch tests). Bash builtins only
# (no grep/cksum processes): the tests run many steps on a busy machine.
set -u
LOG=')SH" + call_log + R"SH('
DELAY=)SH" + std::to_string(estimate_delay_s) +
                      R"SH(
cmd=$1; shift
case "$cmd" in
  estimate)
    in=$1; out=$3; shift 3
    [ "$DELAY" != 0.000000 ] && sleep "$DELAY"
    IFS= read -r -d '' content < "$in"
    if [[ $content == *segv* ]]; then kill -SEGV $$; fi
    if [[ $content == *corrupt* ]]; then echo "hapcine estimate: $in: corrupt video stream at byte 10" >&2; exit 1; fi
    if [[ $content != FAKEVIDEO* ]]; then echo "hapcine estimate: $in: no video stream found" >&2; exit 1; fi
    if [[ $content == *silent* ]]; then exit 0; fi
    printf 'frame,time_s,model\n%s\nbytes:%d\nargs:%s\n' "$content" "${#content}" "$*" > "$out"
    echo "estimate $in" >> "$LOG"
    ;;
  haptics)
    cam=$1; model=$3; out=$5; hjif=""; edits=""
    args=("$@")
    for ((i = 5; i + 1 < ${#args[@]}; i++)); do
      [ "${args[$i]}" = --hjif ] && hjif=${args[$((i + 1))]}
      [ "${args[$i]}" = --edits ] && edits=${args[$((i + 1))]}
    done
    IFS= read -r -d '' camera < "$cam"
    printf 'model,%s\n%s' "$model" "$camera" > "$out"
    # An edits file's bytes end the track, so a test sees which edits made it.
    if [ -n "$edits" ]; then IFS= read -r -d '' e < "$edits"; printf 'edits:%s' "$e" >> "$out"; fi
    [ -n "$hjif" ] && echo "{\"model\":\"$model\"}" > "$hjif"
    echo "haptics $model $cam" >> "$LOG"
    ;;
  plot)
    # plot camera|haptic FILE --format png -o PREFIX: a "picture" of FILE's bytes.
    kind=$1; in=$2; prefix=$6
    IFS= read -r -d '' content < "$in"
    printf 'plot %s\n%s' "$kind" "$content" > "$prefix.png"
    echo "plot $kind $in" >> "$LOG"
    ;;
  preview)
    # preview FILM --track TRACK [...] -o OUT: a "video" of the track's bytes.
    track=""; out=""
    args=("$@")
    for ((i = 1; i + 1 < ${#args[@]}; i++)); do
      [ "${args[$i]}" = --track ] && track=${args[$((i + 1))]}
      [ "${args[$i]}" = -o ] && out=${args[$((i + 1))]}
    done
    IFS= read -r -d '' content < "$track"
    printf 'preview\n%s' "$content" > "$out"
    echo "preview $track" >> "$LOG"
    ;;
  *) echo "fake hapcine: unknown command $cmd" >&2; exit 2 ;;
esac
)SH");
  ::chmod(path.c_str(), 0755);
  return path;
}

// A library with every kind of input; returns name -> kind.
//   good: a.mp4, b.mov, "sub dir/with space.mkv", "é clip.mp4", "日本.mkv"
//   duplicate: "zz copy of a.mp4" (same bytes as a.mp4; sorts after it)
//   failures: corrupt.mp4 (step fails), empty.mp4 (0 bytes),
//             notes.mp4 (a text file named .mp4)
//   ignored: readme.txt (not a video extension)
struct TestLibrary {
  std::string root;
  std::vector<std::string> good = {"a.mp4", "b.mov", "sub dir/with space.mkv", "é clip.mp4",
                                   "日本.mkv"};
  std::string duplicate = "zz copy of a.mp4";
  std::vector<std::string> failing = {"corrupt.mp4", "empty.mp4", "notes.mp4"};
  int total() const { return static_cast<int>(good.size() + failing.size()) + 1; }
};

inline TestLibrary MakeTestLibrary(const std::string& root) {
  TestLibrary lib;
  lib.root = root;
  for (const std::string& name : lib.good) WriteFile(root + "/" + name, "FAKEVIDEO " + name + "\n");
  WriteFile(root + "/" + lib.duplicate, "FAKEVIDEO a.mp4\n");
  WriteFile(root + "/corrupt.mp4", "FAKEVIDEO but corrupt\n");
  WriteFile(root + "/empty.mp4", "");
  WriteFile(root + "/notes.mp4", "shopping list: milk\n");
  WriteFile(root + "/readme.txt", "FAKEVIDEO not a video extension\n");
  return lib;
}

// Lines of the call log starting with `prefix`.
inline std::vector<std::string> LogLines(const std::string& log, const std::string& prefix) {
  std::vector<std::string> lines;
  std::ifstream in(log);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(prefix, 0) == 0) lines.push_back(line);
  }
  return lines;
}

// Every leftover temporary (".tmp" folders, "*.hapcine-tmp" and "*.tmp-<pid>"
// files) under dir.
inline std::vector<std::string> TempLeftovers(const std::string& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name == ".tmp" || name.find(".tmp-") != std::string::npos ||
        name.find(".hapcine-tmp") != std::string::npos)
      found.push_back(e.path());
  }
  return found;
}

// Relative path -> bytes of every output file (not state, logs or locks).
inline std::map<std::string, std::string> OutputFiles(const std::string& out_dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(out_dir)) {
    const std::string name = e.path().filename().string();
    if (!e.is_regular_file()) continue;
    const bool output = name.size() > 4 && (name.find(".camera.csv") != std::string::npos ||
                                            name.find(".haptic.csv") != std::string::npos ||
                                            name.rfind(".hjif") == name.size() - 5);
    if (output) files[fs::relative(e.path(), out_dir).string()] = ReadAll(e.path());
  }
  return files;
}

}  // namespace hapcine::batch::testutil
