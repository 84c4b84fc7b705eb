// Part 4: the lights, a port of pt_lights.cpp (sample, intersect, blocks,
// pdf, escaped) and environment_sampler.cpp (the dome's map sampling).
const int kDistant = 0, kSphere = 1, kRect = 2, kDisk = 3, kCylinder = 4, kDome = 5;  // LightKind's order

struct Light {
  ivec4 info;           // kind, delta, has map, a point (a sphere light with treatAsPoint)
  vec4 radiancePick;    // radiance (a delta distant light's irradiance), pick probability
  vec4 positionRadius;
  vec4 axisXWidth, axisYHeight, axisZLength;
  vec4 emitArea;        // the emitting direction (-Z), area
  vec4 toLightCone;     // distant: toward the light, 1 - cos of the cone
  vec4 misc;            // sin^2 of the cone's half-angle, the dome's map probability, inputs:diffuse, inputs:specular
  vec4 mapScale, ambient;
  vec4 domeFromWorld[3];  // rows
};
layout(std430, binding = 12) readonly buffer Lights { Light lights[]; };

struct LightSample {
  vec3 direction;
  float distance;
  vec3 radiance;
  float pdf;
  bool delta;
  int light;
};

// --- The dome's map: EnvironmentSampler and PtDomeMap ---
vec2 latLongFromDirection(vec3 d) {
  float longitude = atan(d.x, d.z);
  return vec2(0.5 - longitude / (2.0 * kPi), acos(clamp(d.y, -1.0, 1.0)) / kPi);
}
vec3 directionFromLatLong(float u, float v) {
  float longitude = (0.5 - u) * 2.0 * kPi;
  float polar = v * kPi;
  float s = sin(polar);
  return vec3(s * sin(longitude), cos(polar), s * cos(longitude));
}
ivec2 latLongTexel(vec3 direction) {
  vec2 uv = latLongFromDirection(direction);
  int w = params.dome.x, h = params.dome.y;
  return ivec2(clamp(int(uv.x * float(w)), 0, w - 1), clamp(int(uv.y * float(h)), 0, h - 1));
}
vec3 domeTexel(vec3 domeDirection) {
  ivec2 t = latLongTexel(domeDirection);
  uint at = uint(params.dome.z) + 4u * (uint(t.y) * uint(params.dome.x) + uint(t.x));
  return vec3(uintBitsToFloat(texels[at]), uintBitsToFloat(texels[at + 1u]), uintBitsToFloat(texels[at + 2u]));
}
// The cell with cdf[cell] <= u < cdf[cell + 1] (std::upper_bound), and where u falls inside it.
int pickCell(int cdf, int count, float u, out float offset) {
  int lo = 0, n = count + 1;  // first entry above u, by bisection
  while (n > 0) {
    int half_ = n >> 1;
    if (!(u < params.tables[cdf + lo + half_])) {
      lo += half_ + 1;
      n -= half_ + 1;
    } else {
      n = half_;
    }
  }
  int cell = min(max(lo - 1, 0), count - 1);
  float a = params.tables[cdf + cell], b = params.tables[cdf + cell + 1];
  float width = b - a;
  offset = clamp(width > 0.0 ? (u - a) / width : 0.0, 0.0, kOneBelowOne);
  return cell;
}
float domeMapPdf(vec3 direction) {
  ivec2 t = latLongTexel(direction);
  int w = params.dome.x;
  int rowCdf = params.domeTables.x, columns = params.domeTables.y + t.y * (w + 1);
  float probability = (params.tables[rowCdf + t.y + 1] - params.tables[rowCdf + t.y]) *
                      (params.tables[columns + t.x + 1] - params.tables[columns + t.x]);
  return probability / params.tables[params.domeTables.w + t.y];
}
vec3 domeMapSample(vec2 u) {
  int w = params.dome.x, h = params.dome.y;
  float rowOffset, columnOffset;
  int row = pickCell(params.domeTables.x, h, u.y, rowOffset);
  int column = pickCell(params.domeTables.y + row * (w + 1), w, u.x, columnOffset);
  float top = params.tables[params.domeTables.z + row], bottom = params.tables[params.domeTables.z + row + 1];
  float cosTheta = top + rowOffset * (bottom - top);
  float v = acos(clamp(cosTheta, -1.0, 1.0)) / kPi;
  return directionFromLatLong((float(column) + columnOffset) / float(w), v);
}

vec3 rows3(vec4 rows[3], vec3 v) { return vec3(dot(rows[0].xyz, v), dot(rows[1].xyz, v), dot(rows[2].xyz, v)); }
vec3 rows3T(vec4 rows[3], vec3 v) { return rows[0].xyz * v.x + rows[1].xyz * v.y + rows[2].xyz * v.z; }

