#include "stage/prim_types.h"

#include <string>

namespace sdg {
namespace {

AttributeSpec attr(std::string name, Value fallback, std::string doc) {
  return makeAttributeSpec(std::move(name), std::move(fallback), std::move(doc));
}

AttributeSpec tokenAttr(std::string name, std::string fallback, std::vector<std::string> allowed,
                        std::string doc) {
  AttributeSpec spec = attr(std::move(name), Value::makeToken(std::move(fallback)), std::move(doc));
  spec.allowedTokens = std::move(allowed);
  return spec;
}

AttributeSpec fileAttr(std::string name, FileKind kind, std::string doc) {
  AttributeSpec spec = attr(std::move(name), Value::makeAsset(""), std::move(doc));
  spec.files = kind;
  return spec;
}

AttributeSpec positive(AttributeSpec spec) {
  spec.minimum = 0.0;
  return spec;
}

std::vector<AttributeSpec> concat(std::vector<AttributeSpec> a, const std::vector<AttributeSpec>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

const std::vector<AttributeSpec>& imageable() {
  static const std::vector<AttributeSpec> specs = {
      tokenAttr("visibility", "inherited", {"inherited", "invisible"},
                "'invisible' hides the prim and its descendants from every render pass."),
  };
  return specs;
}

const std::vector<AttributeSpec>& gprim() {
  static const std::vector<AttributeSpec> specs = concat(
      imageable(),
      {attr("primvars:displayColor", Value::makeColor3f(Vec3f(0.5f, 0.5f, 0.5f)),
            "Base colour used when no material is bound."),
       positive(attr("primvars:displayOpacity", Value::makeFloat(1.0f),
                     "Opacity used when no material is bound: drawn where it is at least 0.5 (a cut-out).")),
       attr("doubleSided", Value::makeBool(false), "Render back faces too.")});
  return specs;
}

std::vector<AttributeSpec> axisShape(double radius, double height, std::string_view what) {
  return concat(gprim(),
                {positive(attr("radius", Value::makeDouble(radius), "Radius of the " + std::string(what) + ".")),
                 positive(attr("height", Value::makeDouble(height),
                               "Length along the axis" + std::string(what == "capsule" ? ", without the caps." : "."))),
                 tokenAttr("axis", "Z", {"X", "Y", "Z"}, "Axis the shape is aligned with.")});
}

const std::vector<AttributeSpec>& light() {
  static const std::vector<AttributeSpec> specs = concat(
      imageable(),
      {positive(attr("inputs:intensity", Value::makeFloat(1.0f),
                     "Scales the brightness (USD units; the emitted power is intensity * 2^exposure * color).")),
       attr("inputs:exposure", Value::makeFloat(0.0f), "Brightness as a power of 2."),
       attr("inputs:color", Value::makeColor3f(Vec3f(1, 1, 1)), "Colour of the emitted light (linear RGB)."),
       attr("inputs:normalize", Value::makeBool(false), "Divide the power by the light's area."),
       attr("inputs:diffuse", Value::makeFloat(1.0f), "Multiplier for the diffuse response."),
       attr("inputs:specular", Value::makeFloat(1.0f), "Multiplier for the specular response.")});
  return specs;
}

std::vector<AttributeSpec> lightWith(std::vector<AttributeSpec> extra) { return concat(light(), extra); }

// The camera's calibrated lens: the attributes of NVIDIA's omni_lens_distortion
// API schemas (docs/scene-format.md, "Lens models"), under the same names.
// Defaults are NVIDIA's where its schema reference shows them (f-theta, the
// K-B nominal size); the others are marked as not checked in the docs.
std::vector<AttributeSpec> lensDistortion() {
  const std::string p = "omni:lensdistortion:";
  std::vector<AttributeSpec> s = {tokenAttr(
      p + "model", "", {"", "opencvPinhole", "opencvFisheye", "ftheta", "kannalaBrandtK3"},
      "Calibrated lens model; its parameters then replace focalLength and the apertures for projection. Empty: "
      "the ideal pinhole of focalLength and the apertures.")};
  auto number = [&](const std::string& name, float fallback, const std::string& doc) {
    s.push_back(attr(p + name, Value::makeFloat(fallback), doc));
  };
  for (const std::string model : {"opencvPinhole", "opencvFisheye"}) {
    const std::string m = model + ":";
    number(m + "fx", 900.0f, "Focal length along x (pixels of imageSize).");
    number(m + "fy", 800.0f, "Focal length along y (pixels of imageSize).");
    number(m + "cx", 1024.0f, "Principal point x (pixels of imageSize, pixel centres at integers).");
    number(m + "cy", 512.0f, "Principal point y (pixels of imageSize, y down).");
    s.push_back(attr(p + m + "imageSize", Value::makeInt2(2048, 1024),
                     "Width and height of the calibrated image; another render resolution scales the intrinsics."));
    const int radial = model == "opencvPinhole" ? 6 : 4;
    for (int i = 1; i <= radial; ++i)
      number(m + "k" + std::to_string(i), 0.0f,
             radial == 6 ? "Radial coefficient (k1-k3 numerator, k4-k6 denominator, as OpenCV)."
                         : "Coefficient of theta^" + std::to_string(2 * i + 1) + " (OpenCV fisheye).");
  }
  for (const char* t : {"p1", "p2"}) number(std::string("opencvPinhole:") + t, 0.0f, "Tangential coefficient (OpenCV).");
  for (int i = 1; i <= 4; ++i)
    number("opencvPinhole:s" + std::to_string(i), 0.0f, "Thin-prism coefficient (OpenCV).");
  for (const std::string model : {"ftheta", "kannalaBrandtK3"}) {
    const std::string m = model + ":";
    number(m + "nominalWidth", 1936.0f, "Width of the calibrated sensor (pixels).");
    number(m + "nominalHeight", 1216.0f, "Height of the calibrated sensor (pixels).");
    s.push_back(attr(p + m + "opticalCenter", Value::makeFloat2(970.9424f, 600.3748f),
                     "Optical centre (pixels of the nominal size, y down)."));
    number(m + "maxFov", 200.0f, "Full field of view (degrees); directions beyond half of it are not imaged.");
  }
  const float fthetaK[] = {0.0f, 0.00245f, 0.0f, 0.0f, 0.0f};
  for (int i = 0; i <= 4; ++i)
    number("ftheta:k" + std::to_string(i), fthetaK[i],
           "Coefficient of r^" + std::to_string(i) + " in angle(r) (radians, r the distance to the optical centre in pixels).");
  for (int i = 0; i <= 3; ++i)
    number("kannalaBrandtK3:k" + std::to_string(i), 0.0f,
           "Coefficient of theta^" + std::to_string(2 * i + 1) + " in radius(theta) (pixels).");
  return s;
}

std::vector<PrimTypeInfo> buildTable() {
  std::vector<PrimTypeInfo> t;
  t.push_back({PrimType::Xform, "Xform", true, false, false,
               "A transformable group (the default type).", imageable()});
  t.push_back({PrimType::Scope, "Scope", false, false, false,
               "A grouping prim with no transform.", {}});
  t.push_back({PrimType::Mesh, "Mesh", true, true, false,
               "Geometry loaded from an asset file (OBJ, glTF/GLB, FBX, PLY, STL, DAE, USD), or written inline "
               "as USD writes it (points, faceVertexCounts, faceVertexIndices).",
               concat(gprim(), {fileAttr("asset", FileKind::Mesh, "Path of the mesh file."),
                                attr("submesh", Value::makeString(""),
                                     "Name of one mesh inside the file; empty means all of them."),
                                attr("points", Value::makeFloatArray(ValueType::Point3fArray, {}),
                                     "Inline geometry: the vertex positions (used when `asset` is empty)."),
                                attr("faceVertexCounts", Value::makeIntArray({}), "Inline geometry: corners of each face."),
                                attr("faceVertexIndices", Value::makeIntArray({}),
                                     "Inline geometry: the point of each corner, face after face."),
                                attr("normals", Value::makeFloatArray(ValueType::Normal3fArray, {}),
                                     "Inline geometry: normals, one per face-vertex or one per point (computed when absent)."),
                                attr("primvars:st", Value::makeFloatArray(ValueType::TexCoord2fArray, {}),
                                     "Inline geometry: texture coordinates, one per face-vertex or one per point."),
                                attr("primvars:displayColor:faceVarying", Value::makeFloatArray(ValueType::Color3fArray, {}),
                                     "Inline geometry: a colour per face-vertex, replacing primvars:displayColor (USD's "
                                     "non-constant displayColor; used when no material is bound)."),
                                attr("primvars:displayOpacity:faceVarying", Value::makeFloatArray(ValueType::FloatArray, {}),
                                     "Inline geometry: an opacity per face-vertex, replacing primvars:displayOpacity "
                                     "(interpolated, drawn where at least 0.5; used when no material is bound)."),
                                tokenAttr("subdivisionScheme", "catmullClark", {"catmullClark", "loop", "bilinear", "none"},
                                          "Inline geometry: a subdivision surface, refined to render.subdivision_level "
                                          "with smooth normals; 'none' draws the polygons as authored with faceted "
                                          "computed normals."),
                                tokenAttr("interpolateBoundary", "edgeAndCorner", {"none", "edgeOnly", "edgeAndCorner"},
                                          "Subdivision: how boundary edges and corners are kept."),
                                tokenAttr("faceVaryingLinearInterpolation", "cornersPlus1",
                                          {"none", "cornersOnly", "cornersPlus1", "cornersPlus2", "boundaries", "all"},
                                          "Subdivision: where texture coordinates are refined linearly."),
                                tokenAttr("triangleSubdivisionRule", "catmullClark", {"catmullClark", "smooth"},
                                          "Subdivision: the weights catmullClark gives triangles."),
                                attr("creaseIndices", Value::makeIntArray({}),
                                     "Subdivision: the points of the creases, crease after crease."),
                                attr("creaseLengths", Value::makeIntArray({}), "Subdivision: points of each crease."),
                                attr("creaseSharpnesses", Value::makeFloatArray(ValueType::FloatArray, {}),
                                     "Subdivision: sharpness of each crease or each crease edge; 10 or more is infinitely sharp."),
                                attr("cornerIndices", Value::makeIntArray({}), "Subdivision: points made sharp corners."),
                                attr("cornerSharpnesses", Value::makeFloatArray(ValueType::FloatArray, {}),
                                     "Subdivision: sharpness of each corner; 10 or more is infinitely sharp."),
                                attr("holeIndices", Value::makeIntArray({}), "Inline geometry: faces left out (holes)."),
                                tokenAttr("orientation", "rightHanded", {"rightHanded", "leftHanded"},
                                          "Winding of the front faces: counter-clockwise (rightHanded) or clockwise.")})});
  t.push_back({PrimType::Cube, "Cube", true, true, false, "An axis-aligned cube centred at the origin.",
               concat(gprim(), {positive(attr("size", Value::makeDouble(2.0), "Edge length."))})});
  t.push_back({PrimType::Sphere, "Sphere", true, true, false, "A sphere centred at the origin.",
               concat(gprim(), {positive(attr("radius", Value::makeDouble(1.0), "Radius."))})});
  t.push_back({PrimType::Cylinder, "Cylinder", true, true, false, "A capped cylinder centred at the origin.",
               axisShape(1.0, 2.0, "cylinder")});
  t.push_back({PrimType::Cone, "Cone", true, true, false, "A cone centred at the origin, apex toward +axis.",
               axisShape(1.0, 2.0, "cone")});
  t.push_back({PrimType::Capsule, "Capsule", true, true, false, "A cylinder with hemispherical caps.",
               axisShape(0.5, 1.0, "capsule")});
  t.push_back({PrimType::Plane, "Plane", true, true, false, "A flat rectangle through the origin.",
               concat(gprim(), {positive(attr("width", Value::makeDouble(2.0), "Extent along the first in-plane axis.")),
                                positive(attr("length", Value::makeDouble(2.0), "Extent along the second in-plane axis.")),
                                tokenAttr("axis", "Z", {"X", "Y", "Z"}, "Normal of the plane."),
                                attr("doubleSided", Value::makeBool(true), "Render back faces too.")})});
  t.push_back({PrimType::Camera, "Camera", true, false, false,
               "A camera looking down its local -Z axis with +Y up.",
               concat(concat(imageable(),
                      {positive(attr("focalLength", Value::makeFloat(50.0f), "Focal length (tenths of a scene unit, usually mm).")),
                       positive(attr("horizontalAperture", Value::makeFloat(20.955f), "Horizontal film aperture (same unit as focalLength).")),
                       positive(attr("verticalAperture", Value::makeFloat(15.2908f), "Vertical film aperture.")),
                       attr("horizontalApertureOffset", Value::makeFloat(0.0f), "Horizontal shift of the aperture."),
                       attr("verticalApertureOffset", Value::makeFloat(0.0f), "Vertical shift of the aperture."),
                       positive(attr("clippingRange", Value::makeFloat2(1.0f, 1000000.0f), "Near and far clipping distances (scene units).")),
                       tokenAttr("projection", "perspective", {"perspective", "orthographic"}, "Projection model."),
                       positive(attr("focusDistance", Value::makeFloat(0.0f), "Distance to the focus plane (metadata only).")),
                       positive(attr("fStop", Value::makeFloat(0.0f), "Lens aperture; 0 disables depth of field (metadata only)."))}),
                      lensDistortion())});
  t.push_back({PrimType::Lidar, "Lidar", true, false, false,
               "A LiDAR sensor: a spinning (or solid-state) pattern of rays cast from the prim's origin, x forward, "
               "y left, z up (its spin axis); one sweep per captured frame (capture.lidars).",
               concat(imageable(),
                      {tokenAttr("preset", "none", {"none", "VLP-16", "HDL-32E", "OS1-64", "OS1-128"},
                                 "A published sensor's channels and elevations (docs/scene-format.md cites each); "
                                 "'none' takes channels and elevations or verticalFov."),
                       tokenAttr("pattern", "spinning", {"spinning", "solidState"},
                                 "spinning: horizontalResolution azimuths over 360 degrees; solidState: over "
                                 "horizontalFov, centred on +x."),
                       attr("channels", Value::makeInt(16), "Number of beams (rings) per azimuth."),
                       attr("elevations", Value::makeFloatArray(ValueType::FloatArray, {}),
                            "Each ring's elevation (degrees above the x-y plane), one per channel; empty: "
                            "verticalFov evenly spaced."),
                       attr("verticalFov", Value::makeFloat2(-15.0f, 15.0f),
                            "Lowest and highest elevation (degrees) of evenly spaced rings, used when elevations is empty."),
                       attr("horizontalFov", Value::makeFloat(120.0f),
                            "solidState: the azimuth span (degrees), centred on +x."),
                       attr("horizontalResolution", Value::makeInt(1800),
                            "Azimuths per sweep (points per revolution per channel; per horizontalFov for solidState)."),
                       attr("rotationRate", Value::makeFloat(10.0f),
                            "Sweeps per second (Hz): a sweep lasts 1 / rotationRate (the points' time offsets)."),
                       attr("range", Value::makeFloat2(0.1f, 100.0f),
                            "Nearest and farthest return (metres); rays hitting nothing in it return nothing."),
                       attr("rangeNoise", Value::makeFloat(0.0f), "Standard deviation of the Gaussian range noise (metres)."),
                       attr("dropout", Value::makeFloat(0.0f), "Probability that a return is lost, 0 to 1."),
                       attr("beamDivergence", Value::makeFloat(0.0f),
                            "Full beam divergence angle (milliradians); recorded in the sweep's JSON, not traced "
                            "(every ray is a line).")})});
  t.push_back({PrimType::DistantLight, "DistantLight", true, false, true,
               "Parallel light shining down the prim's local -Z axis.",
               [] {
                 auto specs = lightWith({positive(attr("inputs:angle", Value::makeFloat(0.53f), "Angular diameter of the source (degrees)."))});
                 for (auto& s : specs)
                   if (s.name == "inputs:intensity") s.defaultValue = Value::makeFloat(50000.0f);
                 return specs;
               }()});
  t.push_back({PrimType::SphereLight, "SphereLight", true, false, true, "A spherical emitter.",
               lightWith({positive(attr("inputs:radius", Value::makeFloat(0.5f), "Radius of the sphere.")),
                          attr("treatAsPoint", Value::makeBool(false), "Treat as a point light of zero radius.")})});
  t.push_back({PrimType::RectLight, "RectLight", true, false, true, "A rectangle emitting toward -Z.",
               lightWith({positive(attr("inputs:width", Value::makeFloat(1.0f), "Width along X.")),
                          positive(attr("inputs:height", Value::makeFloat(1.0f), "Height along Y.")),
                          fileAttr("inputs:texture:file", FileKind::Image, "Optional emission texture.")})});
  t.push_back({PrimType::DiskLight, "DiskLight", true, false, true, "A disk emitting toward -Z.",
               lightWith({positive(attr("inputs:radius", Value::makeFloat(0.5f), "Radius of the disk."))})});
  t.push_back({PrimType::CylinderLight, "CylinderLight", true, false, true, "A cylinder along X emitting outward.",
               lightWith({positive(attr("inputs:length", Value::makeFloat(1.0f), "Length along X.")),
                          positive(attr("inputs:radius", Value::makeFloat(0.5f), "Radius."))})});
  t.push_back({PrimType::DomeLight, "DomeLight", true, false, true,
               "Light from every direction: a uniform colour or a lat-long texture.",
               lightWith({fileAttr("inputs:texture:file", FileKind::Image,
                                   "Lat-long environment map: EXR or HDR for real sky brightness (linear), or an "
                                   "8-bit image (sRGB). Its pole follows the stage's up axis."),
                          tokenAttr("inputs:texture:format", "automatic",
                                    {"automatic", "latlong", "mirroredBall", "angular", "cubeMapVerticalCross"},
                                    "Layout of the texture.")})});
  t.push_back({PrimType::Material, "Material", false, false, false,
               "An OmniPBR-like surface material, bound to prims with `material:`.",
               {attr("inputs:diffuse_color_constant", Value::makeColor3f(Vec3f(0.2f, 0.2f, 0.2f)), "Base colour when no texture is set."),
                fileAttr("inputs:diffuse_texture", FileKind::Image, "Base colour texture (sRGB if 8 or 16 bits, linear if float)."),
                positive(attr("inputs:texture_scale", Value::makeFloat2(1.0f, 1.0f), "UV scale of the texture.")),
                attr("inputs:texture_rotate", Value::makeFloat(0.0f), "Rotation of the texture (degrees)."),
                attr("inputs:project_uvw", Value::makeBool(false), "Project the texture in world space (triplanar) instead of using UVs."),
                positive(attr("inputs:reflection_roughness_constant", Value::makeFloat(0.5f), "Surface roughness, 0 (mirror) to 1 (matte).")),
                positive(attr("inputs:metallic_constant", Value::makeFloat(0.0f), "Metalness, 0 to 1.")),
                positive(attr("inputs:specular_level", Value::makeFloat(0.5f),
                              "Strength of a dielectric's reflection: 0.5 reflects 4 % head-on, 0 none (pure diffuse).")),
                fileAttr("inputs:reflectionroughness_texture", FileKind::Image, "Roughness map (linear, red channel)."),
                positive(attr("inputs:reflection_roughness_texture_influence", Value::makeFloat(0.0f),
                              "How much the roughness map replaces the constant, 0 to 1 (OmniPBR's default 0: set 1 to use the map).")),
                fileAttr("inputs:metallic_texture", FileKind::Image, "Metallic map (linear, red channel)."),
                positive(attr("inputs:metallic_texture_influence", Value::makeFloat(0.0f),
                              "How much the metallic map replaces the constant, 0 to 1 (OmniPBR's default 0: set 1 to use the map).")),
                attr("inputs:enable_ORM_texture", Value::makeBool(false), "Read roughness and metallic from ORM_texture instead."),
                fileAttr("inputs:ORM_texture", FileKind::Image,
                         "Occlusion-roughness-metallic map (linear): roughness in green, metallic in blue."),
                fileAttr("inputs:normalmap_texture", FileKind::Image,
                         "Tangent-space normal map (linear, +Y up as in OpenGL and glTF); UV-mapped materials only."),
                positive(attr("inputs:bump_factor", Value::makeFloat(1.0f), "Strength of the normal map.")),
                attr("inputs:enable_opacity", Value::makeBool(false), "Cut the surface out where its opacity is below the threshold."),
                attr("inputs:enable_opacity_texture", Value::makeBool(false), "Take the opacity from opacity_texture."),
                positive(attr("inputs:opacity_constant", Value::makeFloat(1.0f), "Opacity, multiplied by the map's value.")),
                fileAttr("inputs:opacity_texture", FileKind::Image, "Opacity map (linear, red channel)."),
                positive(attr("inputs:opacity_threshold", Value::makeFloat(0.0f),
                              "Drawn where opacity >= this; 0 (OmniPBR's fractional mode) cuts at 0.5."))}});
  return t;
}

const std::vector<PrimTypeInfo>& table() {
  static const std::vector<PrimTypeInfo> t = buildTable();
  return t;
}

}  // namespace

std::span<const PrimTypeInfo> allPrimTypes() { return table(); }

const PrimTypeInfo& primTypeInfo(PrimType type) {
  for (const PrimTypeInfo& info : table())
    if (info.type == type) return info;
  return table().front();
}

std::optional<PrimType> primTypeFromName(std::string_view name) {
  for (const PrimTypeInfo& info : table())
    if (info.name == name) return info.type;
  return std::nullopt;
}

const AttributeSpec* findSchemaAttribute(PrimType type, std::string_view name) {
  for (const AttributeSpec& spec : primTypeInfo(type).attributes)
    if (spec.name == name) return &spec;
  return nullptr;
}

}  // namespace sdg
