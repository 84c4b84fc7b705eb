#pragma once
// GLSL 3.30 core sources. One program draws every pass at once into four
// attachments: tone-mapped colour, world normal + distance to the camera,
// distance to the image plane, and the instance id (exact, unsigned).
namespace sdg::shaders {

inline constexpr int kMaxLights = 16;

// Fragment programs are compiled from several strings: this header, the
// common functions, then their own body.
// The four render targets every frame pass writes (colour, normal and
// distance, image-plane distance, instance id), after the version line.
inline constexpr const char* kFragmentHeader = R"(#version 330 core
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oNormalDistance;
layout(location = 2) out float oPlaneDistance;
layout(location = 3) out uint oInstanceId;
)";

inline constexpr const char* kCommonFunctions = R"(
const float PI = 3.14159265358979;

// A lat-long environment in OpenEXR's convention (render/latlong.h): the
// dome's +Y is the pole, the image's centre looks along +Z, a quarter in
// from the left along +X; the top row is uploaded first, at t = 0.
// llvmpipe evaluates atan and acos in software at several times the cost of
// a texture fetch, and a lit pixel maps two directions: polynomial forms
// instead, within 0.002 radians (a sixth of a texel of the 512-wide top
// specular level) and continuous across the seam.
float fastAtan2(float y, float x) {
  float ax = abs(x), ay = abs(y);
  float a = min(ax, ay) / max(max(ax, ay), 1e-20);
  float s = a * a;
  float r = ((-0.0464964749 * s + 0.15931422) * s - 0.327622764) * s * a + a;
  r = ay > ax ? 1.57079637 - r : r;
  r = x < 0.0 ? 3.14159274 - r : r;
  return y < 0.0 ? -r : r;
}

float fastAcos(float x) {  // Abramowitz and Stegun 4.4.45
  float ax = min(abs(x), 1.0);
  float r = ((-0.0187293 * ax + 0.0742610) * ax - 0.2121144) * ax + 1.5707288;
  r *= sqrt(1.0 - ax);
  return x < 0.0 ? PI - r : r;
}

vec2 latLong(vec3 d) {
  return vec2(0.5 - fastAtan2(d.x, d.z) / (2.0 * PI), fastAcos(d.y) / PI);
}

// The documented tone curve, then sRGB encoding.
vec4 displayColor(vec3 radiance, float exposureScale) {
  vec3 mapped = 1.0 - exp(-radiance * exposureScale);
  vec3 srgb = mix(mapped * 12.92, 1.055 * pow(mapped, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, mapped));
  return vec4(srgb, 1.0);
}
)";

// Per-instance attributes (divisor 1) follow the mesh's own three; their
// layout is InstanceRecord's (render/instance_batches.h).
inline constexpr const char* kSceneVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;
layout(location = 3) in mat4 aWorldFromLocal;
layout(location = 7) in mat3 aNormalMatrix;
layout(location = 10) in vec3 aBaseColor;
layout(location = 11) in vec4 aSurface;
layout(location = 12) in vec4 aTextureTransform;
layout(location = 13) in uint aInstanceId;
layout(location = 14) in vec4 aColor;  // the mesh's vertex colours, when it has them
uniform mat4 uViewProjection;
uniform mat4 uShadowMatrix[4];
out vec3 vWorldPosition;
// Each shadow slot's light clip coordinates. They are affine in the world
// position, so interpolating them is the per-pixel product up to rounding,
// and llvmpipe interpolates far faster than it multiplies a uniform matrix
// per pixel (4 ms a frame for three lights at 512 x 512). The fragment
// stage reads only its lights' slots; the linker drops the rest.
out vec4 vShadowCoord0;
out vec4 vShadowCoord1;
out vec4 vShadowCoord2;
out vec4 vShadowCoord3;
out vec3 vWorldNormal;
out vec2 vUv;
out vec4 vColor;
flat out vec3 vBaseColor;
flat out vec4 vSurface;
flat out vec4 vTextureTransform;
flat out uint vInstanceId;
invariant gl_Position;  // bit-identical to the depth pre-pass
void main() {
  vec4 world = aWorldFromLocal * vec4(aPosition, 1.0);
  vWorldPosition = world.xyz;
  vWorldNormal = aNormalMatrix * aNormal;
  vUv = aUv;
  vColor = aColor;
  vBaseColor = aBaseColor;
  vSurface = aSurface;
  vTextureTransform = aTextureTransform;
  vInstanceId = aInstanceId;
  vShadowCoord0 = uShadowMatrix[0] * world;
  vShadowCoord1 = uShadowMatrix[1] * world;
  vShadowCoord2 = uShadowMatrix[2] * world;
  vShadowCoord3 = uShadowMatrix[3] * world;
  gl_Position = uViewProjection * world;
}
)";

