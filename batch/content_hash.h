#pragma once
// Content identity of input films, for resumability and duplicate detection.
//
// A batch must notice when a film's CONTENT changed (re-encoded, replaced)
// even if its name, size or mtime did not, and must see two paths holding the
// same bytes as one film. Reading whole films (often gigabytes) on every
// re-run would cost more than the check is worth, so the identity is a
// SAMPLED hash: FNV-1a 64 over the file size and three 1 MiB windows (head,
// middle, tail); files of at most 3 MiB are hashed whole. This reads at most
// 3 MiB per film (milliseconds), catches re-encodes, truncations, appends and
// replaced files (containers put headers/indexes at both ends), and misses
// only an in-place edit that keeps the size and touches none of the three
// windows (use --force for that). Duplicates are therefore CONFIRMED by a
// full byte comparison (FilesEqual) before a film is skipped as a copy.
//
// FNV-1a (core/hash.h) is not cryptographic; it needs no library, is stable
// across platforms and is plenty for telling a user's own films apart.

#include <cstdint>
#include <string>

#include "core/hash.h"

namespace hapcine::batch {

struct ContentId {
  uint64_t size_bytes = 0;
  std::string hash;  // "fnv1a64s:<16 hex>" (sampled, see above)
};

// Size + sampled hash. Throws hapcine::Error(path, reason) if unreadable.
ContentId SampledContentId(const std::string& path);

// FNV-1a 64 of the whole file ("fnv1a64:<16 hex>"), for recording outputs.
std::string FullFileHash(const std::string& path);

// True if both files hold exactly the same bytes. Throws if unreadable.
bool FilesEqual(const std::string& a, const std::string& b);

}  // namespace hapcine::batch
