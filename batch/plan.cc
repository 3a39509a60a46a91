#include "batch/plan.h"

#include <map>

#include "batch/content_hash.h"
#include "batch/json_bytes.h"
#include "batch/library.h"
#include "core/error.h"

namespace hapcine::batch {

BatchPlan MakePlan(const BatchOptions& options) {
  BatchPlan plan;
  plan.library = options.library;
  plan.settings_hash = SettingsHash(options);
  plan.shard_count = options.shard_count;
  for (const std::string& path : ListLibrary(options.library)) {
    FilmPlan f;
    f.path = path;
    f.id = FilmId(path);
    f.stem = OutputStem(FileStem(path), options.models);
    try {
      const ContentId cid = SampledContentId(path);
      f.size_bytes = cid.size_bytes;
      f.input_hash = cid.hash;
      if (cid.size_bytes == 0) f.precheck_error = path + ": empty file (0 bytes)";
    } catch (const Error& e) {
      f.precheck_error = e.what();
    }
    plan.films.push_back(f);
  }
  // Duplicates: same sampled hash, then confirmed byte by byte.
  std::map<std::string, std::vector<size_t>> originals_by_hash;
  for (size_t i = 0; i < plan.films.size(); ++i) {
    FilmPlan& f = plan.films[i];
    if (!f.precheck_error.empty()) continue;
    std::vector<size_t>& originals = originals_by_hash[f.input_hash];
    for (size_t o : originals) {
      bool equal = false;
      try {
        equal = FilesEqual(plan.films[o].path, f.path);
      } catch (const Error&) {
        equal = false;
      }
      if (equal) {
        f.duplicate_of = plan.films[o].id;
        break;
      }
    }
    if (f.duplicate_of.empty()) originals.push_back(i);
  }
  // Shards: round-robin over films that are not duplicates.
  std::map<std::string, int> shard_of_id;
  int next = 0;
  for (FilmPlan& f : plan.films) {
    if (!f.duplicate_of.empty()) continue;
    f.shard = next++ % plan.shard_count;
    shard_of_id[f.id] = f.shard;
  }
  for (FilmPlan& f : plan.films) {
    if (!f.duplicate_of.empty()) f.shard = shard_of_id[f.duplicate_of];
  }
  return plan;
}

nlohmann::json PlanToJson(const BatchPlan& plan) {
  nlohmann::json films = nlohmann::json::array();
  for (const FilmPlan& f : plan.films) {
    films.push_back({{"path", JsonFromBytes(f.path)},
                     {"id", f.id},
                     {"stem", JsonFromBytes(f.stem)},
                     {"size_bytes", f.size_bytes},
                     {"input_hash", f.input_hash},
                     {"precheck_error", f.precheck_error},
                     {"duplicate_of", f.duplicate_of},
                     {"shard", f.shard}});
  }
  return {{"library", JsonFromBytes(plan.library)},
          {"settings_hash", plan.settings_hash},
          {"shard_count", plan.shard_count},
          {"films", films}};
}

BatchPlan PlanFromJson(const nlohmann::json& j) {
  BatchPlan plan;
  plan.library = BytesFromJson(j.at("library"));
  plan.settings_hash = j.at("settings_hash").get<std::string>();
  plan.shard_count = j.at("shard_count").get<int>();
  for (const auto& jf : j.at("films")) {
    FilmPlan f;
    f.path = BytesFromJson(jf.at("path"));
    f.id = jf.at("id").get<std::string>();
    f.stem = BytesFromJson(jf.at("stem"));
    f.size_bytes = jf.at("size_bytes").get<uint64_t>();
    f.input_hash = jf.at("input_hash").get<std::string>();
    f.precheck_error = jf.at("precheck_error").get<std::string>();
    f.duplicate_of = jf.at("duplicate_of").get<std::string>();
    f.shard = jf.at("shard").get<int>();
    plan.films.push_back(f);
  }
  return plan;
}

}  // namespace hapcine::batch
