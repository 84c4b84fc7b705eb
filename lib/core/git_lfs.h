#pragma once
// Git LFS pointer files: what a clone made without `git lfs` holds in place
// of a large file (a few lines of text starting with the spec's URL). Every
// reader of layers, images and meshes names them as such, since "not a USD
// layer" or "bad image header" would hide the fix.
#include <string>
#include <string_view>

namespace sdg {

inline bool isGitLfsPointer(std::string_view head) {
  return head.starts_with("version https://git-lfs.github.com/spec/v1");
}

// "<file> is a Git LFS pointer, not <what>: run git lfs pull ...".
inline std::string gitLfsPointerMessage(const std::string& file, const std::string& what) {
  return file + " is a Git LFS pointer, not " + what +
         ": run git lfs pull in its repository (the clone was made without Git LFS)";
}

}  // namespace sdg
