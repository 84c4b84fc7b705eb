#pragma once
// Where the real USD sample files are: ../shared/usd-samples beside the
// repository. Tests that read them are tagged [samples]; the ctest entry
// usd.samples runs them, or skips (exit 77) when the folder is absent.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace sdg::usd::test {

inline std::string samplesDir() {
  return (std::filesystem::path(SDG_SOURCE_DIR) / "../shared/usd-samples").lexically_normal().generic_string();
}

// Every file under the samples folder whose name ends with one of `extensions`, sorted.
inline std::vector<std::string> sampleFiles(const std::vector<std::string>& extensions) {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(samplesDir())) {
    if (!entry.is_regular_file()) continue;
    std::string ext = entry.path().extension().string();
    for (const std::string& wanted : extensions)
      if (ext == wanted) files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace sdg::usd::test
