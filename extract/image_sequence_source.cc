// FrameSource over still images: a folder (every image file in it, in the
// order of the number at the end of their names when all have one, else by
// name) or a printf pattern ("plates/plate.%04d.png", from the lowest number
// present — 1001 for a VFX plate — up to the first missing one, as FFmpeg's
// image2 demuxer reads a sequence). Image files carry no timestamps: frame i
// is at i / image_sequence_fps seconds; the number in each file's name is
// kept (VideoInfo::source_frames). PNG, JPEG, TIFF, BMP, WebP, PNM, JPEG 2000
// and OpenEXR are read by OpenCV (EXR's linear light shown through a 2.2
// gamma), DPX and Cineon by FFmpeg.

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/input_file.h"
#include "core/text.h"
#include "extract/video_sources.h"

namespace hapcine {
namespace {

namespace fs = std::filesystem;

// A PNG or JPEG cut short (an interrupted copy) either fails after libpng
// printed its own line on stderr, or "decodes" with the missing part grey
// (libjpeg, with a warning on stderr). Both end with a fixed marker, so look
// for it first: the IEND chunk closes every PNG; a JPEG's last EOI marker
// (FF D9, which cannot occur inside entropy-coded data) sits at its end,
// allowing for a little padding. Empty when the file looks complete.
std::string TruncatedImageReason(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[8] = {0};
  in.read(head, sizeof head);
  if (in.gcount() < 2) return {};
  static const char kPng[8] = {'\x89', 'P', 'N', 'G', '\r', '\n', '\x1a', '\n'};
  const bool png = in.gcount() == 8 && std::equal(head, head + 8, kPng);
  const bool jpeg = head[0] == '\xff' && head[1] == '\xd8';
  if (!png && !jpeg) return {};
  in.clear();
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  const std::streamoff tail_len = std::min<std::streamoff>(size, 4096);
  std::string tail(static_cast<size_t>(tail_len), '\0');
  in.seekg(size - tail_len);
  in.read(&tail[0], tail_len);
  if (png) {
    static const std::string kIend("\0\0\0\0IEND\xae\x42\x60\x82", 12);
    return tail.size() >= 12 && tail.compare(tail.size() - 12, 12, kIend) == 0
               ? std::string()
               : "truncated PNG (no IEND chunk at the end)";
  }
  return tail.find("\xff\xd9") != std::string::npos ? std::string()
                                                      : "truncated JPEG (no end-of-image marker)";
}

// While alive, whatever is written to the process's stderr (fd 2) goes to a
// private file instead; Take() returns it. One at a time (a mutex): fd 2 is
// shared by every thread.
class StderrCapture {
 public:
  StderrCapture() : lock_(Mutex()) {
    std::fflush(stderr);
    if (File() < 0 || ::ftruncate(File(), 0) != 0 || ::lseek(File(), 0, SEEK_SET) != 0) return;
    saved_ = ::dup(STDERR_FILENO);
    if (saved_ >= 0 && ::dup2(File(), STDERR_FILENO) < 0) {
      ::close(saved_);
      saved_ = -1;
    }
  }
  ~StderrCapture() { Restore(); }
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;

  // Ends the capture; returns what was written (at most 64 KiB).
  std::string Take() {
    Restore();
    std::string text;
    if (File() < 0 || ::lseek(File(), 0, SEEK_SET) != 0) return text;
    char buf[4096];
    ssize_t n;
    while (text.size() < 65536 && (n = ::read(File(), buf, sizeof buf)) > 0) text.append(buf, n);
    return text;
  }

 private:
  static std::mutex& Mutex() {
    static std::mutex m;
    return m;
  }
  static int File() {
    static FILE* const f = std::tmpfile();  // kept open for the process's lifetime
    return f ? fileno(f) : -1;
  }
  void Restore() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    ::dup2(saved_, STDERR_FILENO);
    ::close(saved_);
    saved_ = -1;
  }

  std::lock_guard<std::mutex> lock_;
  int saved_ = -1;
};

// The first line a codec printed that is not an OpenCV log line ("[ WARN..."),
// e.g. libpng's "libpng error: IDAT: CRC error"; "" if none.
std::string CodecReason(const std::string& printed) {
  size_t pos = 0;
  while (pos < printed.size()) {
    size_t end = printed.find('\n', pos);
    if (end == std::string::npos) end = printed.size();
    std::string line = printed.substr(pos, end - pos);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty() && line[0] != '[') return line;
    pos = end + 1;
  }
  return {};
}

