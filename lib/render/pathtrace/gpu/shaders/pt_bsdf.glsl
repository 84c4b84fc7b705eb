// Part 2: the surface model, a port of bsdf.cpp (PbrBsdf, ShadingFrame).
const float kMinCos = 1e-6;
const float kMinAlpha = 1e-3;
const float kDielectricF0 = 0.04;

struct Bsdf {
  vec3 diffuseColor;
  vec3 f0;
  float f90;
  float alpha;
};

Bsdf makeBsdf(vec3 baseColor, float metallic, float roughness, float specularLevel) {
  metallic = clamp(metallic, 0.0, 1.0);
  roughness = clamp(roughness, 0.0, 1.0);
  float coat = 2.0 * clamp(specularLevel, 0.0, 1.0);
  Bsdf b;
  b.diffuseColor = (1.0 - metallic) * baseColor;
  b.f0 = vec3(kDielectricF0 * coat * (1.0 - metallic)) + metallic * baseColor;
  b.f90 = coat * (1.0 - metallic) + metallic;
  b.alpha = max(roughness * roughness, kMinAlpha);
  return b;
}

float schlickWeight(float cosTheta) {
  float m = clamp(1.0 - cosTheta, 0.0, 1.0);
  float m2 = m * m;
  return m2 * m2 * m;
}
vec3 schlickFresnel(vec3 f0, float f90, float cosTheta) { return f0 + (vec3(f90) - f0) * schlickWeight(cosTheta); }

float ggxDistribution(vec3 h, float alpha) {
  float a2 = alpha * alpha;
  float d = (h.x * h.x + h.y * h.y) / a2 + h.z * h.z;
  return 1.0 / (kPi * a2 * d * d);
}
float smithLambda(vec3 w, float alpha) {
  float tan2 = (w.x * w.x + w.y * w.y) / (w.z * w.z);
  return 0.5 * (sqrt(1.0 + alpha * alpha * tan2) - 1.0);
}

vec3 sampleVisibleNormal(vec3 wo, float alpha, vec2 u) {
  vec3 v = normalize(vec3(alpha * wo.x, alpha * wo.y, wo.z));
  float horizontal2 = v.x * v.x + v.y * v.y;
  vec3 t1 = horizontal2 > 0.0 ? vec3(-v.y, v.x, 0.0) / sqrt(horizontal2) : vec3(1.0, 0.0, 0.0);
  vec3 t2 = cross(v, t1);
  float r = sqrt(u.x);
  float phi = 2.0 * kPi * u.y;
  float p1 = r * cos(phi);
  float blend = 0.5 * (1.0 + v.z);
  float p2 = (1.0 - blend) * sqrt(max(0.0, 1.0 - p1 * p1)) + blend * r * sin(phi);
  vec3 onHemisphere = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * v;
  return normalize(vec3(alpha * onHemisphere.x, alpha * onHemisphere.y, max(0.0, onHemisphere.z)));
}

// Shirley and Chiu's concentric map of the square onto the unit disk.
vec2 concentricDisk(vec2 u) {
  float a = 2.0 * u.x - 1.0, b = 2.0 * u.y - 1.0;
  if (a == 0.0 && b == 0.0) return vec2(0.0);
  float radius, phi;
  if (abs(a) > abs(b)) {
    radius = a;
    phi = 0.25 * kPi * (b / a);
  } else {
    radius = b;
    phi = 0.5 * kPi - 0.25 * kPi * (a / b);
  }
  return vec2(radius * cos(phi), radius * sin(phi));
}
vec3 sampleCosineHemisphere(vec2 u) {
  vec2 d = concentricDisk(u);
  if (d == vec2(0.0)) return vec3(0.0, 0.0, 1.0);
  return vec3(d, sqrt(max(0.0, 1.0 - d.x * d.x - d.y * d.y)));
}

float specularProbability(Bsdf b, vec3 wo) {
  float cosTheta = max(wo.z, 0.0);
  float specular = luminance(schlickFresnel(b.f0, b.f90, cosTheta));
  float diffuse = luminance(b.diffuseColor);
  return specular + diffuse > 0.0 ? specular / (specular + diffuse) : 1.0;
}

// f cos θi by lobe (PbrBsdf::evalLobes); bsdfEval is their sum.
void bsdfEvalLobes(Bsdf b, vec3 wo, vec3 wi, out vec3 diffuse, out vec3 specular) {
  diffuse = specular = vec3(0.0);
  if (wo.z <= kMinCos || wi.z <= kMinCos) return;
  diffuse = b.diffuseColor * (wi.z / kPi);
  vec3 h = normalize(wo + wi);
  float g2 = 1.0 / (1.0 + smithLambda(wo, b.alpha) + smithLambda(wi, b.alpha));
  specular = schlickFresnel(b.f0, b.f90, dot(wo, h)) * (ggxDistribution(h, b.alpha) * g2 / (4.0 * wo.z));
}
vec3 bsdfEval(Bsdf b, vec3 wo, vec3 wi) {
  vec3 diffuse, specular;
  bsdfEvalLobes(b, wo, wi, diffuse, specular);
  return diffuse + specular;
}

float bsdfPdf(Bsdf b, vec3 wo, vec3 wi) {
  if (wo.z <= kMinCos || wi.z <= kMinCos) return 0.0;
  vec3 h = normalize(wo + wi);
  float g1 = 1.0 / (1.0 + smithLambda(wo, b.alpha));
  float specularPdf = g1 * ggxDistribution(h, b.alpha) / (4.0 * wo.z);
  float diffusePdf = wi.z / kPi;
  float p = specularProbability(b, wo);
  return p * specularPdf + (1.0 - p) * diffusePdf;
}

// False where PbrBsdf::sample returns nothing.
bool bsdfSample(Bsdf b, vec3 wo, vec2 u, float uLobe, out vec3 wi, out vec3 weight, out float pdf) {
  wi = vec3(0.0);
  weight = vec3(0.0);
  pdf = 0.0;
  if (wo.z <= kMinCos) return false;
  bool specular = uLobe < specularProbability(b, wo);
  if (specular) {
    vec3 h = sampleVisibleNormal(wo, b.alpha, u);
    wi = normalize(2.0 * dot(wo, h) * h - wo);
  } else {
    wi = sampleCosineHemisphere(u);
  }
  pdf = bsdfPdf(b, wo, wi);
  if (!(pdf > 0.0) || isinf(pdf) || isnan(pdf)) return false;
  weight = bsdfEval(b, wo, wi) / pdf;
  return true;
}

struct Frame {
  vec3 s, t, n;
};
Frame frameFromNormal(vec3 n) {
  float sgn = n.z >= 0.0 ? 1.0 : -1.0;  // copysign(1, n.z); -0 rounds to +1 here, harmless
  float a = -1.0 / (sgn + n.z);
  float b = n.x * n.y * a;
  Frame f;
  f.s = vec3(1.0 + sgn * n.x * n.x * a, sgn * b, -sgn * n.x);
  f.t = vec3(b, sgn + n.y * n.y * a, -n.y);
  f.n = n;
  return f;
}
vec3 toLocal(Frame f, vec3 v) { return vec3(dot(v, f.s), dot(v, f.t), dot(v, f.n)); }
vec3 toWorld(Frame f, vec3 v) { return f.s * v.x + f.t * v.y + f.n * v.z; }

float powerHeuristic(float a, float b) {
  float a2 = a * a, b2 = b * b;
  if (!(a2 > 0.0)) return 0.0;
  if (a2 > 1e30) return 1.0;
  return a2 / (a2 + b2);
}
