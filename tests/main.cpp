// The unit tests' entry point: Catch's runner, after what every program that
// draws scenes installs when it starts (the USD mesh reader, for `asset:
// x.usd` meshes).
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#ifdef SDG_INSTALL_SCENE_FORMATS
#include "scene_io/usd_mesh_asset.h"
#endif

int main(int argc, char** argv) {
#ifdef SDG_INSTALL_SCENE_FORMATS
  sdg::registerUsdMeshAssets();
#endif
  return Catch::Session().run(argc, argv);
}