vec3 domeRadiance(Light l, vec3 wi) {
  vec3 radiance = l.ambient.xyz;
  if (kDomeMaps && l.info.z != 0) radiance += l.mapScale.xyz * domeTexel(rows3(l.domeFromWorld, wi));
  return radiance;
}

// --- Shapes ---
vec3 sampleCone(vec3 axis, float oneMinusCosMax, vec2 u) {
  float oneMinusCos = u.x * oneMinusCosMax;
  float cosTheta = 1.0 - oneMinusCos;
  float sinTheta = sqrt(max(0.0, oneMinusCos * (2.0 - oneMinusCos)));
  float phi = 2.0 * kPi * u.y;
  return normalize(toWorld(frameFromNormal(axis), vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta)));
}

bool hitShape(Light l, vec3 o, vec3 d, float tMin, float tMax, out float t) {
  t = 0.0;
  int kind = l.info.x;
  vec3 position = l.positionRadius.xyz;
  float radius = l.positionRadius.w;
  if (kSphereLights && kind == kSphere) {
    if (l.info.w != 0) return false;
    vec3 oc = o - position;
    float r2 = radius * radius;
    float c = dot(oc, oc) - r2;
    if (!(c > 0.0)) return false;
    float b = dot(oc, d);
    if (b >= 0.0) return false;
    vec3 perp = oc - b * d;
    float disc = r2 - dot(perp, perp);
    if (disc < 0.0) return false;
    float q = -b + sqrt(disc);
    t = c / q;
    return t > tMin && t < tMax;
  }
  if (kShapeLights && (kind == kRect || kind == kDisk)) {
    vec3 emit = l.emitArea.xyz;
    float facing = dot(d, emit);
    if (!(facing < 0.0)) return false;
    t = dot(position - o, emit) / facing;
    if (!(t > tMin && t < tMax)) return false;
    vec3 q = o + t * d - position;
    float x = dot(q, l.axisXWidth.xyz), y = dot(q, l.axisYHeight.xyz);
    if (kind == kRect) return abs(x) <= 0.5 * l.axisXWidth.w && abs(y) <= 0.5 * l.axisYHeight.w;
    return x * x + y * y <= radius * radius;
  }
  if (kShapeLights && kind == kCylinder) {
    vec3 oc = o - position;
    float oy = dot(oc, l.axisYHeight.xyz), oz = dot(oc, l.axisZLength.xyz);
    float dy = dot(d, l.axisYHeight.xyz), dz = dot(d, l.axisZLength.xyz);
    float a = dy * dy + dz * dz;
    if (!(a > 0.0)) return false;
    float b = oy * dy + oz * dz;
    float c = oy * oy + oz * oz - radius * radius;
    if (!(c > 0.0) || b >= 0.0) return false;
    float disc = b * b - a * c;
    if (disc < 0.0) return false;
    t = c / (-b + sqrt(disc));
    if (!(t > tMin && t < tMax)) return false;
    return abs(dot(oc + t * d, l.axisXWidth.xyz)) <= 0.5 * l.axisZLength.w;
  }
  return false;
}

float densityOf(Light l, vec3 p, vec3 n, vec3 wi) {
  int kind = l.info.x;
  if (kSphereLights && kind == kSphere) {
    vec3 toCentre = l.positionRadius.xyz - p;
    float d2 = dot(toCentre, toCentre), r2 = l.positionRadius.w * l.positionRadius.w;
    if (l.info.w != 0 || !(d2 > r2)) return 0.0;
    float sin2Max = r2 / d2;
    float oneMinusCosMax = sin2Max / (1.0 + sqrt(max(0.0, 1.0 - sin2Max)));
    return 1.0 / (2.0 * kPi * oneMinusCosMax);
  }
  if (kShapeLights && (kind == kRect || kind == kDisk || kind == kCylinder)) {
    float t;
    if (!hitShape(l, p, wi, 0.0, kInf, t)) return 0.0;
    vec3 q = p + t * wi;
    vec3 normal = l.emitArea.xyz;
    if (kind == kCylinder) {
      vec3 rel = q - l.positionRadius.xyz;
      normal = normalize(rel - dot(rel, l.axisXWidth.xyz) * l.axisXWidth.xyz);
    }
    float cosLight = -dot(normal, wi);
    return cosLight > 0.0 ? t * t / (l.emitArea.w * cosLight) : 0.0;
  }
  if (kDistantLights && kind == kDistant) {
    if (l.info.y != 0) return 0.0;
    vec3 c = cross(wi, l.toLightCone.xyz);
    return dot(wi, l.toLightCone.xyz) > 0.0 && dot(c, c) <= l.misc.x ? 1.0 / (2.0 * kPi * l.toLightCone.w) : 0.0;
  }
  if (!kDomeLights) return 0.0;
  // The dome.
  float density = (1.0 - l.misc.y) * max(0.0, dot(n, wi)) / kPi;
  if (kDomeMaps && l.info.z != 0 && l.misc.y > 0.0) density += l.misc.y * domeMapPdf(rows3(l.domeFromWorld, wi));
  return density;
}

