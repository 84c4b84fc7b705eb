// HDR domes and material maps on the rasterizer, on real OSMesa output:
// the dome's orientation, its pre-filtered lighting against the analytic
// irradiance, roughness / metallic / ORM / normal / opacity maps, and
// textures embedded in glTF files against the same textures as files.
#include "render_fixtures.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>

#include "run/scene_setup.h"
#include "render/raster/environment_map.h"
#include "render/latlong.h"
#include "test_images.h"
#include "writers/png_encoder.h"

using namespace sdg;
using sdg::test::writePng;
using sdg::test::writeRgbe;
namespace fs = std::filesystem;

namespace {

fs::path scratchFolder(const std::string& name) {
  fs::path dir = fs::path(SDG_BINARY_DIR) / "dome_and_maps" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}


// Every camera of a scene rendered with one renderer.
std::vector<FramePasses> renderCameras(const std::string& yaml, RenderSettings settings) {
  Scene scene = buildScene(sceneDocumentFromText(yaml, "t.yaml"), builtinRegistry().catalog());
  RenderList list = buildRenderList(scene.stage);
  const AssetResolver assets({SDG_SOURCE_DIR "/scenes", SDG_SOURCE_DIR "/tests/data"});
  Renderer renderer(test::sharedContext(), assets, settings);
  std::vector<FramePasses> frames(list.cameras.size());
  for (size_t c = 0; c < list.cameras.size(); ++c) renderer.render(list, c, frames[c]);
  return frames;
}

const uint8_t* pixel(const FramePasses& f, int x, int y) {
  return f.rgba.data() + (size_t(y) * size_t(f.width) + size_t(x)) * 4;
}

double srgbDecode(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

// Linear radiance from an 8-bit output code: the tone curve undone.
double radianceOf(int code, double exposureScale) {
  return -std::log(1.0 - srgbDecode(code / 255.0)) / exposureScale;
}

// Mean radiance of the central 8 x 8 pixels of channel c.
double centralRadiance(const FramePasses& f, int c, double exposureScale) {
  double sum = 0;
  for (int y = f.height / 2 - 4; y < f.height / 2 + 4; ++y)
    for (int x = f.width / 2 - 4; x < f.width / 2 + 4; ++x) sum += radianceOf(pixel(f, x, y)[c], exposureScale);
  return sum / 64.0;
}

}  // namespace

TEST_CASE("dome: the camera sees the map in OpenEXR's lat-long orientation, its pole on the stage's up axis",
          "[render][dome]") {
  const fs::path dir = scratchFolder("orientation");
  // Sectors by longitude (OpenEXR: u = 0.25 looks along the dome's +X, 0.5
  // along +Z, 0.75 along -X) and a yellow cap at the pole.
  test::writeSectorSky(dir / "sectors.hdr");
  // Z-up stage: the dome's +Y turns to +Z, so its +X stays +X, +Z becomes
  // -Y and -Z becomes +Y. Cameras at the origin look along each axis.
  const std::string yaml = "version: 1\nprims:\n  /Sky: {type: DomeLight, inputs:intensity: 250, inputs:texture:file: " +
                           (dir / "sectors.hdr").string() + R"(}
  /PlusX: {type: Camera, focalLength: 50, rotateXYZ: [90, 0, -90]}
  /MinusY: {type: Camera, focalLength: 50, rotateXYZ: [90, 0, 180]}
  /MinusX: {type: Camera, focalLength: 50, rotateXYZ: [90, 0, 90]}
  /PlusY: {type: Camera, focalLength: 50, rotateXYZ: [90, 0, 0]}
  /Up: {type: Camera, focalLength: 50, rotateXYZ: [180, 0, 0]}
)";
  RenderSettings settings = defaultRenderSettings();
  settings.width = settings.height = 16;
  const std::vector<FramePasses> frames = renderCameras(yaml, settings);
  REQUIRE(frames.size() == 5);
  // 4 x 250 = 1000 radiance: 1 - exp(-2) = 0.865 -> sRGB code 240.
  const std::array<std::array<int, 3>, 5> expected = {
      {{240, 0, 0}, {0, 240, 0}, {0, 0, 240}, {240, 240, 240}, {240, 240, 0}}};
  for (size_t c = 0; c < frames.size(); ++c) {
    INFO("camera " << c);
    const uint8_t* centre = pixel(frames[c], 8, 8);
    for (int k = 0; k < 3; ++k) CHECK(std::abs(int(centre[k]) - expected[c][size_t(k)]) <= 2);
  }
}