inline constexpr const char* kSceneFragment = R"(
#define MAX_LIGHTS 16
in vec3 vWorldPosition;
in vec3 vWorldNormal;
in vec2 vUv;
#if VERTEX_COLORS
in vec4 vColor;  // rgb, opacity: multiply the base colour and the opacity
#endif

uniform vec3 uCameraPosition;
uniform vec3 uCameraForward;
uniform float uMetersPerUnit;
flat in vec3 vBaseColor;
flat in vec4 vSurface;  // roughness, metallic
flat in vec4 vTextureTransform;  // scale, cos and sin of the rotation
flat in uint vInstanceId;
// A mesh file's own material for this part, shared by every instance.
uniform int uUsePartMaterial;
uniform vec3 uPartBaseColor;
uniform vec2 uPartSurface;  // roughness, metallic
uniform sampler2D uTexture;
uniform sampler2D uRoughnessMap;
uniform sampler2D uMetallicMap;
uniform sampler2D uOrmMap;
uniform sampler2D uNormalMap;
uniform sampler2D uOpacityMap;
uniform float uNormalScale;
uniform float uSpecularLevel;  // OmniPBR's specular_level: a dielectric's F0 = 0.08 level, F90 = 2 level
uniform float uOpacityConstant;
uniform float uOpacityCutoff;
uniform float uExposureScale;
uniform vec3 uAmbient;          // the untextured domes' radiance times their inputs:diffuse
uniform vec3 uAmbientSpecular;  // ... times their inputs:specular
uniform vec2 uDomeResponse;     // the textured dome's inputs:diffuse, inputs:specular
uniform vec3 uLightRadiance[MAX_LIGHTS];
uniform vec3 uLightPosition[MAX_LIGHTS];
uniform vec3 uLightDirection[MAX_LIGHTS];
uniform vec4 uLightParams[MAX_LIGHTS];
uniform vec2 uLightResponse[MAX_LIGHTS];  // inputs:diffuse, inputs:specular (lightContributionScaled only)
in vec4 vShadowCoord0;
in vec4 vShadowCoord1;
in vec4 vShadowCoord2;
in vec4 vShadowCoord3;
uniform sampler2DShadow uShadowAtlas;  // 2 x 2 tiles, one per shadow slot
uniform float uShadowTexel;
// Image-based lighting from a textured dome (render/environment_map.h):
// GGX-prefiltered levels by roughness, irradiance / pi, the split-sum table.
uniform sampler2D uDome;
uniform sampler2D uDomeIrradiance;
uniform sampler2D uBrdfLut;
uniform mat3 uDomeFromWorld;
uniform float uDomeLod;  // the last prefiltered level (roughness 1)
uniform vec3 uDomeScale;

vec2 transformUv(vec2 uv) {
  float c = vTextureTransform.z, s = vTextureTransform.w;
  uv *= vTextureTransform.xy;
  return vec2(c * uv.x - s * uv.y, s * uv.x + c * uv.y);
}

// Each program is compiled for one arrangement of maps (render/
// shading_variant.h): PROJECTION (1 the mesh's uvs, 2 world-space
// triplanar), BASE_MAP, ROUGHNESS_MAP and METALLIC_MAP (0 none, 1 the red
// channel of their own map, 2 the green / blue channel of the ORM map),
// NORMAL_MAP, OPACITY (0 opaque, 1 constant, 2 the opacity map's red
// channel, 3 the base colour's alpha), VERTEX_COLORS and HAS_DOME are literals, not tested
// per pixel: llvmpipe runs both sides of a branch on a uniform with lanes
// masked, so a runtime test would make every pixel pay for every lookup.
vec4 sampleMap(sampler2D map, vec3 n) {
#if PROJECTION == 2
  // Blended by the normal.
  vec3 w = abs(n);
  w /= (w.x + w.y + w.z);
  return texture(map, transformUv(vWorldPosition.yz)) * w.x + texture(map, transformUv(vWorldPosition.xz)) * w.y +
         texture(map, transformUv(vWorldPosition.xy)) * w.z;
#else
  return texture(map, transformUv(vUv));
#endif
}