// cv::imread without the codec libraries' own lines on stderr: a bad image
// becomes one hapcine line naming it, with the codec's reason in it. What a
// codec prints about an image it did decode (a libjpeg warning) goes to
// `warnings`, for the caller to tell (FrameSource::Warnings).
cv::Mat ReadImageQuietly(const std::string& path, std::vector<std::string>* warnings) {
  cv::Mat image;
  std::string printed;
  {
    StderrCapture capture;
    // Any depth: 16-bit and float images are brought to 8 bits below, with
    // the scale their depth means (imread's own conversion truncates floats).
    image = cv::imread(path, cv::IMREAD_COLOR | cv::IMREAD_ANYDEPTH);
    printed = capture.Take();
  }
  if (image.empty()) {
    const std::string reason = CodecReason(printed);
    throw Error(path, "not an image OpenCV can read" + (reason.empty() ? "" : " (" + reason + ")"));
  }
  while (!printed.empty() && (printed.back() == '\n' || printed.back() == '\r')) printed.pop_back();
  if (!printed.empty()) warnings->push_back(path + ": " + printed);
  return image;
}

// 8-bit BGR from what imread gave: 16-bit scaled by 1/257; float (EXR: scene
// linear light) clamped to [0, 1] and shown through a 2.2 gamma, as a
// viewer would, so that the trackers see contrast where a viewer does.
cv::Mat ToBgr8(const cv::Mat& image, bool linear_light) {
  if (image.depth() == CV_8U) return image;
  cv::Mat out;
  if (image.depth() == CV_16U) {
    image.convertTo(out, CV_8U, 1.0 / 257.0);
    return out;
  }
  cv::Mat unit;
  image.convertTo(unit, CV_32F);
  cv::min(cv::max(unit, 0.0), 1.0, unit);
  if (linear_light) cv::pow(unit, 1.0 / 2.2, unit);
  unit.convertTo(out, CV_8U, 255.0);
  return out;
}

// DPX and Cineon, which OpenCV does not read: one frame through FFmpeg's
// image2 demuxer and its decoder.
cv::Mat ReadImageWithFfmpeg(const std::string& path) {
  FrameSourceOptions options;
  options.max_working_side = 0;
  Frame frame;
  try {
    auto source = OpenFfmpegSource(path, options);
    if (source->Next(&frame) && !frame.bgr.empty()) return frame.bgr;
  } catch (const Error& e) {
    throw Error(path, "not an image FFmpeg can read (" + e.reason() + ")");
  }
  throw Error(path, "not an image FFmpeg can read (no frame decoded)");
}

bool HasImageExtension(const fs::path& p) {
  const std::string ext = LowerExtension(p.string());
  static const char* kExts[] = {".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".webp",
                                ".pgm", ".ppm", ".pnm",  ".exr", ".jp2", ".dpx", ".cin"};
  for (const char* e : kExts)
    if (ext == e) return true;
  return false;
}

// The number at the end of a file's stem ("plate.1001.exr" -> 1001), or -1.
long TrailingNumber(const fs::path& file) {
  const std::string stem = file.stem().string();
  size_t begin = stem.size();
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(stem[begin - 1]))) --begin;
  if (begin == stem.size() || stem.size() - begin > 9) return -1;
  return std::stol(stem.substr(begin));
}

// A folder's image files in the order of their trailing numbers when every
// one has a distinct one (plate.999 before plate.1000), else by name; the
// numbers go to *numbers (empty when not used).
std::vector<std::string> OrderedFolderImages(std::vector<std::string> files,
                                             std::vector<long>* numbers) {
  std::sort(files.begin(), files.end());
  std::vector<std::pair<long, std::string>> numbered;
  for (const std::string& f : files) numbered.emplace_back(TrailingNumber(f), f);
  std::sort(numbered.begin(), numbered.end());
  bool usable = !numbered.empty() && numbered.front().first >= 0;
  for (size_t i = 1; usable && i < numbered.size(); ++i)
    usable = numbered[i].first != numbered[i - 1].first;
  numbers->clear();
  if (!usable) return files;
  files.clear();
  for (const auto& [n, f] : numbered) {
    numbers->push_back(n);
    files.push_back(f);
  }
  return files;
}

