// Part 5: one invocation per pixel, a port of path_tracer.cpp's
// tracePath, traceLabels and the per-pixel sample loop. Each dispatch adds
// samples [first, first + count) of every pixel to its running sum, in
// sample order, so the sum is the same whatever the dispatches' split.
const int kRouletteDepth = 3;

vec3 offsetOrigin(vec3 p, vec3 sideNormal) {
  float scale = max(1.0, maxComponent(abs(p)));
  return p + sideNormal * (2e-5 * scale);
}

void cameraRay(vec2 pixel, out vec3 origin, out vec3 direction, out float tMax) {
  vec3 a = params.camNear0.xyz + pixel.x * params.camNearX.xyz + pixel.y * params.camNearY.xyz;
  vec3 b = params.camFar0.xyz + pixel.x * params.camFarX.xyz + pixel.y * params.camFarY.xyz;
  vec3 along = b - a;
  tMax = length(along);
  origin = a;
  direction = along / tMax;
}

// One path's radiance: path_tracer.cpp's tracePath, its vertices and their
// shadow rays taken in the same order, written around a single scene
// trace (the current ray is either the path's or a pending shadow ray) so
// the traversal and the shading are each compiled once. With `label`, the
// path stops at its first surface and writes the pixel's label planes.
vec3 tracePath(vec3 origin, vec3 direction, float tMax, inout Sampler sampler, inout uint rays, bool label,
               inout FilmPixel px) {
  int maxBounces = params.counts.x;
  vec3 radiance = vec3(0.0);
  vec3 beta = vec3(1.0);
  float pdfBsdf = 0.0;
  vec3 previousPoint = vec3(0.0), previousNormal = vec3(0.0);
  float tMin = 0.0;
  int depth = 0;
  // The shadow ray being traced (shadow true): what it adds if nothing blocks it, and where the path goes after.
  bool shadow = false;
  vec3 shadowRadiance = vec3(0.0);
  int shadowLight = -1;
  bool continues = false;
  vec3 nextOrigin = vec3(0.0), nextDirection = vec3(0.0);
  // The previous vertex's BSDF lobes along the sampled direction, where a light scales them apart.
  bool lobeMultipliers = params.counts.w != 0;
  vec3 previousDiffuse = vec3(0.0), previousSpecular = vec3(0.0);
  for (;;) {
    Hit hit;
    bool found = traceScene(origin, direction, tMin, tMax, shadow, hit);
    rays++;
    if (shadow) {
      if (!found && !lightsBlock(origin, direction, 0.0, tMax, shadowLight)) radiance += shadowRadiance;
      shadow = false;
    } else {
      int light;
      vec3 lightRadiance;
      if (depth > 0 && intersectLights(origin, direction, tMin, found ? hit.t : tMax, light, lightRadiance)) {
        float weight = powerHeuristic(pdfBsdf, lightPdf(light, previousPoint, previousNormal, direction));
        if (lobeMultipliers) lightRadiance *= responseScale(light, previousDiffuse, previousSpecular);
        radiance += beta * lightRadiance * weight;
        break;
      }
      if (!found) {
        float pdf = depth == 0 ? 0.0 : pdfBsdf;
        if (!label)
          radiance += beta * escaped(previousPoint, previousNormal, direction, pdf, depth > 0 && lobeMultipliers,
                                     previousDiffuse, previousSpecular);
        break;
      }
      if (depth == maxBounces && !label) break;
      float uPick = next1D(sampler);
      vec2 uLight = next2D(sampler);
      float uLobe = next1D(sampler);
      vec2 uBsdf = next2D(sampler);
      float uRoulette = next1D(sampler);

      Geometry g = surfaceGeometry(hit.instance, hit.triangle, hit.u, hit.v);
      vec3 wo = -direction;
      Shaded surface = shadeSurface(materialOf(hit.instance, g.part), g, wo);
      if (label) {
        px.albedo = vec4(surface.albedo, 0.0);
        px.normalDepth = vec4(surface.normal, length(g.position - params.eye.xyz));
        px.rays.w = uint(instances[hit.instance].ids.w);
        break;
      }
      vec3 side = dot(g.geometricNormal, wo) < 0.0 ? -g.geometricNormal : g.geometricNormal;
      Frame shading = frameFromNormal(surface.normal);
      Bsdf bsdf = makeBsdf(surface.baseColor, surface.metallic, surface.roughness, surface.specularLevel);
      vec3 woLocal = toLocal(shading, wo);
      vec3 next = offsetOrigin(g.position, side);

      // Next-event estimation: one light, one direction, one shadow ray (traced next).
      float shadowMax = 0.0;
      vec3 shadowDirection = vec3(0.0);
      LightSample ls;
      if (sampleLight(g.position, surface.normal, uPick, uLight, ls) && dot(ls.direction, side) > 0.0) {
        vec3 wiLocal = toLocal(shading, ls.direction);
        vec3 fd, fs;
        bsdfEvalLobes(bsdf, woLocal, wiLocal, fd, fs);
        vec3 f = lightResponse(ls.light, fd, fs);
        if (maxComponent(f) > 0.0) {
          shadow = true;
          shadowMax = isinf(ls.distance) ? kInf : ls.distance * (1.0 - 1e-4);
          shadowDirection = ls.direction;
          shadowLight = ls.light;
          float weight = ls.delta ? 1.0 : powerHeuristic(ls.pdf, bsdfPdf(bsdf, woLocal, wiLocal));
          shadowRadiance = beta * f * ls.radiance * (weight / ls.pdf);
        }
      }

      // The BSDF's direction continues the path.
      vec3 wiLocal, weight;
      float pdf;
      continues = bsdfSample(bsdf, woLocal, uBsdf, uLobe, wiLocal, weight, pdf);
      vec3 wi = normalize(toWorld(shading, wiLocal));
      continues = continues && dot(wi, side) > 0.0;
      if (continues) {
        beta *= weight;
        pdfBsdf = pdf;
        previousPoint = g.position;
        previousNormal = surface.normal;
        if (lobeMultipliers) bsdfEvalLobes(bsdf, woLocal, wiLocal, previousDiffuse, previousSpecular);
        if (depth >= kRouletteDepth) {
          float q = max(0.0, 1.0 - maxComponent(beta));
          if (uRoulette < q) continues = false;
          else beta /= 1.0 - q;
        }
      }
      nextOrigin = next;
      nextDirection = wi;
      if (shadow) {
        origin = next;
        direction = shadowDirection;
        tMin = 0.0;
        tMax = shadowMax;
        continue;
      }
    }
    if (!continues) break;
    origin = nextOrigin;
    direction = nextDirection;
    tMin = 0.0;
    tMax = kInf;
    depth++;
  }
  return radiance;
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  int width = params.size.x, height = params.size.y;
  if (pixel.x >= uint(width) || pixel.y >= uint(height)) return;
  uint index = pixel.y * uint(width) + pixel.x;
  FilmPixel px = film[index];
  uint rays = 0u;
  bool labels = params.seed.w != 0u;
  if (labels) {
    // Cleared here, then written by the label ray (the ray through the pixel's centre) if it meets a surface.
    px.sum = vec4(0.0);
    px.albedo = vec4(0.0);
    px.normalDepth = vec4(0.0, 0.0, 0.0, kInf);
    px.rays = uvec4(0u);
  }
  Sampler sampler = pixelSampler(params.seed.xy, pixel.x, pixel.y);
  // Sample -1 is the label ray: one code path for both, so the kernel holds one copy of it.
  for (int s = params.size.z - (labels ? 1 : 0); s < params.size.z + params.size.w; ++s) {
    bool label = s < 0;
    vec2 jitter = vec2(0.5);
    if (!label) {
      startSample(sampler, uint(s));
      jitter = next2D(sampler);
    }
    vec3 o, d;
    float tMax;
    cameraRay(vec2(pixel) + jitter, o, d, tMax);
    vec3 L = tracePath(o, d, tMax, sampler, rays, label, px);
    if (label) continue;
    if (any(isnan(L)) || any(isinf(L))) {
      px.sum.w += 1.0;
      continue;
    }
    px.sum.xyz += L;
    float l = luminance(L);
    px.albedo.w += l * l;  // for the per-pixel variance (PathTracedFrame::variance)
  }
  px.rays.z += uint(params.size.w) + (labels ? 1u : 0u);
  uint low = px.rays.x + rays;
  px.rays.y += low < rays ? 1u : 0u;
  px.rays.x = low;
  film[index] = px;
}
