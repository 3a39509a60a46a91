#pragma once
// The plan of a batch: every input film with its content id, output folder,
// duplicate relation and Slurm shard. Every run and every shard computes the
// same plan from the same library, so shards never step on each other.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "batch/batch_options.h"

namespace hapcine::batch {

struct FilmPlan {
  std::string path;  // absolute input path
  std::string id;    // output folder name (FilmId)
  std::string stem;  // output file stem (input name without extension)
  uint64_t size_bytes = 0;
  std::string input_hash;      // sampled content hash; empty if unreadable
  std::string precheck_error;  // set: fails without running a step (missing, empty file)
  std::string duplicate_of;    // set: same bytes as this film id, processed once there
  int shard = 0;               // Slurm shard (array task) that owns the film
};

struct BatchPlan {
  std::string library;
  std::string settings_hash;
  int shard_count = 1;
  std::vector<FilmPlan> films;  // sorted by path
};

// Lists and hashes the library. Files with equal sampled hashes are compared
// byte by byte; the first path (byte order) of a set of true copies is
// processed, the others become duplicates. Shards are dealt round-robin over
// the processed films in path order; a duplicate goes with its original.
BatchPlan MakePlan(const BatchOptions& options);

nlohmann::json PlanToJson(const BatchPlan& plan);
BatchPlan PlanFromJson(const nlohmann::json& j);  // throws on a malformed plan

}  // namespace hapcine::batch
