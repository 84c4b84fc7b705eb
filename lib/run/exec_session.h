#pragma once
// `sdgbehave exec PROGRAM.py`: runs an Isaac Sim Script Editor program (a
// driver that opens or builds a stage, attaches behavior scripts, drives
// events and the timeline, and captures frames through Replicator's
// writers) over sdgbehave's stage, behaviors, renderer and writers. The
// program's Isaac APIs are the Isaac layer's Python modules
// (lib/scripting/isaac_compat); what they ask of the run goes through
// scripting/driver_host.h, implemented here.
#include <cstdint>
#include <string>
#include <vector>

#include "run/scene_setup.h"

namespace sdg {

struct ExecOptions {
  std::string program;
  std::vector<std::string> args;  // sys.argv[1:]
  // What get_assets_root_path() answers: this, else $SDGBEHAVE_ASSETS_ROOT,
  // else the stand-in root sdgbehave ships (isaacStandInRoot()).
  std::string assetsRoot;
  // The program's working folder ("" = the current one): where
  // os.getcwd()-relative output goes.
  std::string outRoot;
  unsigned threads = 0;     // encoding threads of each writer (0 = one per core)
  RenderOverrides render;   // --gpu, --backend, --render-mode, ...
};

struct ExecDataset {
  std::string folder;
  uint64_t frames = 0;
  uint64_t files = 0;
};

struct ExecResult {
  std::vector<ExecDataset> datasets;  // one per writer, in the order they finished
  uint64_t updates = 0;               // app updates the program awaited
  double seconds = 0;
};

// Runs the program to its end. A failure of the program (its exception,
// a behavior's) is a RunError at the program's file:line (exit 1); a
// missing program a SceneError (exit 2). Writers still attached at the end
// are finished; a failure keeps the frames already written.
ExecResult runExec(const ExecOptions& options);

// The stand-in Isaac asset root sdgbehave ships (scenes/isaac-stand-in):
// beside the executable when installed, else in the source tree.
std::string isaacStandInRoot();

}  // namespace sdg
