#pragma once
// The Python source files a run's behavior scripts pulled in through
// `import` (modules beside or below a script's folder, not the standard
// library or installed packages): they shape the output as much as the
// scripts themselves, so the run's identity hashes them too.
#include <string>
#include <vector>

namespace sdg::scripting {

// Absolute paths, sorted, without the scripts themselves; empty when no
// script was loaded (the interpreter is not started for that).
std::vector<std::string> importedSourceFiles(const std::vector<std::string>& scriptFiles);

}  // namespace sdg::scripting