// A tangent-space normal map applied with the frame the uvs make on screen
// (Schueler 2013, "Normal mapping without precomputed tangents"): meshes
// need no tangent attribute.
vec3 mappedNormal(vec3 n) {
#if NORMAL_MAP && PROJECTION == 1
  vec2 uv = transformUv(vUv);
  vec3 dp1 = dFdx(vWorldPosition), dp2 = dFdy(vWorldPosition);
  vec2 duv1 = dFdx(uv), duv2 = dFdy(uv);
  vec3 dp2perp = cross(dp2, n), dp1perp = cross(n, dp1);
  vec3 t = dp2perp * duv1.x + dp1perp * duv2.x;
  vec3 b = dp2perp * duv1.y + dp1perp * duv2.y;
  float scale = inversesqrt(max(max(dot(t, t), dot(b, b)), 1e-20));
  vec3 m = texture(uNormalMap, uv).xyz * 2.0 - 1.0;
  m.xy *= uNormalScale;
  // Rows are uploaded top first, so "up" in the image (the map's +Y) is
  // the direction of decreasing t.
  vec3 mapped = t * scale * m.x - b * scale * m.y + n * m.z;
  return dot(mapped, mapped) > 1e-12 ? normalize(mapped) : n;
#else
  return n;
#endif
}

// Fraction of the light that reaches this point: one bilinear PCF tap (the
// hardware compares and blends 2 x 2 texels). The maps are fitted to what
// the camera sees, about one texel per pixel, so this anti-aliases the edge
// over about a pixel; wider kernels cost llvmpipe 4-5 ms a frame per light.
float shadow(int slot) {
  vec4 q = slot == 0 ? vShadowCoord0 : slot == 1 ? vShadowCoord1 : slot == 2 ? vShadowCoord2 : vShadowCoord3;
  if (q.w <= 0.0) return 1.0;
  vec3 p = q.xyz / q.w * 0.5 + 0.5;
  if (p.x <= 0.0 || p.x >= 1.0 || p.y <= 0.0 || p.y >= 1.0 || p.z >= 1.0) return 1.0;
  // Into the slot's tile of the atlas, keeping the filter inside it.
  vec2 tile = vec2(slot % 2, slot / 2);
  vec2 inTile = clamp(p.xy, uShadowTexel, 1.0 - uShadowTexel);
  return texture(uShadowAtlas, vec3((tile + inTile) * 0.5, p.z));
}

// GGX specular (Smith-Schlick visibility, Schlick Fresnel).
vec3 specularBrdf(vec3 n, vec3 v, vec3 l, vec3 base, float roughness, float metallic) {
  float coat = 2.0 * uSpecularLevel;
  vec3 h = normalize(l + v);
  float nl = max(dot(n, l), 0.0), nv = max(dot(n, v), 1e-4), nh = max(dot(n, h), 0.0), vh = max(dot(v, h), 0.0);
  float a = max(roughness * roughness, 1e-3);
  float a2 = a * a;
  float denominator = nh * nh * (a2 - 1.0) + 1.0;
  float d = a2 / (PI * denominator * denominator);
  float k = a / 2.0;
  float g = (nl / (nl * (1.0 - k) + k)) * (nv / (nv * (1.0 - k) + k));
  vec3 f0 = mix(vec3(0.04 * coat), base, metallic);
  float f90 = mix(coat, 1.0, metallic);
  float m = 1.0 - vh, m2 = m * m;
  vec3 f = f0 + (f90 - f0) * (m2 * m2 * m);
  return d * g * f / max(4.0 * nl * nv, 1e-4);
}

// Lambert diffuse + GGX specular.
vec3 brdf(vec3 n, vec3 v, vec3 l, vec3 base, float roughness, float metallic) {
  return base * (1.0 - metallic) / PI + specularBrdf(n, v, l, base, roughness, metallic);
}