float lightPdf(int light, vec3 p, vec3 n, vec3 wi) {
  Light l = lights[light];
  return l.radiancePick.w * densityOf(l, p, n, wi);
}

bool sampleLight(vec3 p, vec3 n, float uPick, vec2 u, out LightSample s) {
  s.direction = vec3(0.0);
  s.distance = 0.0;
  s.radiance = vec3(0.0);
  s.pdf = 0.0;
  s.delta = false;
  s.light = -1;
  int count = params.counts.y;
  int cdf = params.dome.w;
  if (count == 0 || !(params.tables[cdf + count] > 0.0)) return false;
  int above = 0;  // std::upper_bound over the count + 1 entries
  while (above <= count && !(uPick < params.tables[cdf + above])) above++;
  int index = min(max(above - 1, 0), count - 1);
  Light l = lights[index];
  float pick = l.radiancePick.w;
  if (!(pick > 0.0)) return false;
  float uRest = clamp((uPick - params.tables[cdf + index]) / pick, 0.0, kOneBelowOne);
  s.light = index;
  int kind = l.info.x;
  if (kSphereLights && kind == kSphere) {
    vec3 toCentre = l.positionRadius.xyz - p;
    float d2 = dot(toCentre, toCentre);
    float r2 = l.positionRadius.w * l.positionRadius.w;
    if (l.info.w != 0) {  // intensity L pi r^2: the irradiance it gives at distance d, head-on
      if (!(d2 > 0.0)) return false;
      float d = sqrt(d2);
      s.direction = toCentre / d;
      s.distance = d;
      s.radiance = l.radiancePick.xyz * (kPi * r2 / d2);
      s.pdf = pick;
      s.delta = true;
      return s.pdf > 0.0 && !isinf(s.pdf) && !isnan(s.pdf);
    }
    if (!(d2 > r2)) return false;
    float d = sqrt(d2);
    float sin2Max = r2 / d2;
    float cosMax = sqrt(max(0.0, 1.0 - sin2Max));
    float oneMinusCosMax = sin2Max / (1.0 + cosMax);
    vec3 axis = toCentre / d;
    s.direction = sampleCone(axis, oneMinusCosMax, u);
    float along = dot(s.direction, toCentre);
    float disc = r2 - (d2 - along * along);
    s.distance = disc > 0.0 ? along - sqrt(disc) : sqrt(max(d2 - r2, 0.0));
    s.radiance = l.radiancePick.xyz;
    s.pdf = pick / (2.0 * kPi * oneMinusCosMax);
  } else if (kShapeLights && (kind == kRect || kind == kDisk || kind == kCylinder)) {
    vec3 q, normal;
    vec3 position = l.positionRadius.xyz;
    if (kind == kRect) {
      q = position + (u.x - 0.5) * l.axisXWidth.w * l.axisXWidth.xyz + (u.y - 0.5) * l.axisYHeight.w * l.axisYHeight.xyz;
      normal = l.emitArea.xyz;
    } else if (kind == kDisk) {
      vec2 d = concentricDisk(u) * l.positionRadius.w;
      q = position + d.x * l.axisXWidth.xyz + d.y * l.axisYHeight.xyz;
      normal = l.emitArea.xyz;
    } else {
      float phi = 2.0 * kPi * u.y;
      normal = cos(phi) * l.axisYHeight.xyz + sin(phi) * l.axisZLength.xyz;
      q = position + (u.x - 0.5) * l.axisZLength.w * l.axisXWidth.xyz + l.positionRadius.w * normal;
    }
    vec3 toLight = q - p;
    float d2 = dot(toLight, toLight);
    if (!(d2 > 0.0)) return false;
    float d = sqrt(d2);
    s.direction = toLight / d;
    float cosLight = -dot(normal, s.direction);
    if (!(cosLight > 0.0)) return false;
    s.distance = d;
    s.radiance = l.radiancePick.xyz;
    s.pdf = pick * d2 / (l.emitArea.w * cosLight);
  } else if (kDistantLights && kind == kDistant) {
    if (l.info.y != 0) {
      s.direction = l.toLightCone.xyz;
      s.pdf = pick;
      s.delta = true;
    } else {
      s.direction = sampleCone(l.toLightCone.xyz, l.toLightCone.w, u);
      s.pdf = pick / (2.0 * kPi * l.toLightCone.w);
    }
    s.distance = kInf;
    s.radiance = l.radiancePick.xyz;
  } else if (kDomeLights) {
    if (kDomeMaps && uRest < l.misc.y) {
      s.direction = normalize(rows3T(l.domeFromWorld, domeMapSample(u)));
    } else {
      vec2 d = concentricDisk(u);
      float z = sqrt(max(0.0, 1.0 - dot(d, d)));
      s.direction = normalize(toWorld(frameFromNormal(n), vec3(d, z)));
    }
    s.distance = kInf;
    s.radiance = domeRadiance(l, s.direction);
    s.pdf = pick * densityOf(l, p, n, s.direction);
  }
  return s.pdf > 0.0 && !isinf(s.pdf) && !isnan(s.pdf);
}

