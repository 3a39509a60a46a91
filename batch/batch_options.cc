#include "batch/batch_options.h"

#include <unistd.h>

#include <climits>
#include <set>
#include <filesystem>
#include <thread>

#include "batch/content_hash.h"
#include "core/error.h"

#ifndef HAPCINE_VERSION
#define HAPCINE_VERSION "unknown"
#endif

namespace hapcine::batch {

std::string HapcineVersion() { return HAPCINE_VERSION; }

std::string SelfExecutable() {
  char buf[PATH_MAX];
  const ssize_t n = ::readlink("/proc/self/exe", buf, sizeof(buf) - 1);
  if (n <= 0) throw Error("/proc/self/exe", "cannot resolve the running executable");
  return std::string(buf, static_cast<size_t>(n));
}

void BatchOptions::Check() const {
  if (library.empty()) throw UsageError("LIBRARY (folder or manifest) is required");
  if (out_dir.empty()) throw UsageError("-o OUT_DIR is required");
  if (jobs < 0 || jobs > 1024) throw UsageError("--jobs must be in [0, 1024] (0 = number of CPUs)");
  if (models.empty()) throw UsageError("--models needs at least one model");
  // The models of `hapcine haptics --model`: a misspelt one would otherwise
  // fail every film after its estimate.
  static const std::set<std::string> kModels = {"cinematic", "semantic", "random", "none"};
  std::set<std::string> seen;
  for (const std::string& m : models) {
    if (!kModels.count(m)) {
      throw UsageError("unknown model '" + m +
                       "' in --models (expected cinematic, semantic, random or none)");
    }
    if (!seen.insert(m).second) throw UsageError("model '" + m + "' given twice in --models");
  }
  if (shard_count < 1 || shard_index < 0 || shard_index >= shard_count) {
    throw UsageError("--shard must be i/K with 0 <= i < K");
  }
}

int BatchOptions::ResolvedJobs() const {
  if (jobs > 0) return jobs;
  const unsigned n = std::thread::hardware_concurrency();
  return n > 0 ? static_cast<int>(n) : 1;
}

std::string BatchOptions::ResolvedStepExe() const {
  return step_exe.empty() ? SelfExecutable() : step_exe;
}

nlohmann::json ArgumentFileHashes(const std::vector<std::string>& args) {
  nlohmann::json files = nlohmann::json::object();
  for (const std::string& word : args) {
    std::string path = word;
    if (word.rfind("-", 0) == 0) {
      const size_t eq = word.find('=');
      if (eq == std::string::npos) continue;  // a flag or an option name
      path = word.substr(eq + 1);
    }
    std::error_code ec;
    if (path.empty() || !std::filesystem::is_regular_file(path, ec)) continue;
    try {
      files[word] = FullFileHash(path);
    } catch (const std::exception&) {
      files[word] = "unreadable";  // the step will fail on it and say why
    }
  }
  return files;
}

nlohmann::json SettingsJson(const BatchOptions& options) {
  nlohmann::json j = {{"hapcine_version", HapcineVersion()},
                      {"estimate_args", options.estimate_args},
                      {"haptics_args", options.haptics_args},
                      {"models", options.models}};
  // Only when they differ from a batch's, so batch settings hashes stay
  // what they were.
  if (!options.hjif) j["hjif"] = false;
  if (options.preview) j["preview"] = true;
  if (options.plot) j["plot"] = true;
  // Only when there are any, so settings hashes of runs without file
  // arguments stay what they were.
  if (const auto f = ArgumentFileHashes(options.estimate_args); !f.empty()) {
    j["estimate_arg_files"] = f;
  }
  if (const auto f = ArgumentFileHashes(options.haptics_args); !f.empty()) {
    j["haptics_arg_files"] = f;
  }
  return j;
}

std::string SettingsHash(const BatchOptions& options) {
  return Fnv1a64Hex(SettingsJson(options).dump());
}

std::string EstimateStepKey(const BatchOptions& options) {
  nlohmann::json j = {{"hapcine_version", HapcineVersion()},
                      {"estimate_args", options.estimate_args}};
  if (const auto f = ArgumentFileHashes(options.estimate_args); !f.empty()) {
    j["estimate_arg_files"] = f;
  }
  return Fnv1a64Hex(j.dump());
}

std::string HapticsStepKey(const BatchOptions& options, const std::string& model) {
  nlohmann::json j = {{"hapcine_version", HapcineVersion()},
                      {"estimate_args", options.estimate_args},
                      {"haptics_args", options.haptics_args},
                      {"model", model}};
  // The camera path it reads depends on the estimate settings, already in.
  if (const auto f = ArgumentFileHashes(options.estimate_args); !f.empty()) {
    j["estimate_arg_files"] = f;
  }
  if (const auto f = ArgumentFileHashes(options.haptics_args); !f.empty()) {
    j["haptics_arg_files"] = f;
  }
  return Fnv1a64Hex(j.dump());
}

}  // namespace hapcine::batch