// The irradiance at normal incidence that light `i` of type `type` (0
// distant, 1 sphere, 2 rect, 3 disk, 4 cylinder) sends, its shadow map in
// atlas slot `slot` (-1: none) applied, and the direction `l` toward it.
vec3 incidentLight(int i, int type, int slot, out vec3 l) {
  vec3 irradiance;
  if (type == 0) {  // distant: radiance is irradiance at normal incidence
    l = -uLightDirection[i];
    irradiance = uLightRadiance[i];
  } else {
    vec3 toLight = uLightPosition[i] - vWorldPosition;
    float d2 = max(dot(toLight, toLight), 1e-8);
    l = toLight * inversesqrt(d2);
    vec4 p = uLightParams[i];
    float area;
    float facing = 1.0;
    if (type == 1) area = PI * p.x * p.x;                                           // sphere (projected disk)
    else if (type == 2) { area = p.y * p.z; facing = max(dot(uLightDirection[i], -l), 0.0); }  // rect
    else if (type == 3) { area = PI * p.x * p.x; facing = max(dot(uLightDirection[i], -l), 0.0); }  // disk
    else area = 2.0 * p.x * p.w;                                                     // cylinder (projected)
    irradiance = uLightRadiance[i] * area * facing / d2;
  }
  if (slot >= 0) irradiance *= shadow(slot);
  return irradiance;
}

vec3 lightContribution(int i, int type, int slot, vec3 n, vec3 v, vec3 base, float roughness, float metallic) {
  vec3 l;
  vec3 irradiance = incidentLight(i, type, slot, l);
  float nl = max(dot(n, l), 0.0);
  return brdf(n, v, l, base, roughness, metallic) * irradiance * nl;
}

// The same for a light whose inputs:diffuse and inputs:specular are not
// both 1: each lobe scaled by its multiplier.
vec3 lightContributionScaled(int i, int type, int slot, vec3 n, vec3 v, vec3 base, float roughness, float metallic) {
  vec3 l;
  vec3 irradiance = incidentLight(i, type, slot, l);
  float nl = max(dot(n, l), 0.0);
  vec2 k = uLightResponse[i];
  vec3 f = k.x * base * (1.0 - metallic) / PI + k.y * specularBrdf(n, v, l, base, roughness, metallic);
  return f * irradiance * nl;
}

void main() {
  vec3 n = normalize(vWorldNormal);
  vec3 v = normalize(uCameraPosition - vWorldPosition);
  if (dot(n, v) < 0.0) n = -n;  // back faces of double-sided geometry
  bool part = uUsePartMaterial != 0;
#if BASE_MAP || OPACITY == 3
  vec4 baseTexel = sampleMap(uTexture, n);
#endif
  // Cut-outs: the depth pre-pass leaves them out, so a discarded pixel
  // shows what lies behind it.
#if OPACITY
  float opacity = uOpacityConstant;
#if OPACITY == 2
  opacity *= sampleMap(uOpacityMap, n).r;
#elif OPACITY == 3
  opacity *= baseTexel.a;
#endif
#if VERTEX_COLORS
  opacity *= vColor.a;
#endif
  if (opacity < uOpacityCutoff) discard;
#endif
  // A prim's material: value = mix(constant, map, influence) (OmniPBR); a
  // mesh file's: value = factor * map (glTF), its influence 1.
  vec4 surface = part ? vec4(uPartSurface, 1.0, 1.0) : vSurface;
  float roughness = surface.x;
  float metallic = surface.y;
#if ROUGHNESS_MAP == 1
  roughness = mix(roughness, (part ? surface.x : 1.0) * sampleMap(uRoughnessMap, n).r, surface.z);
#elif ROUGHNESS_MAP == 2
  roughness = mix(roughness, (part ? surface.x : 1.0) * sampleMap(uOrmMap, n).g, surface.z);
#endif
#if METALLIC_MAP == 1
  metallic = mix(metallic, (part ? surface.y : 1.0) * sampleMap(uMetallicMap, n).r, surface.w);
#elif METALLIC_MAP == 2
  metallic = mix(metallic, (part ? surface.y : 1.0) * sampleMap(uOrmMap, n).b, surface.w);
#endif
  roughness = clamp(roughness, 0.0, 1.0);
  metallic = clamp(metallic, 0.0, 1.0);
#if BASE_MAP
  vec3 base = baseTexel.rgb;
#else
  vec3 base = part ? uPartBaseColor : vBaseColor;
#endif
#if VERTEX_COLORS
  base *= vColor.rgb;
#endif
  vec3 geometric = n;
  n = mappedNormal(n);
  // Image-based lighting, split sum (Karis 2013): diffuse from the
  // irradiance map, specular from the level pre-filtered for this roughness
  // times the table's scale and bias of F0. A dome without a texture is the
  // same with uniform radiance.
  float nv = max(dot(n, v), 1e-4);
#if HAS_DOME
  vec3 diffuseLight = uDomeResponse.x * uDomeScale * textureLod(uDomeIrradiance, latLong(uDomeFromWorld * n), 0.0).rgb;
  vec3 specularLight = uDomeResponse.y * uDomeScale *
                       textureLod(uDome, latLong(uDomeFromWorld * reflect(-v, n)), roughness * uDomeLod).rgb;
#else
  vec3 diffuseLight = uAmbient;
  vec3 specularLight = uAmbientSpecular;
#endif
  vec2 ab = textureLod(uBrdfLut, vec2(nv, roughness), 0.0).rg;
  float coat = 2.0 * uSpecularLevel;
  vec3 f0 = mix(vec3(0.04 * coat), base, metallic);
  // The diffuse base is not darkened by the coat, as in brdf() above, the
  // path tracer and Blender's Principled BSDF.
  vec3 specularAlbedo = f0 * ab.x + mix(coat, 1.0, metallic) * ab.y;
  vec3 radiance = base * (1.0 - metallic) * diffuseLight + specularLight * specularAlbedo;
  // One call per light, written out by the renderer with the light's type
  // and shadow slot as literals: the compiler folds every branch away.
  ADD_LIGHTS
  oColor = displayColor(radiance, uExposureScale);
  float distance = length(vWorldPosition - uCameraPosition);
  // Labels keep the geometric normal: they describe the shape, not the map.
  oNormalDistance = vec4(geometric, distance * uMetersPerUnit);
  oPlaneDistance = dot(vWorldPosition - uCameraPosition, uCameraForward) * uMetersPerUnit;
  oInstanceId = vInstanceId;
}
)";

