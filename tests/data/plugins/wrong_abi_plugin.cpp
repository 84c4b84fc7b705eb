// A plugin built for another ABI version: sdgbehave must refuse it.
namespace sdg {
class BehaviorRegistry;
}
extern "C" __attribute__((visibility("default"))) int sdgbehave_plugin_abi_version(void) { return 999; }
extern "C" __attribute__((visibility("default"))) void sdgbehave_plugin_register(sdg::BehaviorRegistry*) {}