TEST_CASE("dome: one bright patch lights a diffuse plane with the analytic irradiance, by the cosine law",
          "[render][dome]") {
  const fs::path dir = scratchFolder("irradiance");
  // A 2 x 2 texel patch centred on the dome's +X (world +X on a Z-up stage).
  const int w = 64, h = 32;
  const float patch = 1000.0f;
  auto texel = [&](int x, int y) {
    return (x == 15 || x == 16) && (y == 15 || y == 16) ? Vec3f(patch, patch, patch) : Vec3f(0, 0, 0);
  };
  writeRgbe(dir / "patch.hdr", w, h, texel);
  // Its irradiance on a surface facing +X, integrated over the texels'
  // exact areas: E = integral of L cos(theta) d(omega).
  double irradiance = 0;
  const int n = 64;
  for (int y = 15; y <= 16; ++y)
    for (int x = 15; x <= 16; ++x)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const float u = (x + (i + 0.5f) / n) / w, v = (y + (j + 0.5f) / n) / h;
          const Vec3f d = directionFromLatLong(u, v);
          const double solidAngle = (2 * std::numbers::pi / (w * n)) * (std::numbers::pi / (h * n)) *
                                    std::sin(v * std::numbers::pi);
          irradiance += patch * std::max(0.0f, d.x()) * solidAngle;
        }
  const double intensity = 4.0;  // inputs:intensity scales the map
  const double albedo = 0.8;
  // The 4 % dielectric specular of the material: the split-sum terms the
  // shader uses (at N.V = 1, roughness 1), with the pre-filtered map's value
  // along the mirror direction (+X, the patch).
  const SplitSumLut lut = integrateSplitSumLut();
  const float* ab = &lut.scaleBias[2 * size_t((lut.size - 1) * lut.size + lut.size - 1)];
  const double specularAlbedo = 0.04 * ab[0] + ab[1];
  ImageRgbaF map{uint32_t(w), uint32_t(h), std::vector<float>(size_t(w) * h * 4, 1.0f)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < 3; ++k) map.pixels[(size_t(y) * w + x) * 4 + k] = texel(x, y)[k];
  const PrefilteredEnvironment env = prefilterEnvironment(map);
  const double specular = sampleBilinear(env.specular.back(), Vec3f(1, 0, 0)).x() * specularAlbedo;
  const double expected = intensity * (albedo * irradiance / std::numbers::pi + specular);
  INFO("diffuse " << intensity * albedo * irradiance / std::numbers::pi << ", specular "
                  << intensity * specular);

  // Planes facing the patch head-on and turned 60 degrees from it, each
  // seen along its normal by an orthographic camera.
  const std::string yaml = "version: 1\nprims:\n  /Sky: {type: DomeLight, inputs:intensity: 4, inputs:texture:file: " +
                           (dir / "patch.hdr").string() + R"(}
  /Looks: {type: Scope}
  /Looks/Matte: {type: Material, inputs:diffuse_color_constant: [0.8, 0.8, 0.8], inputs:reflection_roughness_constant: 1.0}
  /Facing: {type: Plane, axis: X, width: 4, length: 4, material: /Looks/Matte}
  /FacingCam: {type: Camera, projection: orthographic, horizontalAperture: 10, translate: [5, 0, 0], rotateXYZ: [90, 0, 90], clippingRange: [0.1, 100]}
  /Turned: {type: Plane, axis: X, width: 4, length: 4, material: /Looks/Matte, translate: [0, 50, 0], rotateXYZ: [0, 0, 60]}
  /TurnedCam: {type: Camera, projection: orthographic, horizontalAperture: 10, translate: [2.5, 54.330127, 0], rotateXYZ: [90, 0, 150], clippingRange: [0.1, 100]}
  /AwayCam: {type: Camera, projection: orthographic, horizontalAperture: 10, translate: [-5, 0, 0], rotateXYZ: [90, 0, -90], clippingRange: [0.1, 100]}
)";
  RenderSettings settings = defaultRenderSettings();
  settings.width = settings.height = 32;
  const std::vector<FramePasses> frames = renderCameras(yaml, settings);
  const double facing = centralRadiance(frames[0], 0, settings.exposureScale);
  CHECK(std::abs(facing / expected - 1.0) < 0.02);
  // Turned 60 degrees: the diffuse part halves (cos 60); the specular part
  // is small and only bounded here.
  const double turned = centralRadiance(frames[1], 0, settings.exposureScale);
  const double diffuseTurned = intensity * albedo * irradiance / std::numbers::pi * 0.5;
  CHECK(turned > diffuseTurned * 0.98);
  CHECK(turned < diffuseTurned + intensity * specular * 1.5);
  // The back of the plane faces away from the patch: no light at all.
  CHECK(centralRadiance(frames[2], 0, settings.exposureScale) < 0.01 * facing);
}

