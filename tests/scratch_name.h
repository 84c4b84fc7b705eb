#pragma once
// A name no other test process uses. CTest runs test cases as separate
// processes in parallel (`ctest -j`), so a scratch file with a fixed name
// can be written by two of them at once; this one carries the process id
// and a per-process count.
#include <atomic>
#include <filesystem>
#include <string>

#include <unistd.h>

namespace sdg::test {

inline std::string uniqueSuffix() {
  static std::atomic<unsigned> counter{0};
  return "." + std::to_string(::getpid()) + "." + std::to_string(counter++);
}

// `stem` + the suffix, in the system's temporary folder.
inline std::filesystem::path uniqueTempPath(const std::string& stem) {
  return std::filesystem::temp_directory_path() / (stem + uniqueSuffix());
}

// A folder of this process's own, made now and removed with everything in
// it when the object goes (a function-local static: at exit).
class ScratchFolder {
 public:
  explicit ScratchFolder(const std::string& stem) : path_(uniqueTempPath(stem)) {
    std::filesystem::create_directories(path_);
  }
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace sdg::test
