#pragma once
// Each subcommand: an options struct, a function that adds it to the CLI
// and a function that runs it. Run functions return the exit code or throw;
// main() maps exceptions to exit codes.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "run/scene_setup.h"

namespace sdg::cli {

// Exit codes shell scripts and schedulers can rely on.
inline constexpr int kExitOk = 0;
inline constexpr int kExitRunFailure = 1;
inline constexpr int kExitInvalid = 2;

struct SceneArgs {
  std::string scene;
  std::vector<std::string> overrides;
  std::vector<std::string> plugins;
  std::vector<std::string> scripts;
  std::vector<std::string> assetRoots;
  std::string isaacAssets;
  std::optional<double> hookTimeout;  // --hook-timeout (run only)
  std::string isaacScripts;           // --isaac-scripts ("" = run.isaac_scripts)
};
// What the library needs to load the scene the arguments name.
SceneRequest sceneRequest(const SceneArgs& args);

// "sdgbehave 0.1.0 (git describe)"
std::string versionText();

// The arguments the program was started with (argv[1..]), for commands
// that start workers with the same ones (run --gpus).
void setCommandLine(std::vector<std::string> args);
const std::vector<std::string>& commandLine();

// "640x480" -> (640, 480); anything else is a usage error (exit 2).
std::pair<int, int> parseResolution(const std::string& text);

// SCENE, --set, --plugin, --script, --asset-root and --isaac-assets, shared
// by every scene command.
void addSceneArgs(CLI::App& cmd, SceneArgs& args);
// --hook-timeout, for the commands that run behaviors.
void addHookTimeoutArg(CLI::App& cmd, SceneArgs& args);

// --resolution, --subframes, --backend and --gpu, shared by run and render.
struct ImageArgs {
  std::string resolution;  // "" = render.resolution
  std::optional<int> subframes;
  std::string backend;     // "" = render.backend
  int gpu = -1;
  std::string renderMode;  // "" = render.mode
  std::optional<int> samples;
  bool denoise = false;    // --denoise: on whatever render.denoise says
};
void addImageArgs(CLI::App& cmd, ImageArgs& args);
// The overrides they give (a bad --resolution is a usage error, exit 2).
RenderOverrides renderOverrides(const ImageArgs& args);

// Prints what the scene's USD files have that the stage does not carry
// over (one warning per kind of loss; docs/usd.md "What is dropped").
void printDropped(const LoadedScene& loaded);

void addValidate(CLI::App& app, int& exitCode);
void addInspect(CLI::App& app, int& exitCode);
void addSchema(CLI::App& app, int& exitCode);
void addDescribe(CLI::App& app, int& exitCode);
void addRun(CLI::App& app, int& exitCode);
void addRender(CLI::App& app, int& exitCode);
void addVerify(CLI::App& app, int& exitCode);
void addMerge(CLI::App& app, int& exitCode);
void addNewBehavior(CLI::App& app, int& exitCode);
void addFlatten(CLI::App& app, int& exitCode);
void addExportUsd(CLI::App& app, int& exitCode);
void addExec(CLI::App& app, int& exitCode);
void addStudio(CLI::App& app, int& exitCode);

}  // namespace sdg::cli
