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

// The pixel's samples: path_tracer.cpp's tracePath for each, its vertices
// and their shadow rays taken in the same order. One loop whose every
// iteration is the same three steps for every invocation: trace the shadow
// ray the previous vertex left (if any), trace the path's ray, shade what
// it met. So a warp's invocations stay in step, shading together, whatever
// sample or bounce each is at (with a shadow ray and a path ray in
// alternate iterations, invocations out of step shaded in every other
// iteration: on an H100 this form is 7-10 % faster). A path that ends
// starts the pixel's next sample in the same iteration. Both rays go
// through one traceWithLights call in a two-pass loop, so the traversal is
// compiled once. Sample -1 is the label ray: it stops at its first surface
// and writes the pixel's label planes.
void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  int width = params.size.x, height = params.size.y;
  if (pixel.x >= uint(width) || pixel.y >= uint(height)) return;
  uint index = pixel.y * uint(width) + pixel.x;
  uint rays = 0u;
  bool labels = params.seed.w != 0u;
  // Only the running sums live in registers through the loop; the label
  // planes go to the film when the label ray meets its surface.
  vec4 sum = vec4(0.0);
  float luminanceSquares = 0.0;
  if (labels) {
    // Cleared here, then written by the label ray (the ray through the pixel's centre) if it meets a surface.
    film[index].albedo = vec4(0.0);
    film[index].normalDepth = vec4(0.0, 0.0, 0.0, kInf);
    film[index].rays = uvec4(0u);
  } else {
    sum = film[index].sum;
    luminanceSquares = film[index].albedo.w;
  }
  Sampler sampler = pixelSampler(params.seed.xy, pixel.x, pixel.y, params.sampling.yz);
  int maxBounces = params.counts.x;
  bool lobeMultipliers = kLobeMultipliers && params.counts.w != 0;
  int sampleEnd = params.size.z + params.size.w;
  int s = params.size.z - (labels ? 1 : 0);

  // The path's state. pathLive: origin and direction hold the path's next ray.
  bool pathLive = false, label = false;
  vec3 origin = vec3(0.0), direction = vec3(0.0);
  float tMax = 0.0;
  vec3 radiance = vec3(0.0), beta = vec3(1.0);
  float pdfBsdf = 0.0;
  vec3 previousPoint = vec3(0.0), previousNormal = vec3(0.0);
  int depth = 0;
  // The shadow ray pending (shadow true): from `origin` (the next ray of a path that goes on starts at
  // the same point), along what, how far, and what it adds if nothing blocks it. The path's ray has no
  // near distance of its own (its origin is offset from the surface instead): every register the loop
  // keeps costs invocations in flight.
  bool shadow = false;
  vec3 shadowDirection = vec3(0.0), shadowRadiance = vec3(0.0);
  float shadowMax = 0.0;
  int shadowLight = -1;
  // The previous vertex's BSDF lobes along the sampled direction, where a light scales them apart.
  vec3 previousDiffuse = vec3(0.0), previousSpecular = vec3(0.0);

  bool unfinished = false;  // the current sample's radiance is not yet in the pixel's sum
  for (;;) {
    Hit hit;
    bool found = false;
    int hitLight = -1;
    for (int pass = shadow ? 0 : 1; pass < 2; ++pass) {
      if (pass == 1 && !pathLive) {
        // The path is done (its last shadow ray traced): its sample joins the pixel's sum, in sample order.
        if (unfinished && !label) {
          if (any(isnan(radiance)) || any(isinf(radiance))) {
            sum.w += 1.0;
          } else {
            sum.xyz += radiance;
            float l = luminance(radiance);
            luminanceSquares += l * l;  // for the per-pixel variance (PathTracedFrame::variance)
          }
        }
        if (unfinished) s++;
        unfinished = false;
        if (s >= sampleEnd) break;
        // The next sample's camera ray, traced in this pass.
        label = s < 0;
        vec2 jitter = vec2(0.5);
        if (!label) {
          startSample(sampler, uint(s));
          jitter = next2D(sampler);
        }
        cameraRay(vec2(pixel) + jitter, origin, direction, tMax);
        radiance = vec3(0.0);
        beta = vec3(1.0);
        pdfBsdf = 0.0;
        previousPoint = previousNormal = vec3(0.0);
        depth = 0;
        previousDiffuse = previousSpecular = vec3(0.0);
        pathLive = unfinished = true;
      }
      bool isShadow = pass == 0;
      Hit traced;
      int metLight;
      bool met = traceWithLights(origin, isShadow ? shadowDirection : direction, isShadow ? shadowMax : tMax, isShadow,
                                 isShadow ? shadowLight : (depth > 0 ? kEveryLight : kNoLights), traced, metLight);
      rays++;
      if (isShadow) {
        if (!met) radiance += shadowRadiance;
        shadow = false;
      } else {
        hit = traced;
        found = met && metLight < 0;
        hitLight = metLight;
      }
    }
    if (!pathLive) break;  // every sample done

    // What the path's ray met.
    bool continues = false;
    vec3 next = vec3(0.0), wi = vec3(0.0);
    if (hitLight >= 0) {
      int light = hitLight;
      vec3 lightRadiance = lights[light].radiancePick.xyz;
      float weight = powerHeuristic(pdfBsdf, lightPdf(light, previousPoint, previousNormal, direction));
      if (lobeMultipliers) lightRadiance *= responseScale(light, previousDiffuse, previousSpecular);
      radiance += beta * lightRadiance * weight;
    } else if (!found) {
      float pdf = depth == 0 ? 0.0 : pdfBsdf;
      if (!label)
        radiance += beta * escaped(previousPoint, previousNormal, direction, pdf, depth > 0 && lobeMultipliers,
                                   previousDiffuse, previousSpecular);
    } else if (depth < maxBounces || label) {

      Geometry g = surfaceGeometry(hit.instance, hit.triangle, hit.u, hit.v);
      vec3 wo = -direction;
      Shaded surface = shadeSurface(materialOf(hit.instance, g.part), g, wo);
      if (label) {
        film[index].albedo.xyz = surface.albedo;
        film[index].normalDepth = vec4(surface.normal, length(g.position - params.eye.xyz));
        film[index].rays.w = uint(instances[hit.instance].ids.w);
      } else {
        vec3 side = dot(g.geometricNormal, wo) < 0.0 ? -g.geometricNormal : g.geometricNormal;
        Frame shading = frameFromNormal(surface.normal);
        Bsdf bsdf = makeBsdf(surface.baseColor, surface.metallic, surface.roughness, surface.specularLevel);
        vec3 woLocal = toLocal(shading, wo);
        next = offsetOrigin(g.position, side);

        // Next-event estimation: one light, one direction, one shadow ray (traced first in the next iteration).
        LightSample ls;
        // The vertex's draws in the CPU tracer's order (pick, light, lobe,
        // BSDF, roulette), each made where it is used rather than all up
        // front, so fewer values are live through the light and BSDF code
        // (on an H100, with traceWithLights, the done-when run 3.4 % and the
        // demo's stage 3 % faster; the same numbers).
        float uPick = next1D(sampler);
        vec2 uLight = next2D(sampler);
        if (sampleLight(g.position, surface.normal, uPick, uLight, ls) && dot(ls.direction, side) > 0.0) {
          vec3 wiLocal = toLocal(shading, ls.direction);
          vec3 fd, fs;
          bsdfEvalLobes(bsdf, woLocal, wiLocal, fd, fs);
          vec3 f = lightResponse(ls.light, fd, fs);
          if (maxComponent(f) > 0.0) {
            shadow = true;
            origin = next;  // the shadow ray's origin; the path's next ray starts there too
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
        float uLobe = next1D(sampler);
        vec2 uBsdf = next2D(sampler);
        continues = bsdfSample(bsdf, woLocal, uBsdf, uLobe, wiLocal, weight, pdf);
        wi = normalize(toWorld(shading, wiLocal));
        continues = continues && dot(wi, side) > 0.0;
        if (continues) {
          beta *= weight;
          pdfBsdf = pdf;
          previousPoint = g.position;
          previousNormal = surface.normal;
          if (lobeMultipliers) bsdfEvalLobes(bsdf, woLocal, wiLocal, previousDiffuse, previousSpecular);
          if (depth >= kRouletteDepth) {
            float uRoulette = next1D(sampler);
            float q = max(0.0, 1.0 - maxComponent(beta));
            if (uRoulette < q) continues = false;
            else beta /= 1.0 - q;
          } else {
            sampler.slot++;  // the roulette's draw, not needed: the next vertex's draws keep their slots
          }
        }
      }
    }
    if (continues) {  // the next bounce, traced after the shadow ray
      origin = next;
      direction = wi;
      tMax = kInf;
      depth++;
    } else {
      pathLive = false;  // finished once its shadow ray, if any, is traced
    }
  }
  film[index].sum = sum;
  film[index].albedo.w = luminanceSquares;
  uvec3 counts = film[index].rays.xyz;
  counts.z += uint(params.size.w) + (labels ? 1u : 0u);
  uint low = counts.x + rays;
  counts.y += low < rays ? 1u : 0u;
  counts.x = low;
  film[index].rays.xyz = counts;
}
