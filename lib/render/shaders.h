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

inline constexpr const char* kSceneVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;
uniform mat4 uWorldFromLocal;
uniform mat4 uNormalMatrix;
uniform mat4 uViewProjection;
out vec3 vWorldPosition;
out vec3 vWorldNormal;
out vec2 vUv;
invariant gl_Position;  // bit-identical to the depth pre-pass
void main() {
  vec4 world = uWorldFromLocal * vec4(aPosition, 1.0);
  vWorldPosition = world.xyz;
  vWorldNormal = mat3(uNormalMatrix) * aNormal;
  vUv = aUv;
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
uniform uint uInstanceId;
uniform vec3 uBaseColor;
uniform float uRoughness;
uniform float uMetallic;
uniform int uHasTexture;
uniform sampler2D uTexture;
uniform vec2 uTextureScale;
uniform float uTextureRotate;
uniform int uProjectUvw;
uniform float uExposureScale;
uniform vec3 uAmbient;
uniform int uLightCount;
uniform int uLightType[MAX_LIGHTS];
uniform vec3 uLightRadiance[MAX_LIGHTS];
uniform vec3 uLightPosition[MAX_LIGHTS];
uniform vec3 uLightDirection[MAX_LIGHTS];
uniform vec4 uLightParams[MAX_LIGHTS];
uniform int uLightShadow[MAX_LIGHTS];  // shadow slot of each light, -1 for none
uniform mat4 uShadowMatrix[4];
uniform sampler2DShadow uShadowAtlas;  // 2 x 2 tiles, one per shadow slot
uniform float uShadowTexel;
uniform int uHasDome;
uniform sampler2D uDome;
uniform mat3 uDomeFromWorld;
uniform float uDomeLod;
uniform vec3 uDomeScale;


vec2 transformUv(vec2 uv) {
  float c = cos(radians(uTextureRotate)), s = sin(radians(uTextureRotate));
  uv *= uTextureScale;
  return vec2(c * uv.x - s * uv.y, s * uv.x + c * uv.y);
}

vec3 albedo(vec3 n) {
  if (uHasTexture == 0) return uBaseColor;
  if (uProjectUvw == 0) return texture(uTexture, transformUv(vUv)).rgb;
  // World-space triplanar projection, blended by the normal.
  vec3 w = abs(n);
  w /= (w.x + w.y + w.z);
  vec3 x = texture(uTexture, transformUv(vWorldPosition.yz)).rgb;
  vec3 y = texture(uTexture, transformUv(vWorldPosition.xz)).rgb;
  vec3 z = texture(uTexture, transformUv(vWorldPosition.xy)).rgb;
  return x * w.x + y * w.y + z * w.z;
}

// Fraction of the light that reaches this point: 2 x 2 taps of bilinear
// PCF (each tap already compares and blends 4 texels), so 4 x 4 texels.
float shadow(int slot) {
  vec4 q = uShadowMatrix[slot] * vec4(vWorldPosition, 1.0);
  if (q.w <= 0.0) return 1.0;
  vec3 p = q.xyz / q.w * 0.5 + 0.5;
  if (p.x <= 0.0 || p.x >= 1.0 || p.y <= 0.0 || p.y >= 1.0 || p.z >= 1.0) return 1.0;
  // Into the slot's tile of the atlas, keeping the PCF taps inside it.
  vec2 tile = vec2(slot % 2, slot / 2);
  vec2 inTile = clamp(p.xy, 2.0 * uShadowTexel, 1.0 - 2.0 * uShadowTexel);
  float lit = 0.0;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      lit += texture(uShadowAtlas, vec3((tile + inTile + (vec2(i, j) - 0.5) * 2.0 * uShadowTexel) * 0.5, p.z));
  return lit / 4.0;
}

// Lambert diffuse + GGX specular (Smith-Schlick visibility, Schlick Fresnel).
vec3 brdf(vec3 n, vec3 v, vec3 l, vec3 base) {
  vec3 h = normalize(l + v);
  float nl = max(dot(n, l), 0.0), nv = max(dot(n, v), 1e-4), nh = max(dot(n, h), 0.0), vh = max(dot(v, h), 0.0);
  float a = max(uRoughness * uRoughness, 1e-3);
  float a2 = a * a;
  float d = a2 / (PI * pow(nh * nh * (a2 - 1.0) + 1.0, 2.0));
  float k = a / 2.0;
  float g = (nl / (nl * (1.0 - k) + k)) * (nv / (nv * (1.0 - k) + k));
  vec3 f0 = mix(vec3(0.04), base, uMetallic);
  vec3 f = f0 + (1.0 - f0) * pow(1.0 - vh, 5.0);
  vec3 specular = d * g * f / max(4.0 * nl * nv, 1e-4);
  return base * (1.0 - uMetallic) / PI + specular;
}

void main() {
  vec3 n = normalize(vWorldNormal);
  vec3 v = normalize(uCameraPosition - vWorldPosition);
  if (dot(n, v) < 0.0) n = -n;  // back faces of double-sided geometry
  vec3 base = albedo(n);
  // Ambient from the dome: a blurred (high mip) lat-long lookup along the
  // normal approximates its irradiance; a dome without a texture is uniform.
  vec3 ambient = uAmbient;
  if (uHasDome != 0) ambient = uDomeScale * textureLod(uDome, latLong(uDomeFromWorld * n), uDomeLod).rgb;
  vec3 radiance = base * (1.0 - uMetallic) * ambient;
  for (int i = 0; i < uLightCount; ++i) {
    vec3 l;
    vec3 irradiance;
    int type = uLightType[i];
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
    if (uLightShadow[i] >= 0) irradiance *= shadow(uLightShadow[i]);
    float nl = max(dot(n, l), 0.0);
    radiance += brdf(n, v, l, base) * irradiance * nl;
  }
  oColor = displayColor(radiance, uExposureScale);
  float distance = length(vWorldPosition - uCameraPosition);
  oNormalDistance = vec4(n, distance * uMetersPerUnit);
  oPlaneDistance = dot(vWorldPosition - uCameraPosition, uCameraForward) * uMetersPerUnit;
  oInstanceId = uInstanceId;
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
uniform mat4 uWorldFromLocal;
uniform mat4 uViewProjection;
invariant gl_Position;
void main() {
  vec4 world = uWorldFromLocal * vec4(aPosition, 1.0);
  gl_Position = uViewProjection * world;
}
)";

inline constexpr const char* kShadowVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
uniform mat4 uWorldFromLocal;
uniform mat4 uLightViewProjection;
void main() { gl_Position = uLightViewProjection * uWorldFromLocal * vec4(aPosition, 1.0); }
)";

inline constexpr const char* kShadowFragment = R"(#version 330 core
void main() {}
)";

// Entities as if alone, for their unoccluded extents (loose boxes,
// occlusion): each ORs its own bit into the mask.
inline constexpr const char* kMaskFragment = R"(#version 330 core
layout(location = 0) out uint oMask;
uniform uint uBit;
void main() { oMask = uBit; }
)";

}  // namespace sdg::shaders