// `pattern` has been checked to hold exactly one %d-style (int) conversion.
std::string Format(const std::string& pattern, long i) {
  char buf[4096];
  const int n = std::snprintf(buf, sizeof(buf), pattern.c_str(), static_cast<int>(i));
  if (n < 0 || n >= static_cast<int>(sizeof(buf))) return {};
  return buf;
}

// Any image of a sequence, 8-bit BGR.
cv::Mat ReadImage(const std::string& path, std::vector<std::string>* warnings) {
  const std::string ext = LowerExtension(path);
  if (ext == ".dpx" || ext == ".cin") return ReadImageWithFfmpeg(path);
  return ToBgr8(ReadImageQuietly(path, warnings), ext == ".exr" || ext == ".hdr");
}

// The numbers of the pattern's files present in its folder, ascending; empty
// when the conversion is in a folder name or the folder cannot be listed.
std::vector<long> PatternNumbers(const std::string& pattern) {
  const fs::path p(pattern);
  const std::string name = p.filename().string();
  const size_t conv = name.find('%');
  if (conv == std::string::npos) return {};
  std::string head = name.substr(0, conv);  // the literal text before the number
  std::vector<long> numbers;
  std::error_code ec;
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string file = entry.path().filename().string();
    if (file.compare(0, head.size(), head) != 0) continue;
    size_t end = head.size();
    while (end < file.size() && std::isdigit(static_cast<unsigned char>(file[end]))) ++end;
    if (end == head.size() || end - head.size() > 9) continue;
    const long n = std::stol(file.substr(head.size(), end - head.size()));
    // The pattern must give back exactly this name (its padding, its tail).
    if (fs::path(Format(pattern, n)).filename().string() == file) numbers.push_back(n);
  }
  std::sort(numbers.begin(), numbers.end());
  return numbers;
}

class ImageSequenceSource : public FrameSource {
 public:
  ImageSequenceSource(const std::string& path, const FrameSourceOptions& options)
      : options_(options) {
    info_.path = path;
    info_.fps = options.image_sequence_fps;
    info_.codec = "image";
    info_.stills = true;
    if (path.find('%') != std::string::npos) {
      pattern_ = path;
      ValidatePattern();
      FindPatternRange();
    } else {
      std::error_code ec;
      std::vector<std::string> files;
      for (const auto& entry : fs::directory_iterator(path, ec))
        if (entry.is_regular_file() && HasImageExtension(entry.path()))
          files.push_back(entry.path().string());
      if (ec) throw Error(path, "cannot list folder (" + ec.message() + ")");
      if (files.empty()) throw Error(path, "folder holds no image files");
      std::vector<long> numbers;
      files_ = OrderedFolderImages(files, &numbers);
      info_.source_frames.assign(numbers.begin(), numbers.end());
      info_.frame_count = static_cast<long>(files_.size());
      info_.duration_s = files_.size() / info_.fps;
    }
    // Read the first image now so that a bad sequence fails at open time.
    if (!ReadNext(&first_)) throw Error(path, "no readable image");
    info_.width = first_.cols;
    info_.height = first_.rows;
    have_first_ = true;
  }

  const VideoInfo& info() const override { return info_; }
  std::vector<std::string> Warnings() const override { return warnings_; }

  bool Next(Frame* out) override {
    cv::Mat image;
    if (have_first_) {
      image = first_;
      first_.release();
      have_first_ = false;
    } else if (!ReadNext(&image)) {
      return false;
    }
    const cv::Size work = WorkingSize(image.cols, image.rows, options_.max_working_side);
    cv::Mat bgr;
    if (work == image.size())
      bgr = image;
    else
      cv::resize(image, bgr, work, 0, 0, cv::INTER_AREA);
    cv::cvtColor(bgr, out->gray, cv::COLOR_BGR2GRAY);
    out->bgr = options_.want_color ? bgr : cv::Mat();
    out->index = emitted_;
    out->time_s = emitted_ / info_.fps;
    out->decoded_width = image.cols;
    out->decoded_height = image.rows;
    out->scale = image.cols >= image.rows ? static_cast<double>(work.width) / image.cols
                                          : static_cast<double>(work.height) / image.rows;
    ++emitted_;
    return true;
  }