TEST_CASE("material maps: a map with influence 1 equals the same constant, ORM packs roughness and metallic",
          "[render][maps]") {
  const fs::path dir = scratchFolder("maps");
  auto grey = [](uint8_t v) { return [v](int, int) { return std::array<uint8_t, 4>{v, v, v, 255}; }; };
  writePng(dir / "rough.png", 8, 8, grey(51));    // 0.2
  writePng(dir / "metal.png", 8, 8, grey(255));   // 1
  writePng(dir / "orm.png", 8, 8, [](int, int) { return std::array<uint8_t, 4>{255, 51, 255, 255}; });
  const std::string d = dir.string() + "/";
  // A glossy gold-ish plane under a light placed for a highlight.
  auto scene = [&](const std::string& material) {
    return "version: 1\nprims:\n  /Looks: {type: Scope}\n  /Looks/M: {type: Material, inputs:diffuse_color_constant: [0.9, 0.6, 0.2], " +
           material + R"(}
  /Floor: {type: Plane, width: 20, length: 20, material: /Looks/M}
  /Sun: {type: DistantLight, inputs:intensity: 2000, rotateXYZ: [-40, 0, 0]}
  /Cam: {type: Camera, focalLength: 18, translate: [0, -6, 4], rotateXYZ: [60, 0, 0], clippingRange: [0.1, 100]}
)";
  };
  RenderSettings settings = defaultRenderSettings();
  settings.width = settings.height = 48;
  auto render = [&](const std::string& material) { return test::renderYaml(scene(material), settings).frame.rgba; };
  const auto constant = render("inputs:reflection_roughness_constant: 0.2, inputs:metallic_constant: 1.0");
  const auto mapped = render("inputs:reflection_roughness_constant: 0.9, inputs:reflectionroughness_texture: " + d +
                             "rough.png, inputs:reflection_roughness_texture_influence: 1, inputs:metallic_constant: 0, "
                             "inputs:metallic_texture: " + d + "metal.png, inputs:metallic_texture_influence: 1");
  const auto orm = render("inputs:reflection_roughness_constant: 0.9, inputs:enable_ORM_texture: true, inputs:ORM_texture: " +
                          d + "orm.png, inputs:reflection_roughness_texture_influence: 1, inputs:metallic_texture_influence: 1");
  const auto ignored = render("inputs:reflection_roughness_constant: 0.9, inputs:reflectionroughness_texture: " + d +
                              "rough.png, inputs:metallic_constant: 1.0");  // influence 0 (OmniPBR's default)
  const auto rough = render("inputs:reflection_roughness_constant: 0.9, inputs:metallic_constant: 1.0");
  int worstMapped = 0, worstOrm = 0, worstIgnored = 0, differs = 0;
  for (size_t i = 0; i < constant.size(); ++i) {
    worstMapped = std::max(worstMapped, std::abs(int(constant[i]) - int(mapped[i])));
    worstOrm = std::max(worstOrm, std::abs(int(constant[i]) - int(orm[i])));
    worstIgnored = std::max(worstIgnored, std::abs(int(rough[i]) - int(ignored[i])));
    differs = std::max(differs, std::abs(int(constant[i]) - int(rough[i])));
  }
  CHECK(worstMapped <= 1);
  CHECK(worstOrm <= 1);
  CHECK(worstIgnored <= 1);
  CHECK(differs > 40);  // the roughness matters in this view, so the checks above can fail
}

