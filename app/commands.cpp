#include "commands.h"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <regex>

#include "core/diagnostics.h"
#include "core/log.h"
#include "scene_io/inspect.h"
#include "scene_io/json_schema.h"
#include "scene_io/scene_writer.h"
#include "core/file_io.h"
#include "behavior/describe.h"
#include "core/text.h"
#include "run/scene_setup.h"

namespace sdg::cli {

namespace {
std::vector<std::string>& storedCommandLine() {
  static std::vector<std::string> args;
  return args;
}
}  // namespace

void setCommandLine(std::vector<std::string> args) { storedCommandLine() = std::move(args); }
const std::vector<std::string>& commandLine() { return storedCommandLine(); }

void addSceneArgs(CLI::App& cmd, SceneArgs& args) {
  cmd.add_option("scene", args.scene, "Scene file (YAML)")->required()->type_name("SCENE");
  cmd.add_option("--set", args.overrides,
                 "Override a value after loading: /Prim/Path.attribute=VALUE or section.option=VALUE\n"
                 "(e.g. --set render.resolution=[640,480] --set /Root/Camera.focalLength=35)")
      ->type_name("TARGET=VALUE")
      ->allow_extra_args(false);
  cmd.add_option("--plugin", args.plugins, "Load a behavior plugin library (.so) before reading the scene")
      ->type_name("LIB")
      ->allow_extra_args(false);
  cmd.add_option("--script", args.scripts,
                 "Load a behavior script (.py) before reading the scene, as the scene's scripts: do; repeatable")
      ->type_name("FILE.py")
      ->allow_extra_args(false);
  cmd.add_option("--asset-root", args.assetRoots, "Also search this folder for assets (after the scene's asset_roots)")
      ->type_name("DIR")
      ->allow_extra_args(false);
  cmd.add_option("--isaac-assets", args.isaacAssets,
                 "A local copy of Isaac Sim's asset pack (the folder holding Isaac/): /Isaac/... paths, such as the "
                 "defaults of textureRandomizer and volumeStackRandomizer, resolve below it. Default: "
                 "$SDGBEHAVE_ISAAC_ASSETS, then the scene's isaac_assets:")
      ->type_name("DIR");
  cmd.add_option("--isaac-scripts", args.isaacScripts,
                 "Isaac's six behavior scripts a prim lists in omni:scripting:scripts: auto (the file when it exists, "
                 "else the built-in of its name), builtin (always the built-in) or script (always the file); "
                 "overrides run.isaac_scripts")
      ->check(CLI::IsMember({"auto", "builtin", "script"}))
      ->type_name("CHOICE");
}

void addHookTimeoutArg(CLI::App& cmd, SceneArgs& args) {
  cmd.add_option("--hook-timeout", args.hookTimeout,
                 "Seconds one call into a behavior script may take before the run stops with an error naming the "
                 "prim, behavior, hook, frame and script line; 0: no limit (overrides run.hook_timeout, default 60)")
      ->check(CLI::NonNegativeNumber)
      ->type_name("SECONDS");
}

SceneRequest sceneRequest(const SceneArgs& args) {
  return SceneRequest{.scenePath = args.scene,
                      .overrides = args.overrides,
                      .plugins = args.plugins,
                      .scripts = args.scripts,
                      .assetRoots = args.assetRoots,
                      .isaacAssets = args.isaacAssets,
                      .hookTimeout = args.hookTimeout,
                      .isaacScripts = args.isaacScripts};
}

void addImageArgs(CLI::App& cmd, ImageArgs& args) {
  cmd.add_option("--resolution", args.resolution, "Image size, e.g. 640x480 (overrides render.resolution)")
      ->type_name("WxH");
  cmd.add_option("--subframes", args.subframes, "Anti-aliasing samples (overrides render.subframes)")
      ->check(CLI::Range(1, 64))
      ->type_name("K");
  cmd.add_option("--backend", args.backend,
                 "GL back end: auto (an EGL GPU when present, else OSMesa), osmesa (CPU), egl (GPU, or Mesa's "
                 "surfaceless llvmpipe without one); overrides render.backend")
      ->check(CLI::IsMember({"auto", "osmesa", "egl"}))
      ->type_name("NAME");
  cmd.add_option("--gpu", args.gpu, "EGL GPU device index (0-based); one process per GPU, with --shard")
      ->check(CLI::Range(0, 1023))
      ->type_name("N");
  cmd.add_option("--render-mode", args.renderMode,
                 "Colour from the rasterizer (raster: fast) or the CPU path tracer (pathtraced: physically based, "
                 "soft shadows, bounced light); labels always come from the rasterizer; overrides render.mode")
      ->check(CLI::IsMember({"raster", "pathtraced"}))
      ->type_name("MODE");
  cmd.add_option("--samples", args.samples, "Path-traced samples per pixel (overrides render.samples)")
      ->check(CLI::Range(1, 1 << 20))
      ->type_name("N");
  cmd.add_flag("--denoise", args.denoise, "Denoise path-traced colour (sets render.denoise)");
}

std::pair<int, int> parseResolution(const std::string& text) {
  std::smatch m;
  static const std::regex pattern("([0-9]{1,5})x([0-9]{1,5})");
  if (!std::regex_match(text, m, pattern) || std::stoi(m[1]) < 1 || std::stoi(m[2]) < 1 ||
      std::stoi(m[1]) > 16384 || std::stoi(m[2]) > 16384)
    throw SceneError(SourceLoc{"--resolution", 0, 0},
                     "expected WIDTHxHEIGHT with each side 1 to 16384 (e.g. 640x480), found '" + text + "'");
  return {std::stoi(m[1]), std::stoi(m[2])};
}

RenderOverrides renderOverrides(const ImageArgs& args) {
  RenderOverrides o;
  if (!args.resolution.empty()) {
    auto [w, h] = parseResolution(args.resolution);
    o.width = w;
    o.height = h;
  }
  o.subframes = args.subframes;
  if (!args.backend.empty()) o.backend = args.backend;
  o.gpu = args.gpu;
  if (!args.renderMode.empty()) o.mode = args.renderMode;
  o.samples = args.samples;
  if (args.denoise) o.denoise = true;
  return o;
}

namespace {

LoadedScene load(const SceneArgs& args) {
  LoadedScene loaded = loadSceneForRun(sceneRequest(args));
  printDropped(loaded);
  return loaded;
}

size_t behaviorCount(const Scene& scene) {
  size_t n = 0;
  scene.stage.traverse([&](const Prim& p) { n += p.behaviors().size(); });
  return n;
}

}  // namespace

void printDropped(const LoadedScene& loaded) {
  for (const DroppedWarning& d : loaded.dropped) log::dropped(d);
}

void addValidate(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<SceneArgs>();
  auto strict = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("validate", "Check a scene and report every problem with its file:line:column");
  cmd->footer("Exit status: 0 when the scene is valid, 2 when it is not (with --strict, also when a USD file has\n"
              "something the stage would drop: an unread prim type, schema, material network...).");
  addSceneArgs(*cmd, *args);
  cmd->add_flag("--strict", *strict, "Fail (exit 2) when anything in the scene's USD files would be dropped");
  cmd->callback([args, strict, &exitCode] {
    const LoadedScene loaded = load(*args);
    const Scene& scene = loaded.scene;
    if (*strict && !loaded.dropped.empty()) {
      std::printf("%s: invalid under --strict: %zu kinds of content would be dropped (listed above)\n",
                  args->scene.c_str(), loaded.dropped.size());
      exitCode = kExitInvalid;
      return;
    }
    std::printf("%s: valid (%zu prims, %zu behaviors, %zu writers)%s\n", args->scene.c_str(), scene.stage.primCount(),
                behaviorCount(scene), scene.writers.size(),
                loaded.dropped.empty() ? "" : (", " + std::to_string(loaded.dropped.size()) + " kinds of content dropped").c_str());
    exitCode = kExitOk;
  });
}

void addInspect(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<SceneArgs>();
  CLI::App* cmd = app.add_subcommand("inspect", "Print the scene's settings and prim tree (types, transforms, labels, "
                                                "attributes, behaviors)");
  addSceneArgs(*cmd, *args);
  cmd->callback([args, &exitCode] {
    std::fputs(inspectScene(load(*args).scene).c_str(), stdout);
    exitCode = kExitOk;
  });
}

void addFlatten(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<SceneArgs>();
  auto out = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("flatten", "Write the scene as one self-contained file: references to smart "
                                                "assets expanded, paths absolute");
  addSceneArgs(*cmd, *args);
  cmd->add_option("-o,--out", *out, "Write to this file instead of standard output")->type_name("FILE");
  cmd->footer("The flattened file reloads to the same stage and runs to byte-identical output.\n"
              "Example:\n  sdgbehave flatten scenes/warehouse.yaml -o /tmp/warehouse_flat.yaml");
  cmd->callback([args, out, &exitCode] {
    LoadedScene loaded = load(*args);
    std::string yaml = writeSceneYaml(flattenedScene(loaded), loaded.registry.catalog());
    if (out->empty()) std::fputs(yaml.c_str(), stdout);
    else writeFileAtomic(*out, yaml);
    exitCode = kExitOk;
  });
}

void addSchema(CLI::App& app, int& exitCode) {
  auto out = std::make_shared<std::string>();
  auto plugins = std::make_shared<std::vector<std::string>>();
  auto scripts = std::make_shared<std::vector<std::string>>();
  CLI::App* cmd = app.add_subcommand("schema", "Print the JSON Schema of the scene format (for editors and CI checks)");
  cmd->add_option("-o,--out", *out, "Write to this file instead of standard output")->type_name("FILE");
  cmd->add_option("--plugin", *plugins, "Include the behaviors of this plugin library")->type_name("LIB")->allow_extra_args(false);
  cmd->add_option("--script", *scripts, "Include the behaviors of this script (.py)")->type_name("FILE.py")->allow_extra_args(false);
  cmd->callback([out, plugins, scripts, &exitCode] {
    std::string schema = sceneJsonSchema(registryWithPlugins(*plugins, *scripts).catalog());
    if (out->empty()) {
      std::fputs(schema.c_str(), stdout);
    } else {
      std::ofstream file(*out, std::ios::binary);
      file << schema;
      if (!file.flush()) throw RunError("cannot write " + *out);
    }
    exitCode = kExitOk;
  });
}

void addDescribe(CLI::App& app, int& exitCode) {
  auto name = std::make_shared<std::string>();
  auto plugins = std::make_shared<std::vector<std::string>>();
  auto format = std::make_shared<std::string>("text");
  auto scripts = std::make_shared<std::vector<std::string>>();
  CLI::App* cmd = app.add_subcommand("describe", "List the behaviors, or one behavior's exposed variables "
                                                 "(type, default, documentation)");
  cmd->add_option("name", *name, "A behavior name, e.g. locationRandomizer")->type_name("NAME");
  cmd->add_option("--plugin", *plugins, "Include the behaviors of this plugin library")->type_name("LIB")->allow_extra_args(false);
  cmd->add_option("--script", *scripts, "Include the behaviors of this script (.py)")->type_name("FILE.py")->allow_extra_args(false);
  cmd->add_option("--format", *format,
                  "text for people; json for tools and editors: every behavior with its variables' name, "
                  "attribute, type, default, doc and bounds")
      ->check(CLI::IsMember({"text", "json"}))
      ->capture_default_str();
  cmd->footer("Examples:\n  sdgbehave describe\n  sdgbehave describe locationRandomizer\n"
              "  sdgbehave describe --format json > behaviors.json");
  cmd->callback([name, plugins, scripts, format, &exitCode] {
    BehaviorRegistry registry = registryWithPlugins(*plugins, *scripts);
    const bool json = *format == "json";
    if (name->empty()) {
      std::fputs((json ? describeBehaviorsJson(registry) : describeBehaviors(registry)).c_str(), stdout);
    } else {
      std::string text = json ? describeBehaviorsJson(registry, *name) : describeBehavior(registry, *name);
      if (text.empty()) {
        std::vector<std::string> names = registry.catalog().names();
        std::string suggestion = text::didYouMean(*name, names);
        throw SceneError(SourceLoc{}, "unknown behavior " + text::quote(*name) + "; known behaviors: " +
                                          text::join(names, ", ") +
                                          (suggestion.empty() ? std::string(text::kScriptNotLoadedHint) : suggestion));
      }
      std::fputs(text.c_str(), stdout);
    }
    exitCode = kExitOk;
  });
}

}  // namespace sdg::cli
