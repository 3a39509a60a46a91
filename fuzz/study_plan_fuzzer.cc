// The study plan reader (study/plan.h). It takes only a path, so the input
// goes through a scratch file. A plan whose content does not hash to its
// plan_id is refused after everything else has been read.
#include "fuzz/fuzz_input.h"
#include "study/plan.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path =
      hapcine::fuzz::WriteScratchFile("plan.json", hapcine::fuzz::AsString(data, size));
  hapcine::fuzz::AcceptOnlyError([&] { hapcine::study::ReadPlanFile(path); });
  return 0;
}
