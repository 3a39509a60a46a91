// The COLMAP text model reader (datasets/colmap_text.h). It reads a folder,
// so the input is split into its three files at lines "====":
//   cameras.txt, "====", images.txt, "====", points3D.txt
// A part that is absent leaves its file out (points3D.txt is optional).
// Each model is read as `estimate --backend colmap` does (with the decoded
// frames' times and width) and without them.
#include <filesystem>
#include <vector>

#include "datasets/colmap_text.h"
#include "fuzz/fuzz_input.h"

namespace {

std::vector<std::string> SplitParts(const std::string& text) {
  const std::string separator = "\n====\n";
  std::vector<std::string> parts;
  size_t start = 0;
  while (parts.size() < 2) {
    const size_t at = text.find(separator, start);
    if (at == std::string::npos) break;
    parts.push_back(text.substr(start, at - start));
    start = at + separator.size();
  }
  parts.push_back(text.substr(start));
  return parts;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace fs = std::filesystem;
  const fs::path dir = hapcine::fuzz::ScratchDir() / "colmap";
  fs::create_directories(dir);
  const char* names[] = {"cameras.txt", "images.txt", "points3D.txt"};
  const auto parts = SplitParts(hapcine::fuzz::AsString(data, size));
  for (size_t i = 0; i < 3; ++i) {
    if (i < parts.size())
      hapcine::fuzz::WriteScratchFile(std::string("colmap/") + names[i], parts[i]);
    else
      fs::remove(dir / names[i]);
  }

  hapcine::fuzz::AcceptOnlyError([&] { hapcine::ReadColmapTextModel(dir.string()); });
  hapcine::ColmapReadOptions decoded;
  for (int i = 0; i < 12; ++i) decoded.frame_times.push_back(i / 24.0);
  decoded.decoded_width = 640;
  hapcine::fuzz::AcceptOnlyError([&] { hapcine::ReadColmapTextModel(dir.string(), decoded); });
  return 0;
}
