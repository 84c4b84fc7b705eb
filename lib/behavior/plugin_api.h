#pragma once
// The entry points a behavior plugin exports. A plugin is a shared library
// built against these headers; it states the ABI version it was built for
// and registers its behaviors exactly like the built-ins:
//
//   void registerMine(sdg::BehaviorRegistry& r) { r.add(mySpec(), [] { return std::make_unique<Mine>(); }); }
//   SDG_BEHAVIOR_PLUGIN(registerMine)
//
// Bump the version whenever Behavior, BehaviorSpec or the registry change
// layout; a plugin built for another version is refused with a clear message.
#include "behavior/registry.h"

#define SDG_PLUGIN_ABI_VERSION 3

extern "C" {
typedef int (*SdgPluginAbiVersionFn)(void);
typedef void (*SdgPluginRegisterFn)(sdg::BehaviorRegistry* registry);
}

#define SDG_BEHAVIOR_PLUGIN(registerFunction)                                                      \
  extern "C" __attribute__((visibility("default"))) int sdgbehave_plugin_abi_version(void) {       \
    return SDG_PLUGIN_ABI_VERSION;                                                                 \
  }                                                                                                \
  extern "C" __attribute__((visibility("default"))) void sdgbehave_plugin_register(                \
      sdg::BehaviorRegistry* registry) {                                                           \
    registerFunction(*registry);                                                                   \
  }