// The dome's texture behind everything: a full-screen triangle at the far
// plane; label outputs get the background values.
inline constexpr const char* kSkyVertex = R"(#version 330 core
out vec2 vNdc;
void main() {
  vec2 p = vec2((gl_VertexID == 1) ? 3.0 : -1.0, (gl_VertexID == 2) ? 3.0 : -1.0);
  vNdc = p;
  gl_Position = vec4(p, 1.0, 1.0);
}
)";

inline constexpr const char* kSkyFragment = R"(
in vec2 vNdc;
uniform mat4 uWorldFromClip;
uniform vec3 uCameraPosition;
uniform sampler2D uDomeBackground;  // the map at its own resolution, no mips
uniform mat3 uDomeFromWorld;
uniform vec3 uDomeScale;
uniform float uExposureScale;
void main() {
  vec4 far = uWorldFromClip * vec4(vNdc, 1.0, 1.0);
  vec3 direction = normalize(far.xyz / far.w - uCameraPosition);
  vec3 radiance = uDomeScale * textureLod(uDomeBackground, latLong(uDomeFromWorld * direction), 0.0).rgb;
  oColor = displayColor(radiance, uExposureScale);
  oNormalDistance = vec4(0.0, 0.0, 0.0, 1.0 / 0.0);
  oPlaneDistance = 1.0 / 0.0;
  oInstanceId = 0u;
}
)";

// The depth pre-pass: the same position arithmetic as kSceneVertex, so the
// shading pass can test GL_LEQUAL and shade each pixel once.
inline constexpr const char* kDepthVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 3) in mat4 aWorldFromLocal;
uniform mat4 uViewProjection;
invariant gl_Position;
void main() {
  vec4 world = aWorldFromLocal * vec4(aPosition, 1.0);
  gl_Position = uViewProjection * world;
}
)";

// Shadow maps and coverage masks: positions only, seen from a light or the
// camera; the coverage pass also passes each instance's bit on.
inline constexpr const char* kShadowVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 3) in mat4 aWorldFromLocal;
layout(location = 13) in uint aBit;
uniform mat4 uLightViewProjection;
flat out uint vBit;
void main() {
  vBit = aBit;
  gl_Position = uLightViewProjection * aWorldFromLocal * vec4(aPosition, 1.0);
}
)";

inline constexpr const char* kShadowFragment = R"(#version 330 core
void main() {}
)";

// Entities as if alone, for their unoccluded extents (loose boxes,
// occlusion): each ORs its own bit into the mask.
inline constexpr const char* kMaskFragment = R"(#version 330 core
layout(location = 0) out uint oMask;
flat in uint vBit;
void main() { oMask = vBit; }
)";

}  // namespace sdg::shaders
