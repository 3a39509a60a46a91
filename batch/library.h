#pragma once
// What a batch processes: the list of input films, from a folder or a
// manifest, and the stable output folder name of each.
//
// LIBRARY is either
//   - a folder: searched recursively (symbolic links to files are followed,
//     hidden entries starting with '.' are skipped) for video files by
//     extension, case-insensitive (see IsVideoExtension); or
//   - a video file (by extension, as above): a library of that one film;
//   - a manifest file:
//       * "*.csv": a CSV with a header row holding a column named "path"
//         (case-insensitive; other columns are ignored; fields may be
//         double-quoted, with "" for a quote inside);
//       * anything else: plain text, one path per line; blank lines and
//         lines starting with '#' are ignored; surrounding whitespace is
//         trimmed.
//     Relative paths are relative to the manifest's folder. Every listed path
//     is taken whatever its extension; a missing file becomes a failed film.
// Paths are made absolute and lexically normal, de-duplicated, and sorted
// (byte order), so every run and every Slurm shard sees the same order.

#include <string>
#include <vector>

namespace hapcine::batch {

// True for the container extensions ffmpeg reads films from: mp4 m4v mov
// mkv webm avi mpg mpeg m2v ts m2ts mts wmv flv 3gp ogv vob mxf
// (without the dot, any case).
bool IsVideoExtension(const std::string& extension);

// The input list of a folder or manifest. Throws hapcine::Error if LIBRARY
// does not exist or a manifest is malformed (e.g. a CSV without "path").
std::vector<std::string> ListLibrary(const std::string& library);

// The stem of a film's output files: the file stem, cut (on a UTF-8
// character boundary) so that the longest output name,
// "<stem>.<model>.haptic.csv", fits in 255 bytes.
std::string OutputStem(const std::string& file_stem, const std::vector<std::string>& models);

// Output folder name of an input: "<stem>-<8 hex of FNV-1a of the absolute
// path>". Unique per path, stable across runs, keeps spaces and non-ASCII
// letters of the stem (UTF-8 is kept intact, control characters become '_',
// a leading '.' becomes '_', the stem is cut to at most 80 bytes on a
// character boundary).
std::string FilmId(const std::string& absolute_path);

// File name without folder and last extension ("a/b/é clip.mp4" -> "é clip").
std::string FileStem(const std::string& path);

// Splits a command-line fragment like a POSIX shell would for words:
// whitespace separates, '...' and "..." quote, backslash escapes.
// Throws UsageError on an unterminated quote.
std::vector<std::string> SplitArgs(const std::string& text);

}  // namespace hapcine::batch
