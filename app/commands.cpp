#include "commands.h"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>

#include "core/diagnostics.h"
#include "core/log.h"
#include "scene_io/inspect.h"
#include "scene_io/json_schema.h"
#include "scene_io/scene_loader.h"

namespace sdg::cli {
namespace {

void addSceneArgs(CLI::App& cmd, SceneArgs& args) {
  cmd.add_option("scene", args.scene, "Scene file (YAML)")->required()->type_name("SCENE");
  cmd.add_option("--set", args.overrides,
                 "Override a value after loading: /Prim/Path.attribute=VALUE or section.option=VALUE\n"
                 "(e.g. --set render.resolution=[640,480] --set /Root/Camera.focalLength=35)")
      ->type_name("TARGET=VALUE");
}

BehaviorCatalog catalogFor(const SceneArgs&, const SceneDocument&) { return BehaviorCatalog{}; }

Scene load(const SceneArgs& args) {
  SceneDocument doc = readSceneDocument(args.scene);
  return buildScene(doc, catalogFor(args, doc), args.overrides);
}

size_t behaviorCount(const Scene& scene) {
  size_t n = 0;
  scene.stage.traverse([&](const Prim& p) { n += p.behaviors().size(); });
  return n;
}

}  // namespace

void addValidate(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<SceneArgs>();
  CLI::App* cmd = app.add_subcommand("validate", "Check a scene and report every problem with its file:line:column");
  cmd->footer("Exit status: 0 when the scene is valid, 2 when it is not.");
  addSceneArgs(*cmd, *args);
  cmd->callback([args, &exitCode] {
    Scene scene = load(*args);
    std::printf("%s: valid (%zu prims, %zu behaviors, %zu writers)\n", args->scene.c_str(), scene.stage.primCount(),
                behaviorCount(scene), scene.writers.size());
    exitCode = kExitOk;
  });
}

void addInspect(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<SceneArgs>();
  CLI::App* cmd = app.add_subcommand("inspect", "Print the scene's settings and prim tree (types, transforms, labels, "
                                                "attributes, behaviors)");
  addSceneArgs(*cmd, *args);
  cmd->callback([args, &exitCode] {
    Scene scene = load(*args);
    std::fputs(inspectScene(scene).c_str(), stdout);
    exitCode = kExitOk;
  });
}

void addSchema(CLI::App& app, int& exitCode) {
  auto out = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("schema", "Print the JSON Schema of the scene format (for editors and CI checks)");
  cmd->add_option("-o,--out", *out, "Write to this file instead of standard output")->type_name("FILE");
  cmd->callback([out, &exitCode] {
    std::string schema = sceneJsonSchema(BehaviorCatalog{});
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

}  // namespace sdg::cli
