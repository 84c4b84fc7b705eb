// `new-behavior`: writes a starter behavior script and a scene that uses it.
#include <cstdio>
#include <memory>

#include "commands.h"
#include "scripting/new_behavior.h"

namespace sdg::cli {

void addNewBehavior(CLI::App& app, int& exitCode) {
  struct Args {
    std::string name;
    std::string folder = ".";
    bool events = false;
    bool overwrite = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("new-behavior", "Write a commented starter behavior script (Python) and an "
                                                     "example scene that runs as is");
  cmd->add_option("name", args->name, "The behavior's name (its BEHAVIOR_NS), camelCase, e.g. randomScale")
      ->required()
      ->type_name("NAME");
  cmd->add_flag("--events", args->events,
                "An event-driven behavior (answers NAME.in with NAME.out) instead of a timeline randomizer");
  cmd->add_option("-o,--out", args->folder, "Folder for NAME's .py and .yaml (created if missing)")
      ->type_name("DIR")
      ->capture_default_str();
  cmd->add_flag("--overwrite", args->overwrite, "Replace existing files of the same names");
  cmd->footer("Example:\n  sdgbehave new-behavior randomScale --out my_behaviors\n"
              "  sdgbehave run my_behaviors/random_scale.yaml --frames 6 --out out/random_scale\n"
              "Then edit my_behaviors/random_scale.py (docs/scripting.md lists the API).");
  cmd->callback([args, &exitCode] {
    scripting::NewBehaviorFiles files = scripting::writeNewBehavior(args->name, args->events, args->folder,
                                                                    args->overwrite);
    std::printf("wrote %s\nwrote %s\nnext: sdgbehave run %s --frames 6 --out out/%s\n", files.script.c_str(),
                files.scene.c_str(), files.scene.c_str(), args->name.c_str());
    exitCode = kExitOk;
  });
}

}  // namespace sdg::cli
