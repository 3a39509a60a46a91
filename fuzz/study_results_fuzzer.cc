// The study results reader (study/results.h). It takes only a path, so the
// input goes through a scratch file.
#include "fuzz/fuzz_input.h"
#include "study/results.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path =
      hapcine::fuzz::WriteScratchFile("P01.results.json", hapcine::fuzz::AsString(data, size));
  hapcine::fuzz::AcceptOnlyError([&] {
    const auto results = hapcine::study::ReadResultsFile(path);
    hapcine::study::ResultsToJson(results).dump();
  });
  return 0;
}