 private:
  // Exactly one conversion of the form %d / %5d / %05d (an int), else
  // snprintf would read arguments that are not there.
  void ValidatePattern() const {
    int conversions = 0;
    for (size_t i = 0; i < pattern_.size(); ++i) {
      if (pattern_[i] != '%') continue;
      if (i + 1 < pattern_.size() && pattern_[i + 1] == '%') {
        ++i;
        continue;
      }
      size_t j = i + 1;
      while (j < pattern_.size() && std::isdigit(static_cast<unsigned char>(pattern_[j]))) ++j;
      if (j >= pattern_.size() || pattern_[j] != 'd')
        throw Error(info_.path, "image pattern must use an integer conversion like %05d");
      ++conversions;
      i = j;
    }
    if (conversions != 1)
      throw Error(info_.path, "image pattern must contain exactly one conversion like %05d");
  }

  // From the lowest number present to the first missing one, as FFmpeg's
  // image2 reads a sequence (which by itself looks only at 0..4 unless
  // given -start_number); numbers after a gap are named in a warning.
  void FindPatternRange() {
    const std::vector<long> numbers = PatternNumbers(pattern_);
    if (numbers.empty()) {  // the number is in a folder's name: try 0..4 as image2 does
      for (long first = 0; first <= 4 && next_index_ < 0; ++first)
        if (fs::exists(Format(pattern_, first))) next_index_ = first;
      if (next_index_ < 0) throw Error(info_.path, "no image matches the pattern");
      return;
    }
    next_index_ = numbers.front();
    size_t run = 1;
    while (run < numbers.size() && numbers[run] == numbers[run - 1] + 1) ++run;
    for (size_t i = 0; i < run; ++i) info_.source_frames.push_back(static_cast<int>(numbers[i]));
    info_.frame_count = static_cast<long>(run);
    info_.duration_s = run / info_.fps;
    if (run < numbers.size())
      warnings_.push_back(info_.path + ": " + std::to_string(numbers.size() - run) +
                          " image(s) after the gap at number " + std::to_string(numbers[run - 1] + 1) +
                          " ignored (a sequence ends at its first missing number)");
  }

  // Path of the next image, or empty at the end.
  std::string NextPath() {
    if (!pattern_.empty()) {
      std::string p = Format(pattern_, next_index_);
      if (p.empty() || !fs::exists(p)) return {};
      ++next_index_;
      return p;
    }
    if (next_file_ >= files_.size()) return {};
    return files_[next_file_++];
  }

  bool ReadNext(cv::Mat* image) {
    const std::string p = NextPath();
    if (p.empty()) return false;
    CheckRegularFile(p);  // a FIFO matching a pattern would block the read
    std::error_code ec;
    if (fs::file_size(p, ec) == 0) throw Error(p, "empty image file (0 bytes)");
    const std::string truncated = TruncatedImageReason(p);
    if (!truncated.empty()) throw Error(p, truncated);
    *image = ReadImage(p, &warnings_);
    if (image->cols > kMaxFrameSidePx || image->rows > kMaxFrameSidePx)
      throw Error(p, "absurd image size");
    if (emitted_ + (have_first_ ? 1 : 0) > 0 && info_.width > 0 &&
        (image->cols != info_.width || image->rows != info_.height))
      throw Error(p, "image size " + std::to_string(image->cols) + "x" +
                         std::to_string(image->rows) + " differs from the sequence's " +
                         std::to_string(info_.width) + "x" + std::to_string(info_.height));
    return true;
  }

  FrameSourceOptions options_;
  std::vector<std::string> warnings_;  // Warnings()
  VideoInfo info_;
  std::string pattern_;
  long next_index_ = -1;
  std::vector<std::string> files_;
  size_t next_file_ = 0;
  cv::Mat first_;
  bool have_first_ = false;
  int emitted_ = 0;
};

}  // namespace

bool IsImageSequencePath(const std::string& path) {
  if (path.find('%') != std::string::npos) return true;
  std::error_code ec;
  return fs::is_directory(path, ec);
}

std::unique_ptr<FrameSource> OpenImageSequence(const std::string& path,
                                               const FrameSourceOptions& options) {
  return std::make_unique<ImageSequenceSource>(path, options);
}

}  // namespace hapcine
