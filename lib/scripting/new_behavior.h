#pragma once
// `sdgbehave new-behavior NAME [--events]`: a commented starter script and
// an example scene that runs as is, for a user to copy and edit.
#include <string>

namespace sdg::scripting {

struct NewBehaviorFiles {
  std::string script;  // <folder>/<snake_name>.py
  std::string scene;   // <folder>/<snake_name>.yaml
};

// Writes both files into `folder` (created if missing). NAME is the
// behavior's namespace, a camelCase identifier; `events` picks the
// event-driven template instead of the timeline one. Existing files are
// kept (SceneError, exit 2) unless `overwrite`.
NewBehaviorFiles writeNewBehavior(const std::string& name, bool events, const std::string& folder, bool overwrite);

// "randomScale" -> "random_scale".
std::string snakeCase(const std::string& camelCase);

}  // namespace sdg::scripting
