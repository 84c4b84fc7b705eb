#pragma once
// A behavior written in Python: the runtime sees an ordinary Behavior; each
// hook calls the script's method of the same name. Around the hooks it keeps
// what a script should not have to: the random stream, the journals that
// undo the script's changes on stop and destroy, and the end of its event
// subscriptions. Each hook runs under the hook watchdog; a Python error, a
// timeout or an attempt to exit in a hook becomes a RunError (exit 1) with
// the traceback, the prim path, the hook and the frame (script_call.h).
#include <memory>
#include <string>

#include <pybind11/pybind11.h>

#include "behavior/behavior.h"
#include "scripting/script_context.h"

namespace sdg::scripting {

class ScriptBehavior final : public Behavior {
 public:
  // `script`: the file defining the class, as shown in messages.
  ScriptBehavior(pybind11::object behaviorClass, std::string rngStream, std::string script);
  ~ScriptBehavior() override;

  void onInit() override;
  void onPlay() override;
  void onUpdate(double time, double dt) override;
  void onPause() override;
  void onStop() override;
  void onDestroy() override;

 private:
  template <typename... Args>
  void call(const pybind11::object& method, const char* hook, Args&&... args);
  void detach();

  pybind11::object class_;
  pybind11::object instance_;
  pybind11::object onUpdate_;  // the bound method, looked up once
  std::shared_ptr<ScriptContext> ctx_;
  bool destroyed_ = false;
};

}  // namespace sdg::scripting