TEST_CASE("material maps: a normal map tilts the shading toward the image's top, as the base colour shows it",
          "[render][maps]") {
  const fs::path dir = scratchFolder("normal");
  // Top half red: where is the image's top on screen?
  writePng(dir / "top_red.png", 8, 8, [](int, int y) {
    return y < 4 ? std::array<uint8_t, 4>{255, 0, 0, 255} : std::array<uint8_t, 4>{0, 0, 255, 255};
  });
  // Every texel's normal tilted 45 degrees toward the image's top (+Y).
  writePng(dir / "tilt_up.png", 8, 8, [](int, int) { return std::array<uint8_t, 4>{128, 218, 218, 255}; });
  const std::string d = dir.string() + "/";
  RenderSettings settings = defaultRenderSettings();
  settings.width = settings.height = 32;
  const std::string camera =
      "  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 40, verticalAperture: 40, translate: [0, 0, 10], clippingRange: [0.1, 100]}\n";
  auto look = test::renderYaml("version: 1\nprims:\n  /Looks: {type: Scope}\n  /Looks/M: {type: Material, inputs:diffuse_texture: " + d +
                                   "top_red.png}\n  /Card: {type: Plane, width: 4, length: 4, material: /Looks/M}\n"
                                   "  /Sky: {type: DomeLight, inputs:intensity: 500}\n" + camera,
                               settings);
  // +1 when the image's top is at the screen's top (world +Y), else -1.
  const int topSign = pixel(look.frame, 16, 4)[0] > pixel(look.frame, 16, 4)[2] ? 1 : -1;
  const bool bottomRed = pixel(look.frame, 16, 28)[0] > pixel(look.frame, 16, 28)[2];
  CHECK(bottomRed == (topSign < 0));  // the other half at the other end
  // A grazing light from the image's top side, then from the other side.
  auto brightness = [&](bool mapped, int side) {
    const std::string normal = mapped ? ", inputs:normalmap_texture: " + d + "tilt_up.png" : "";
    const std::string yaml = "version: 1\nprims:\n  /Looks: {type: Scope}\n  /Looks/M: {type: Material, inputs:diffuse_color_constant: [0.8, 0.8, 0.8], "
                             "inputs:reflection_roughness_constant: 1" + normal +
                             "}\n  /Card: {type: Plane, width: 4, length: 4, material: /Looks/M}\n"
                             "  /Sun: {type: DistantLight, inputs:intensity: 1500, rotateXYZ: [" +
                             std::to_string(-60 * topSign * side) + ", 0, 0]}\n" + camera;
    return int(pixel(test::renderYaml(yaml, settings).frame, 16, 16)[1]);
  };
  CHECK(brightness(true, 1) > brightness(false, 1) + 30);
  CHECK(brightness(true, -1) < brightness(false, -1) - 30);
}

TEST_CASE("material maps: an opacity cut-out shows what lies behind it, in colour and in the instance ids",
          "[render][maps]") {
  const fs::path dir = scratchFolder("opacity");
  writePng(dir / "left_clear.png", 8, 8, [](int x, int) {
    const uint8_t v = x < 4 ? 0 : 255;
    return std::array<uint8_t, 4>{v, v, v, 255};
  });
  const std::string yaml = "version: 1\nprims:\n  /Looks: {type: Scope}\n"
                           "  /Looks/Red: {type: Material, inputs:diffuse_color_constant: [0.8, 0.05, 0.05]}\n"
                           "  /Looks/Card: {type: Material, inputs:diffuse_color_constant: [0.05, 0.05, 0.8], inputs:enable_opacity: true, "
                           "inputs:enable_opacity_texture: true, inputs:opacity_threshold: 0.5, inputs:opacity_texture: " +
                           (dir / "left_clear.png").string() + R"(}
  /Floor: {type: Plane, width: 20, length: 20, material: /Looks/Red}
  /Card: {type: Plane, width: 4, length: 4, translate: [0, 0, 1], material: /Looks/Card}
  /Sky: {type: DomeLight, inputs:intensity: 500}
  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 40, translate: [0, 0, 10], clippingRange: [0.1, 100]}
)";
  RenderSettings settings = defaultRenderSettings();
  settings.width = settings.height = 32;
  const auto r = test::renderYaml(yaml, settings);
  const uint32_t floorId = r.list.items[0].instanceId, cardId = r.list.items[1].instanceId;
  // The card covers pixels 8..23; its left half (x < 16) is cut out.
  CHECK(r.frame.instanceIds[size_t(16 * 32 + 11)] == floorId);
  CHECK(r.frame.instanceIds[size_t(16 * 32 + 20)] == cardId);
  CHECK(pixel(r.frame, 11, 16)[0] > pixel(r.frame, 11, 16)[2]);  // red floor through the hole
  CHECK(pixel(r.frame, 20, 16)[2] > pixel(r.frame, 20, 16)[0]);  // the blue card
}

