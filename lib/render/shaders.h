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

// A lat-long environment: the dome's local +Y is up (USD's convention).
vec2 latLong(vec3 d) {
  return vec2(0.5 + atan(d.x, -d.z) / (2.0 * PI), acos(clamp(d.y, -1.0, 1.0)) / PI);
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
uniform float uExposureScale;
uniform vec3 uAmbient;
uniform vec3 uLightRadiance[MAX_LIGHTS];
uniform vec3 uLightPosition[MAX_LIGHTS];
uniform vec3 uLightDirection[MAX_LIGHTS];
uniform vec4 uLightParams[MAX_LIGHTS];
in vec4 vShadowCoord0;
in vec4 vShadowCoord1;
in vec4 vShadowCoord2;
in vec4 vShadowCoord3;
uniform sampler2DShadow uShadowAtlas;  // 2 x 2 tiles, one per shadow slot
uniform float uShadowTexel;
uniform sampler2D uDome;
uniform mat3 uDomeFromWorld;
uniform float uDomeLod;
uniform vec3 uDomeScale;


vec2 transformUv(vec2 uv) {
  float c = vTextureTransform.z, s = vTextureTransform.w;
  uv *= vTextureTransform.xy;
  return vec2(c * uv.x - s * uv.y, s * uv.x + c * uv.y);
}

// TEXTURE_MODE (0 none, 1 the mesh's uvs, 2 world-space triplanar) and
// HAS_DOME are defined per program, not tested per pixel: llvmpipe runs both
// sides of a branch on a uniform with lanes masked, so a runtime test would
// make every pixel pay for every texture lookup.
vec3 albedo(vec3 n, vec3 baseColor) {
#if TEXTURE_MODE == 0
  return baseColor;
#elif TEXTURE_MODE == 1
  return texture(uTexture, transformUv(vUv)).rgb;
#else
  // Blended by the normal.
  vec3 w = abs(n);
  w /= (w.x + w.y + w.z);
  vec3 x = texture(uTexture, transformUv(vWorldPosition.yz)).rgb;
  vec3 y = texture(uTexture, transformUv(vWorldPosition.xz)).rgb;
  vec3 z = texture(uTexture, transformUv(vWorldPosition.xy)).rgb;
  return x * w.x + y * w.y + z * w.z;
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

// Lambert diffuse + GGX specular (Smith-Schlick visibility, Schlick Fresnel).
vec3 brdf(vec3 n, vec3 v, vec3 l, vec3 base, float roughness, float metallic) {
  vec3 h = normalize(l + v);
  float nl = max(dot(n, l), 0.0), nv = max(dot(n, v), 1e-4), nh = max(dot(n, h), 0.0), vh = max(dot(v, h), 0.0);
  float a = max(roughness * roughness, 1e-3);
  float a2 = a * a;
  float denominator = nh * nh * (a2 - 1.0) + 1.0;
  float d = a2 / (PI * denominator * denominator);
  float k = a / 2.0;
  float g = (nl / (nl * (1.0 - k) + k)) * (nv / (nv * (1.0 - k) + k));
  vec3 f0 = mix(vec3(0.04), base, metallic);
  float m = 1.0 - vh, m2 = m * m;
  vec3 f = f0 + (1.0 - f0) * (m2 * m2 * m);
  vec3 specular = d * g * f / max(4.0 * nl * nv, 1e-4);
  return base * (1.0 - metallic) / PI + specular;
}

// Light `i` of type `type` (0 distant, 1 sphere, 2 rect, 3 disk, 4 cylinder),
// its shadow map in atlas slot `slot` (-1: none).
vec3 lightContribution(int i, int type, int slot, vec3 n, vec3 v, vec3 base, float roughness, float metallic) {
  vec3 l;
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
  float nl = max(dot(n, l), 0.0);
  return brdf(n, v, l, base, roughness, metallic) * irradiance * nl;
}

void main() {
  vec3 n = normalize(vWorldNormal);
  vec3 v = normalize(uCameraPosition - vWorldPosition);
  if (dot(n, v) < 0.0) n = -n;  // back faces of double-sided geometry
  bool part = uUsePartMaterial != 0;
  float roughness = part ? uPartSurface.x : vSurface.x;
  float metallic = part ? uPartSurface.y : vSurface.y;
  vec3 base = albedo(n, part ? uPartBaseColor : vBaseColor);
  // Ambient from the dome: a blurred (high mip) lat-long lookup along the
  // normal approximates its irradiance; a dome without a texture is uniform.
#if HAS_DOME
  vec3 ambient = uDomeScale * textureLod(uDome, latLong(uDomeFromWorld * n), uDomeLod).rgb;
#else
  vec3 ambient = uAmbient;
#endif
  vec3 radiance = base * (1.0 - metallic) * ambient;
  // One call per light, written out by the renderer with the light's type
  // and shadow slot as literals: the compiler folds every branch away.
  ADD_LIGHTS
  oColor = displayColor(radiance, uExposureScale);
  float distance = length(vWorldPosition - uCameraPosition);
  oNormalDistance = vec4(n, distance * uMetersPerUnit);
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
uniform sampler2D uDome;
uniform mat3 uDomeFromWorld;
uniform vec3 uDomeScale;
uniform float uExposureScale;
void main() {
  vec4 far = uWorldFromClip * vec4(vNdc, 1.0, 1.0);
  vec3 direction = normalize(far.xyz / far.w - uCameraPosition);
  vec3 radiance = uDomeScale * texture(uDome, latLong(uDomeFromWorld * direction)).rgb;
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
