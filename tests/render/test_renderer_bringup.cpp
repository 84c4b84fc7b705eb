// The renderer brought up on a helper thread (context, programs, shader
// variants) and then used on the test's thread draws what a renderer made
// there would; failures surface where a run would see them.
#include "render_fixtures.h"

#include "core/diagnostics.h"
#include "run/renderer_bringup.h"
#include "run/scene_setup.h"

using namespace sdg;

namespace {

const char* kScene = R"(
version: 1
prims:
  /Looks: {type: Scope}
  /Looks/Wood: {type: Material, inputs:diffuse_texture: textures/wood.png}
  /Floor: {type: Plane, width: 20, length: 20, material: /Looks/Wood, semantics: {class: floor}}
  /A: {type: Cube, size: 1, translate: [-1, 0, 0.5], semantics: {class: box}}
  /B: {type: Sphere, radius: 0.5, translate: [1, 0, 0.5], semantics: {class: ball}}
  /Sun: {type: DistantLight, inputs:intensity: 2000, rotateXYZ: [30, 20, 0]}
  /Lamp: {type: SphereLight, inputs:intensity: 50000, translate: [2, 2, 4]}
  /Cam: {type: Camera, translate: [0, -6, 4], rotateXYZ: [55, 0, 0], clippingRange: [0.1, 100]}
)";

const AssetResolver& assets() {
  static const AssetResolver resolver({SDG_SOURCE_DIR "/scenes", SDG_SOURCE_DIR "/tests/data"});
  return resolver;
}

// The shared context is current on the test thread again when it ends.
struct RestoreSharedContext {
  ~RestoreSharedContext() { test::sharedContext().makeCurrent(); }
};

}  // namespace

TEST_CASE("renderer bring-up: warmed up on a helper thread, it renders the same bytes here", "[render][bringup]") {
  RenderSettings settings = defaultRenderSettings();
  settings.width = settings.height = 80;
  test::RenderedScene direct = test::renderYaml(kScene, settings);
  RestoreSharedContext restore;
  WarmUpFrame warmUp{direct.list, 0, PassSelection{}, std::vector<std::vector<size_t>>{{0}, {1}, {2}}};
  RendererBringUp bringUp(createOsMesaContext, assets(), settings, warmUp);
  Renderer& renderer = bringUp.renderer();
  FramePasses frame;
  renderer.queue(direct.list, 0, PassSelection{}, 1);
  renderer.collect(1, frame);
  CHECK(frame.rgba == direct.frame.rgba);
  CHECK(frame.instanceIds == direct.frame.instanceIds);
  CHECK(frame.distanceToImagePlane == direct.frame.distanceToImagePlane);
  CHECK(bringUp.context().backend() == "osmesa");
}

TEST_CASE("renderer bring-up: compileFor draws nothing that a later frame keeps", "[render][bringup]") {
  RenderSettings settings = defaultRenderSettings();
  settings.width = settings.height = 80;
  test::RenderedScene direct = test::renderYaml(kScene, settings);
  Renderer renderer(test::sharedContext(), assets(), settings);
  const std::vector<std::vector<size_t>> groups{{0}, {1, 2}};
  renderer.compileFor(direct.list, 0, PassSelection{}, &groups);
  FramePasses frame;
  renderer.render(direct.list, 0, frame);
  CHECK(frame.rgba == direct.frame.rgba);
  CHECK(frame.instanceIds == direct.frame.instanceIds);
  // The coverage masks after it are those of a fresh renderer.
  Renderer fresh(test::sharedContext(), assets(), settings);
  Renderer::CoverageMasks warmed, cold;
  renderer.queueCoverage(direct.list, 0, groups, 0);
  renderer.collectCoverage(0, warmed);
  fresh.queueCoverage(direct.list, 0, groups, 0);
  fresh.collectCoverage(0, cold);
  CHECK(warmed.bits == cold.bits);
}

TEST_CASE("renderer bring-up: a context that cannot be made is the caller's error", "[render][bringup]") {
  RestoreSharedContext restore;
  RendererBringUp bringUp([]() -> std::unique_ptr<GlContext> { throw RunError("no back end here"); }, assets(),
                          defaultRenderSettings(), std::nullopt);
  CHECK_THROWS_WITH(bringUp.renderer(), "no back end here");
  CHECK_THROWS_WITH(bringUp.renderer(), "no back end here");  // and stays so
}

TEST_CASE("renderer bring-up: a warm-up frame that fails leaves the error to the frames", "[render][bringup]") {
  RenderSettings settings = defaultRenderSettings();
  settings.width = settings.height = 32;
  test::RenderedScene direct = test::renderYaml(kScene, settings);
  RestoreSharedContext restore;
  WarmUpFrame broken{direct.list, 0, PassSelection{}, std::nullopt};
  broken.list.items[1].mesh.shape = PrimType::Mesh;
  broken.list.items[1].mesh.asset = "props/no_such_mesh.glb";
  broken.list.items[1].meshId.clear();
  RendererBringUp bringUp(createOsMesaContext, assets(), settings, broken);
  Renderer& renderer = bringUp.renderer();  // a fresh renderer, no error yet
  FramePasses frame;
  renderer.render(direct.list, 0, frame);
  CHECK(frame.rgba == direct.frame.rgba);
  CHECK_THROWS_WITH(renderer.render(broken.list, 0, frame), Catch::Contains("no_such_mesh.glb"));
}

TEST_CASE("renderer bring-up: retired in the background, while another renderer goes on drawing", "[render][bringup]") {
  RenderSettings settings = defaultRenderSettings();
  settings.width = settings.height = 48;
  test::RenderedScene direct = test::renderYaml(kScene, settings);
  RestoreSharedContext restore;
  {
    RendererBringUp bringUp(createOsMesaContext, assets(), settings, std::nullopt);
    FramePasses frame;
    bringUp.renderer().render(direct.list, 0, frame);
    CHECK(frame.rgba == direct.frame.rgba);
    bringUp.retireInBackground();
    // This thread has no context now; another one draws while the retired
    // renderer's teardown runs beside it, and the destructor waits for it.
    test::sharedContext().makeCurrent();
    Renderer other(test::sharedContext(), assets(), settings);
    FramePasses again;
    other.render(direct.list, 0, again);
    CHECK(again.rgba == direct.frame.rgba);
  }
}