// A light's inputs:diffuse and inputs:specular on the BSDF's lobes (PtLights::response, responseScale).
vec3 lightResponse(int light, vec3 fd, vec3 fs) { return lights[light].misc.z * fd + lights[light].misc.w * fs; }
vec3 responseScale(int light, vec3 fd, vec3 fs) {
  vec3 sum = fd + fs, weighted = lightResponse(light, fd, fs);
  return vec3(sum.x > 0.0 ? weighted.x / sum.x : 1.0, sum.y > 0.0 ? weighted.y / sum.y : 1.0,
              sum.z > 0.0 ? weighted.z / sum.z : 1.0);
}

// The closest emitting face of a light shape along the ray.
// The lights a ray can meet (gpu_scene.cpp): after the pick cdf's count
// + 1 entries, their number, then their indices in ascending order.
int hittableLightsAt() { return params.dome.w + params.counts.y + 1; }

// The scene's trace (traceScene) with the lights a ray can meet (sphere,
// rect, disk, cylinder) tested first; `lightMode` is kNoLights (a camera
// ray: lights are not seen directly), kEveryLight or the one light a shadow
// ray goes to, left out. A light met shortens the ray before the BVH is
// walked; `light` is the light met when it is nearer than any triangle, -1
// otherwise. A shadow ray (anyHit) that meets a light is blocked and walks
// no BVH. One call for the lights and the scene, where the shading tested
// the lights after the trace (with pt_trace.glsl's draws made where they
// are used: on an H100 the done-when run 3.4 % faster, the same bytes).
const int kNoLights = -2, kEveryLight = -1;
bool traceWithLights(vec3 o, vec3 d, float tMax, bool anyHit, int lightMode, out Hit hit, out int light) {
  light = -1;
  if (lightMode != kNoLights) {
    int at = hittableLightsAt();
    int hittable = int(params.tables[at]);
    for (int k = 1; k <= hittable; ++k) {
      int i = int(params.tables[at + k]);
      float t;
      if (i == lightMode || !hitShape(lights[i], o, d, 0.0, tMax, t)) continue;
      light = i;
      tMax = t;
      if (anyHit) break;
    }
    if (anyHit && light >= 0) {
      hit.instance = hit.triangle = 0u;
      hit.u = hit.v = hit.t = 0.0;
      return true;
    }
  }
  if (traceScene(o, d, 0.0, tMax, anyHit, hit)) light = -1;
  else if (light < 0) return false;
  return true;
}

// `lobes`: whether (fd, fs), the BSDF's lobes along wi at p, scale each light by its multipliers.
vec3 escaped(vec3 p, vec3 n, vec3 wi, float pdfBsdf, bool lobes, vec3 fd, vec3 fs) {
  vec3 sum = vec3(0.0);
  for (int i = 0; i < params.counts.y; ++i) {
    Light l = lights[i];
    vec3 radiance;
    if (kDomeLights && l.info.x == kDome) {
      radiance = domeRadiance(l, wi);
    } else if (kDistantLights && l.info.x == kDistant && l.info.y == 0) {
      vec3 c = cross(wi, l.toLightCone.xyz);
      if (!(dot(wi, l.toLightCone.xyz) > 0.0 && dot(c, c) <= l.misc.x)) continue;
      radiance = l.radiancePick.xyz;
    } else {
      continue;
    }
    float weight = pdfBsdf > 0.0 ? powerHeuristic(pdfBsdf, l.radiancePick.w * densityOf(l, p, n, wi)) : 1.0;
    if (lobes && (l.misc.z != 1.0 || l.misc.w != 1.0)) radiance *= responseScale(i, fd, fs);
    sum += weight * radiance;
  }
  return sum;
}