namespace {

std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = uint32_t(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= uint32_t(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) v |= bytes[i + 2];
    out += digits[(v >> 18) & 63];
    out += digits[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? digits[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? digits[v & 63] : '=';
  }
  return out;
}

// A glTF quad (2 x 2 units in XY, +Z normal, uvs 0..1) whose material's
// base colour texture is `imageUri`: a file name or a data URI.
std::string gltfQuad(const std::string& imageUri) {
  std::vector<uint8_t> buffer;
  auto put = [&](const void* data, size_t size) {
    const auto* p = static_cast<const uint8_t*>(data);
    buffer.insert(buffer.end(), p, p + size);
  };
  const float positions[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  const float normals[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const float uvs[] = {0, 1, 1, 1, 1, 0, 0, 0};
  const uint16_t indices[] = {0, 1, 2, 0, 2, 3};
  put(positions, sizeof positions);
  put(normals, sizeof normals);
  put(uvs, sizeof uvs);
  put(indices, sizeof indices);
  return R"({"asset": {"version": "2.0"},
  "scenes": [{"nodes": [0]}], "scene": 0, "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
  "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0, "roughnessFactor": 1}}],
  "textures": [{"source": 0}], "images": [{"uri": ")" + imageUri + R"("}],
  "buffers": [{"byteLength": 140, "uri": "data:application/octet-stream;base64,)" + base64(buffer) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 96, "byteLength": 32}, {"buffer": 0, "byteOffset": 128, "byteLength": 12}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
    {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}]})";
}

}  // namespace

TEST_CASE("embedded textures: a glTF's embedded base colour renders as the same texture given as a file",
          "[render][maps][embedded]") {
  const fs::path dir = scratchFolder("embedded");
  writePng(dir / "quadrants.png", 16, 16, [](int x, int y) {
    return std::array<uint8_t, 4>{uint8_t(x < 8 ? 230 : 20), uint8_t(y < 8 ? 200 : 30), uint8_t((x + y) * 7), 255};
  });
  std::ifstream in(dir / "quadrants.png", std::ios::binary);
  const std::vector<uint8_t> png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(dir / "external.gltf") << gltfQuad("quadrants.png");
  std::ofstream(dir / "embedded.gltf") << gltfQuad("data:image/png;base64," + base64(png));

  const AssetResolver assets({dir.string()});
  MeshKey key;
  key.shape = PrimType::Mesh;
  key.asset = (dir / "embedded.gltf").string();
  const MeshData embedded = meshDataFor(key, assets, "/Quad");
  REQUIRE(embedded.embeddedImages.size() == 1);
  CHECK(embedded.parts.at(0).maps.baseColor.rfind("embedded:", 0) == 0);

  RenderSettings settings = defaultRenderSettings();
  settings.width = settings.height = 32;
  auto render = [&](const std::string& file) {
    return test::renderYaml("version: 1\nprims:\n  /Quad: {type: Mesh, asset: " + (dir / file).string() +
                                "}\n  /Sky: {type: DomeLight, inputs:intensity: 800}\n"
                                "  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 30, verticalAperture: 30, "
                                "translate: [0, 0, 10], clippingRange: [0.1, 100]}\n",
                            settings)
        .frame.rgba;
  };
  const std::vector<uint8_t> fromFile = render("external.gltf"), fromMemory = render("embedded.gltf");
  CHECK(fromFile == fromMemory);
  // The texture shows: the quad's left and right halves differ in red.
  CHECK(int(fromFile[(16 * 32 + 8) * 4]) - int(fromFile[(16 * 32 + 24) * 4]) > 100);
}
