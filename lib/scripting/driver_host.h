#pragma once
// What a driver program (`sdgbehave exec PROGRAM.py`: an Isaac Sim Script
// Editor program) asks of the run that executes it, through the `_sdgbehave`
// module's `driver()`: the open stage, opening and saving stages, the app's
// updates and the timeline, and capturing frames through writers. The run
// layer implements it (run/exec_session.h); scripting knows only this
// interface, so the dependency still runs one way.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sdg {
class Stage;
class EventBus;
class AssetResolver;
}  // namespace sdg

namespace sdg::scripting {

struct ScriptContext;

class DriverHost {
 public:
  virtual ~DriverHost() = default;

  // The driver's own context over the open stage (ScriptContext::driver):
  // the same object for the whole program, re-pointed when a stage opens.
  virtual std::shared_ptr<ScriptContext> context() = 0;
  // An empty stage (Z up, metres, 60 time codes a second), or a scene or USD
  // stage read from `path`. Both end the behaviors of the stage before.
  virtual void newStage() = 0;
  virtual void openStage(const std::string& path) = 0;
  // The open stage as a USD layer (.usda) or a YAML scene (.yaml).
  virtual void saveStage(const std::string& path) = 0;
  // The prim at `primPath` (an empty Xform or Scope) becomes the default prim
  // of the USD or YAML file `file` (Isaac's AddReference on a new prim).
  virtual void reference(const std::string& primPath, const std::string& file) = 0;
  // Kit's MovePrim: the prim and its subtree at a new path (renamed or
  // reparented), material bindings into it following; refused for a prim
  // with behaviors running below it.
  virtual void movePrim(const std::string& from, const std::string& to) = 0;
  // The folder get_assets_root_path() answers.
  virtual std::string assetsRoot() const = 0;

  // One app update: newly listed behavior scripts attached, then the
  // runtime's update (events; behaviors' on_update while playing).
  virtual void update() = 0;
  virtual void play() = 0;
  virtual void pause() = 0;
  virtual void stop() = 0;
  virtual bool playing() const = 0;
  virtual double time() const = 0;
  virtual double timeCodesPerSecond() const = 0;
  // rep.set_global_seed: the seed of stages opened from now on and of
  // writers made from now on.
  virtual void setSeed(int64_t seed) = 0;

  // A writer writing into `outDir` with `options` (writer.type and its
  // options by Isaac's names) from the render products `cameras` at one
  // resolution; returns its id. Frames are rendered by capture().
  virtual int attachWriter(const std::string& outDir, const nlohmann::json& options,
                           const std::vector<std::string>& cameras, int width, int height) = 0;
  // The open stage as the next frame of every attached writer.
  virtual void capture() = 0;
  // Finishes a writer's dataset (queued frames written, COCO and manifest).
  virtual void detachWriter(int id) = 0;
  virtual size_t attachedWriters() const = 0;
};

// The host of the program that runs now (null outside `sdgbehave exec`).
void setDriverHost(DriverHost* host);
DriverHost* driverHost();

// Runs the Script Editor program `path` with sys.argv [path, args...]:
// its module-level code, then the asyncio tasks it scheduled, each await of
// the app's next update being one update of the host (driver_host.h), until
// every task is done. A failure is a RunError at the program's file:line
// (`path` as the user gave it; `absolute` is what Python's frames name)
// with the traceback (sys.exit(0) is success). The host must be set.
void runDriverProgram(const std::string& absolute, const std::string& path, const std::vector<std::string>& args);

}  // namespace sdg::scripting
