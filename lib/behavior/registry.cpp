#include "behavior/registry.h"

#include <dlfcn.h>

#include "behavior/plugin_api.h"
#include "core/diagnostics.h"
#include "core/text.h"

namespace sdg {

void BehaviorRegistry::add(BehaviorSpec spec, BehaviorFactory factory, std::string source) {
  if (catalog_.find(spec.name))
    throw SceneError(SourceLoc{source, 0, 0}, "behavior " + text::quote(spec.name) + " is already registered by " +
                                                  sourceOf(spec.name));
  catalog_.specs.push_back(std::move(spec));
  factories_.push_back(std::move(factory));
  sources_.push_back(std::move(source));
}

void BehaviorRegistry::replaceBuiltin(BehaviorSpec spec, BehaviorFactory factory, std::string source) {
  for (size_t i = 0; i < catalog_.specs.size(); ++i)
    if (catalog_.specs[i].name == spec.name && sources_[i] == "built-in") {
      catalog_.specs[i] = std::move(spec);
      factories_[i] = std::move(factory);
      sources_[i] = std::move(source);
      return;
    }
  add(std::move(spec), std::move(factory), std::move(source));
}

std::unique_ptr<Behavior> BehaviorRegistry::create(std::string_view name) const {
  for (size_t i = 0; i < catalog_.specs.size(); ++i)
    if (catalog_.specs[i].name == name) return factories_[i]();
  return nullptr;
}

const std::string& BehaviorRegistry::sourceOf(std::string_view name) const {
  static const std::string unknown = "(unknown)";
  for (size_t i = 0; i < catalog_.specs.size(); ++i)
    if (catalog_.specs[i].name == name) return sources_[i];
  return unknown;
}

void BehaviorRegistry::loadPlugin(const std::string& path, const SourceLoc& where) {
  auto fail = [&](const std::string& why) { throw SceneError(where, "plugin " + path + ": " + why); };
  // dlopen searches the system paths for a bare name; insist on a path.
  std::string openPath = path.find('/') == std::string::npos ? "./" + path : path;
  void* handle = dlopen(openPath.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) fail(std::string("cannot load: ") + dlerror());
  std::shared_ptr<void> library(handle, [](void* h) { dlclose(h); });
  auto version = reinterpret_cast<SdgPluginAbiVersionFn>(dlsym(handle, "sdgbehave_plugin_abi_version"));
  auto registerFn = reinterpret_cast<SdgPluginRegisterFn>(dlsym(handle, "sdgbehave_plugin_register"));
  if (!version || !registerFn)
    fail("not an sdgbehave plugin (it lacks sdgbehave_plugin_abi_version / sdgbehave_plugin_register; "
         "use SDG_BEHAVIOR_PLUGIN from behavior/plugin_api.h)");
  if (int v = version(); v != SDG_PLUGIN_ABI_VERSION)
    fail("built for plugin ABI version " + std::to_string(v) + ", this sdgbehave loads version " +
         std::to_string(SDG_PLUGIN_ABI_VERSION) + "; rebuild it against this release's headers");
  size_t before = catalog_.specs.size();
  try {
    registerFn(this);
  } catch (const SceneError& e) {
    fail(e.problems().empty() ? std::string(e.what()) : e.problems().front().message);
  }
  for (size_t i = before; i < sources_.size(); ++i) sources_[i] = path;
  libraries_.push_back(std::move(library));
}

}  // namespace sdg
