#include "render/pathtrace/path_tracer.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <optional>
#include <stdexcept>
#include <thread>

#include "assets/image.h"
#include "assets/mesh_source.h"
#include "assets/texture_source.h"
#include "core/diagnostics.h"
#include "render/camera_math.h"
#include "render/pathtrace/embree_scene.h"
#include "render/pathtrace/pt_lights.h"
#include "render/pathtrace/pt_materials.h"
#include "render/pathtrace/pt_surfaces.h"
#include "render/pathtrace/pt_textures.h"
#include "render/pathtrace/sampler.h"

namespace sdg {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kTileSize = 16;  // a power of two: sampler tiles (sampler.h) hold whole tiles or tile them exactly
static_assert((kTileSize & (kTileSize - 1)) == 0);
// Domes whose maps stay loaded, as in the rasterizer: a randomizer cycling
// through a few does not read them again.
constexpr size_t kMaxCachedDomes = 8;
// Russian roulette starts at this vertex (0 is the first hit).
constexpr int kRouletteDepth = 3;

// New rays leave a surface from a point pushed off it along the geometric
// normal, on the side they go to: far enough that rounding in the hit
// point (a few ulps of its coordinates) cannot put the origin behind the
// surface, and scaled with the coordinates for that reason.
Vec3f offsetOrigin(const Vec3f& p, const Vec3f& sideNormal) {
  const float scale = std::max(1.0f, p.cwiseAbs().maxCoeff());
  return p + sideNormal * (2e-5f * scale);
}

// Primary rays through the rasterizer's projection (camera_math.h): a point
// of the image is taken back to the near and far clipping planes, so
// perspective, orthographic, aperture offsets and the clipping range all
// follow the matrices the rasterizer draws with. A calibrated lens
// (lens_model.h) gives each image point its ray directly, from the eye,
// clipped by distance (nearClip to farClip along the ray: a plane cannot
// clip a view wider than 180 degrees); a point the lens images nothing at
// gets an inactive ray (tMax < tMin), which finds nothing and carries no
// light, so it stays black and unlabelled.
class CameraRays {
 public:
  CameraRays(const RenderCamera& camera, int width, int height)
      : cameraFromClip_(projectionMatrix(camera, width, height).inverse()),
        rotation_(camera.worldFromCamera.block<3, 3>(0, 0)),
        eye_(camera.worldFromCamera.block<3, 1>(0, 3)),
        lens_(camera.lens),
        nearClip_(camera.nearClip),
        farClip_(camera.farClip),
        width_(width),
        height_(height) {}

  // The ray through image point (px, py): x right, y down, in pixels.
  PtRay ray(double px, double py) const {
    if (lens_.calibrated()) return lensRay(px, py);
    const double x = 2.0 * px / width_ - 1.0, y = 1.0 - 2.0 * py / height_;
    Eigen::Vector4d nearPoint = cameraFromClip_ * Eigen::Vector4d(x, y, -1.0, 1.0);
    Eigen::Vector4d farPoint = cameraFromClip_ * Eigen::Vector4d(x, y, 1.0, 1.0);
    const Vec3d a = nearPoint.head<3>() / nearPoint.w(), b = farPoint.head<3>() / farPoint.w();
    const Vec3d along = b - a;
    const double length = along.norm();
    PtRay r;
    r.origin = (rotation_ * a + eye_).cast<float>();
    r.direction = (rotation_ * (along / length)).cast<float>();
    r.tMin = 0.0f;
    r.tMax = float(length);
    return r;
  }
  Vec3f eye() const { return eye_.cast<float>(); }

 private:
  PtRay lensRay(double px, double py) const {
    PtRay r;
    r.origin = eye_.cast<float>();
    // The lens's pixels have their centres at integers, the image's at .5.
    const std::optional<Vec3d> direction =
        lensUnproject(lens_, Eigen::Vector2d(px - 0.5, py - 0.5), int(width_), int(height_));
    r.direction = direction ? (rotation_ * *direction).cast<float>() : Vec3f(0, 0, -1);
    r.tMin = direction ? nearClip_ : 1.0f;
    r.tMax = direction ? farClip_ : -1.0f;
    return r;
  }

  Matrix4d cameraFromClip_;
  Eigen::Matrix3d rotation_;
  Vec3d eye_;
  LensModel lens_;
  float nearClip_, farClip_;
  double width_, height_;
};

}  // namespace

struct PathTracer::Caches {
  explicit Caches(const AssetResolver& assets) : geometry(assets) {}
  PtGeometryCache geometry;
  std::map<std::string, std::unique_ptr<PtDomeMap>> domes;
};

// Everything one render() reads while its threads run: the surfaces
// (materials, ids, the cut-out test) and the lights.
struct PtFrameData final : PtSurfaces {
  PtLights lights;
};

PathTracer::PathTracer(const AssetResolver& assets, const PathTraceSettings& settings)
    : assets_(assets), settings_(settings), caches_(std::make_unique<Caches>(assets)) {
  settings_.samples = std::max(settings_.samples, 1);
  settings_.maxBounces = std::max(settings_.maxBounces, 0);
  if (settings_.threads <= 0) settings_.threads = int(std::max(1u, std::thread::hardware_concurrency()));
}

PathTracer::~PathTracer() = default;

void PathTracer::prepare(const RenderList& list, PtFrameData& frame) {
  Caches& c = *caches_;
  preparePtSurfaces(list, assets_, c.geometry, frame);
  frame.lights.build(list, c.geometry.scene.bounds(), [&](const RenderLight& light) -> const PtDomeMap* {
    auto it = c.domes.find(light.texture);
    if (it != c.domes.end()) return it->second.get();
    ImageRgbaF map = loadDomeMap(light.texture, assets_, light.path);
    if (c.domes.size() >= kMaxCachedDomes) c.domes.erase(c.domes.begin());  // any: which one is not visible
    return c.domes.emplace(light.texture, std::make_unique<PtDomeMap>(std::move(map))).first->second.get();
  });
}

namespace {

struct TraceCounters {
  uint64_t rays = 0, cameraRays = 0, dropped = 0;
  std::vector<TracedRay>* log = nullptr;  // benchmarks only
  void record(const PtRay& ray, TracedRayKind kind) {
    if (log) log->push_back(TracedRay{ray, kind});
  }
};

}  // namespace

// One path of a wave (a tile's paths for one sample index, traced
// together) between two Embree calls.
struct PtWavePath {
  PtRay ray;
  Vec3f radiance = Vec3f::Zero();
  Vec3f beta = Vec3f::Ones();  // the path's throughput
  // The previous vertex, for the MIS weight of light that a BSDF sample finds.
  float bsdfPdf = 0.0f;
  Vec3f previousPoint = Vec3f::Zero(), previousNormal = Vec3f::Zero();
  // Its BSDF's lobes along the sampled direction, kept only where a light
  // scales its diffuse or specular response.
  BsdfLobes previousLobes{Vec3f::Zero(), Vec3f::Zero()};

  void start(const PtRay& cameraRay) {
    ray = cameraRay;
    radiance.setZero();
    // An inactive camera ray (outside a lens's image) carries nothing.
    if (cameraRay.tMax >= cameraRay.tMin) beta.setOnes();
    else beta.setZero();
    bsdfPdf = 0.0f;
    previousPoint.setZero();
    previousNormal.setZero();
    previousLobes = BsdfLobes{Vec3f::Zero(), Vec3f::Zero()};
  }
};

// Next-event estimation's light at a vertex, waiting for its shadow ray.
struct PtPendingLight {
  Vec3f contribution;
  uint32_t path;
  int light;
};

// A thread's wave buffers, reused tile after tile.
struct PtWaveBuffers {
  std::vector<SamplerTile> samplerTiles;    // the sampler tiles the tile covers (one, but at huge sample counts)
  std::vector<PixelSampler> samplers;       // the tile's pixels, row by row
  std::vector<std::array<double, 4>> sums;  // per pixel: the radiance's RGB and luminance^2 over its samples
  std::vector<PtWavePath> paths;            // per pixel: its path of the sample being traced
  std::vector<uint32_t> active, next;       // the paths still going, in pixel order
  std::vector<PtRay> rays;                  // the active paths' rays, for one Embree stream
  std::vector<SurfaceHit> hits;
  std::vector<uint8_t> found;
  std::vector<PtRay> shadowRays;
  std::vector<PtPendingLight> pending;  // one per shadow ray
  std::vector<uint8_t> occluded;
};

namespace {

// One vertex of a path whose ray has been traced (`hit`: null where it left
// the scene): pbrt-v4's PathIntegrator::Li's loop body with this renderer's
// lights and surfaces. Light that the ray finds goes into the radiance;
// next-event estimation queues one shadow ray and what it adds when
// unblocked; the BSDF's direction becomes the path's next ray. False when
// the path ends here. Each vertex draws its numbers in a fixed order, used
// or not (light pick, light direction, BSDF lobe, BSDF direction,
// roulette), after the camera's jitter, so a sample's slots mean the same
// on every path.
bool shadeVertex(const PtFrameData& frame, int maxBounces, int depth, PtWavePath& path, uint32_t pathIndex,
                 const SurfaceHit* hit, PixelSampler& sampler, PtWaveBuffers& wave) {
  const PtLights& lights = frame.lights;
  const PtRay& ray = path.ray;
  // A light shape in front of the surface: its emission, and the path ends.
  // Camera rays pass through light shapes: the rasterizer, the labels and
  // Blender (whose lamps are invisible to the camera) do not show them
  // either; reflections and the light they cast do.
  if (depth > 0) {
    PtRay toLights = ray;
    if (hit) toLights.tMax = hit->t;
    LightHit lightHit;
    if (lights.intersect(toLights, lightHit)) {
      const float lightPdf = lights.pdf(lightHit.light, path.previousPoint, path.previousNormal, ray.direction);
      const float weight = powerHeuristic(path.bsdfPdf, lightPdf);
      Vec3f emitted = lightHit.radiance;
      if (lights.anyLobeMultiplier())
        emitted = emitted.cwiseProduct(lights.responseScale(lightHit.light, path.previousLobes));
      path.radiance += path.beta.cwiseProduct(emitted) * weight;
      return false;
    }
  }
  if (!hit) {
    // Camera rays (depth 0) see the sky unweighted.
    const float pdf = depth == 0 ? 0.0f : path.bsdfPdf;
    const BsdfLobes* lobes = depth > 0 && lights.anyLobeMultiplier() ? &path.previousLobes : nullptr;
    path.radiance +=
        path.beta.cwiseProduct(lights.escaped(path.previousPoint, path.previousNormal, ray.direction, pdf, lobes));
    return false;
  }
  if (depth == maxBounces) return false;
  const float uPick = sampler.next1D();
  const Vec2f uLight = sampler.next2D();
  const float uLobe = sampler.next1D();
  const Vec2f uBsdf = sampler.next2D();
  const float uRoulette = sampler.next1D();

  const SurfaceGeometry g = frame.scene->geometry(*hit);
  const Vec3f wo = -ray.direction;
  const ShadedSurface surface = shadeSurface(frame.material(hit->instance, g.part), g, wo);
  // The geometric normal on the viewer's side: reflected light must stay
  // on this side (pbrt-v3's test; a shading normal alone would let light
  // through the surface).
  const Vec3f side = g.geometricNormal.dot(wo) < 0.0f ? Vec3f(-g.geometricNormal) : g.geometricNormal;
  const ShadingFrame shading = ShadingFrame::fromNormal(surface.normal);
  const PbrBsdf bsdf(surface.material);
  const PbrBsdf::View view = bsdf.view(shading.toLocal(wo));
  const Vec3f origin = offsetOrigin(g.position, side);

  // Next-event estimation: one light, one direction, one shadow ray.
  LightSample light;
  if (lights.sample(g.position, surface.normal, uPick, uLight, light) && light.direction.dot(side) > 0.0f) {
    const Vec3f wiLocal = shading.toLocal(light.direction);
    float bsdfPdf;
    const Vec3f f = lights.response(light.light, bsdf.evalLobes(view, wiLocal, bsdfPdf));
    if (f.maxCoeff() > 0.0f) {
      wave.shadowRays.push_back(PtRay{origin, light.direction, 0.0f,
                                      std::isinf(light.distance) ? kInf : light.distance * (1.0f - 1e-4f)});
      const float weight = light.delta ? 1.0f : powerHeuristic(light.pdf, bsdfPdf);
      wave.pending.push_back(
          PtPendingLight{path.beta.cwiseProduct(f).cwiseProduct(light.radiance) * (weight / light.pdf), pathIndex,
                       light.light});
    }
  }

  // The BSDF's direction continues the path.
  BsdfLobes sampledLobes;
  const std::optional<BsdfSample> next = bsdf.sample(view, uBsdf, uLobe, sampledLobes);
  if (!next) return false;
  const Vec3f wi = shading.toWorld(next->wi).normalized();
  if (!(wi.dot(side) > 0.0f)) return false;
  path.beta = path.beta.cwiseProduct(next->weight);
  path.bsdfPdf = next->pdf;
  path.previousPoint = g.position;
  path.previousNormal = surface.normal;
  if (lights.anyLobeMultiplier()) path.previousLobes = sampledLobes;
  if (depth >= kRouletteDepth) {
    // pbrt-v4: continue with the probability of the throughput's largest
    // component (when below 1), and weigh the survivors up.
    const float q = std::max(0.0f, 1.0f - path.beta.maxCoeff());
    if (uRoulette < q) return false;
    path.beta /= 1.0f - q;
  }
  path.ray = PtRay{origin, wi, 0.0f, kInf};
  return true;
}

// Traces one sample of each of the wave's paths (set up with their camera
// rays, all active) to its end: vertex by vertex, each depth's rays through
// one Embree stream (camera rays as coherent packets) and its shadow rays
// through another. A path's light is summed in the order the vertices find
// it, as a recursive tracer would.
void traceWave(const PtFrameData& frame, int maxBounces, PtWaveBuffers& wave, TraceCounters& counters) {
  const EmbreeScene& scene = *frame.scene;
  const CutOutTest* cutOuts = frame.cutOuts();
  for (int depth = 0; !wave.active.empty(); ++depth) {
    const size_t count = wave.active.size();
    wave.rays.resize(count);
    wave.hits.resize(count);
    wave.found.resize(count);
    for (size_t k = 0; k < count; ++k) wave.rays[k] = wave.paths[wave.active[k]].ray;
    scene.intersectMany(wave.rays.data(), count, depth == 0, cutOuts, wave.hits.data(), wave.found.data());
    counters.rays += count;
    for (const PtRay& r : wave.rays) counters.record(r, depth == 0 ? TracedRayKind::Camera : TracedRayKind::Bounce);
    wave.shadowRays.clear();
    wave.pending.clear();
    wave.next.clear();
    for (size_t k = 0; k < count; ++k) {
      const uint32_t p = wave.active[k];
      if (shadeVertex(frame, maxBounces, depth, wave.paths[p], p, wave.found[k] ? &wave.hits[k] : nullptr,
                      wave.samplers[p], wave))
        wave.next.push_back(p);
    }
    const size_t shadows = wave.shadowRays.size();
    if (shadows > 0) {
      wave.occluded.resize(shadows);
      scene.occludedMany(wave.shadowRays.data(), shadows, false, cutOuts, wave.occluded.data());
      counters.rays += shadows;
      for (const PtRay& r : wave.shadowRays) counters.record(r, TracedRayKind::Shadow);
      for (size_t j = 0; j < shadows; ++j)
        if (!wave.occluded[j] && !frame.lights.blocks(wave.shadowRays[j], wave.pending[j].light))
          wave.paths[wave.pending[j].path].radiance += wave.pending[j].contribution;
    }
    std::swap(wave.active, wave.next);
  }
}

// The label planes of one pixel, from the hit of the ray through its centre.
void writeLabels(const PtFrameData& frame, const PtRay& ray, const SurfaceHit& hit, const Vec3f& eye, size_t pixel,
                 PathTracedFrame& out) {
  const SurfaceGeometry g = frame.scene->geometry(hit);
  const ShadedSurface surface = shadeSurface(frame.material(hit.instance, g.part), g, -ray.direction);
  for (int c = 0; c < 3; ++c) {
    out.albedo[3 * pixel + size_t(c)] = surface.albedo[c];
    out.normal[3 * pixel + size_t(c)] = surface.normal[c];
  }
  out.depth[pixel] = (g.position - eye).norm();
  out.instance[pixel] = frame.instanceIds[hit.instance];
}

// Runs work(tile) for every tile index on `threads` threads, each taking
// the next index from a shared counter. Which thread does a tile changes
// nothing: tiles write only their own pixels.
template <typename Work>
void forEachTile(int tileCount, int threads, Work&& work) {
  std::atomic<int> next{0};
  std::exception_ptr failure;
  std::atomic<bool> failed{false};
  auto run = [&](int thread) {
    try {
      for (int tile = next++; tile < tileCount && !failed; tile = next++) work(thread, tile);
    } catch (...) {
      if (!failed.exchange(true)) failure = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(run, t);
  run(0);
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

void checkSize(const RenderList& list, size_t cameraIndex, int width, int height) {
  if (cameraIndex >= list.cameras.size())
    throw std::invalid_argument("path tracer: camera " + std::to_string(cameraIndex) + " of " +
                                std::to_string(list.cameras.size()));
  if (width < 1 || height < 1) throw std::invalid_argument("path tracer: the image size must be at least 1 x 1");
}

}  // namespace

void PathTracer::render(const RenderList& list, size_t cameraIndex, int width, int height, uint64_t frameSeed,
                        PathTracedFrame& out) {
  checkSize(list, cameraIndex, width, height);
  const auto setupStart = std::chrono::steady_clock::now();
  PtFrameData frame;
  prepare(list, frame);
  const CameraRays camera(list.cameras[cameraIndex], width, height);
  const Vec3f eye = camera.eye();
  const size_t pixels = size_t(width) * size_t(height);
  out.width = width;
  out.height = height;
  out.radiance.assign(3 * pixels, 0.0f);
  out.albedo.assign(3 * pixels, 0.0f);
  out.normal.assign(3 * pixels, 0.0f);
  out.depth.assign(pixels, kInf);
  out.instance.assign(pixels, 0u);
  out.variance.assign(pixels, 0.0f);

  const int tilesX = (width + kTileSize - 1) / kTileSize, tilesY = (height + kTileSize - 1) / kTileSize;
  const int threads = std::min(settings_.threads, tilesX * tilesY);
  std::vector<TraceCounters> counters(static_cast<size_t>(threads));
  if (rayLog_) {
    rayLog_->perThread.assign(size_t(threads), {});
    for (int t = 0; t < threads; ++t) counters[size_t(t)].log = &rayLog_->perThread[size_t(t)];
  }
  const auto traceStart = std::chrono::steady_clock::now();
  while (waves_.size() < size_t(threads)) waves_.push_back(std::make_unique<PtWaveBuffers>());
  forEachTile(tilesX * tilesY, threads, [&](int thread, int tile) {
    TraceCounters& count = counters[size_t(thread)];
    PtWaveBuffers& wave = *waves_[size_t(thread)];
    const int x0 = (tile % tilesX) * kTileSize, y0 = (tile / tilesX) * kTileSize;
    const int x1 = std::min(x0 + kTileSize, width), y1 = std::min(y0 + kTileSize, height);
    const int tileWidth = x1 - x0;
    const size_t n = size_t(tileWidth) * size_t(y1 - y0);
    auto pixelOf = [&](size_t i) {
      return size_t(y0 + int(i) / tileWidth) * size_t(width) + size_t(x0 + int(i) % tileWidth);
    };
    // The sampler's tiles are 2^tileBits pixels a side, aligned, and so are these (a power of two): one holds
    // this whole tile unless the sample count leaves the Morton code too few bits (over 2^24 samples).
    const SampleLayout layout{uint32_t(settings_.samples)};
    const int samplerTileSide = 1 << layout.tileBits, samplerTilesAcross = std::max(1, kTileSize / samplerTileSide);
    wave.samplerTiles.resize(size_t(samplerTilesAcross * samplerTilesAcross));
    auto samplerTileOf = [&](int x, int y) -> SamplerTile& {
      return wave.samplerTiles[size_t(((y - y0) >> layout.tileBits) * samplerTilesAcross + ((x - x0) >> layout.tileBits))];
    };
    for (int y = y0; y < y0 + kTileSize; y += samplerTileSide)
      for (int x = x0; x < x0 + kTileSize; x += samplerTileSide)
        samplerTileOf(x, y).reset(frameSeed, uint32_t(settings_.samples), uint32_t(x), uint32_t(y));
    wave.samplers.clear();
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) wave.samplers.emplace_back(samplerTileOf(x, y), uint32_t(x), uint32_t(y));
    wave.sums.assign(n, {0.0, 0.0, 0.0, 0.0});
    wave.paths.resize(n);
    // Sample by sample: a pixel's samples are summed in their order.
    for (int s = 0; s < settings_.samples; ++s) {
      wave.active.clear();
      for (size_t i = 0; i < n; ++i) {
        PixelSampler& sampler = wave.samplers[i];
        sampler.startSample(uint32_t(s));
        const Vec2f jitter = sampler.next2D();
        wave.paths[i].start(camera.ray(x0 + int(i) % tileWidth + jitter.x(), y0 + int(i) / tileWidth + jitter.y()));
        wave.active.push_back(uint32_t(i));
      }
      traceWave(frame, settings_.maxBounces, wave, count);
      for (size_t i = 0; i < n; ++i) {
        const Vec3f& L = wave.paths[i].radiance;
        if (!L.allFinite()) {
          ++count.dropped;
          continue;
        }
        std::array<double, 4>& sum = wave.sums[i];
        for (int c = 0; c < 3; ++c) sum[size_t(c)] += L[c];
        const double l = 0.2126 * L[0] + 0.7152 * L[1] + 0.0722 * L[2];
        sum[3] += l * l;
      }
    }
    const double samples = settings_.samples;
    for (size_t i = 0; i < n; ++i) {
      const size_t pixel = pixelOf(i);
      const std::array<double, 4>& sum = wave.sums[i];
      for (int c = 0; c < 3; ++c) out.radiance[3 * pixel + size_t(c)] = float(sum[size_t(c)] / samples);
      const double mean = (0.2126 * sum[0] + 0.7152 * sum[1] + 0.0722 * sum[2]) / samples;
      out.variance[pixel] = samples > 1 ? float(std::max(0.0, sum[3] / samples - mean * mean) / (samples - 1)) : 0.0f;
    }
    // The labels: every pixel's centre ray, one coherent stream.
    wave.rays.resize(n);
    wave.hits.resize(n);
    wave.found.resize(n);
    for (size_t i = 0; i < n; ++i)
      wave.rays[i] = camera.ray(x0 + int(i) % tileWidth + 0.5, y0 + int(i) / tileWidth + 0.5);
    frame.scene->intersectMany(wave.rays.data(), n, true, frame.cutOuts(), wave.hits.data(), wave.found.data());
    for (size_t i = 0; i < n; ++i) {
      count.record(wave.rays[i], TracedRayKind::Camera);
      if (wave.found[i]) writeLabels(frame, wave.rays[i], wave.hits[i], eye, pixelOf(i), out);
    }
    count.cameraRays += n * (uint64_t(settings_.samples) + 1);
    count.rays += n;
  });
  const auto traceEnd = std::chrono::steady_clock::now();
  stats_ = PathTraceStats{};
  for (const TraceCounters& c : counters) {
    stats_.rays += c.rays;
    stats_.cameraRays += c.cameraRays;
    stats_.droppedSamples += c.dropped;
  }
  stats_.samples = uint64_t(pixels) * uint64_t(settings_.samples);
  stats_.seconds = std::chrono::duration<double>(traceEnd - traceStart).count();
  stats_.setupSeconds = std::chrono::duration<double>(traceStart - setupStart).count();
  stats_.threads = threads;
}

double PathTracer::primaryRayRate(const RenderList& list, size_t cameraIndex, int width, int height, int repeats) {
  checkSize(list, cameraIndex, width, height);
  PtFrameData frame;
  prepare(list, frame);
  const CameraRays camera(list.cameras[cameraIndex], width, height);
  const int tilesX = (width + kTileSize - 1) / kTileSize, tilesY = (height + kTileSize - 1) / kTileSize;
  const int threads = std::min(settings_.threads, tilesX * tilesY);
  std::vector<uint64_t> hits(static_cast<size_t>(threads), 0);  // keeps the loop from being optimised away
  const auto start = std::chrono::steady_clock::now();
  for (int r = 0; r < std::max(repeats, 1); ++r)
    forEachTile(tilesX * tilesY, threads, [&](int thread, int tile) {
      const int x0 = (tile % tilesX) * kTileSize, y0 = (tile / tilesX) * kTileSize;
      for (int y = y0; y < std::min(y0 + kTileSize, height); ++y)
        for (int x = x0; x < std::min(x0 + kTileSize, width); ++x) {
          SurfaceHit hit;
          hits[size_t(thread)] += frame.scene->intersect(camera.ray(x + 0.5, y + 0.5), frame.cutOuts(), hit);
        }
    });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  uint64_t total = 0;
  for (uint64_t h : hits) total += h;
  (void)total;
  return double(std::max(repeats, 1)) * double(width) * double(height) / seconds;
}

double PathTracer::replayRate(const RenderList& list, const RayLog& log, bool streams, int repeats) {
  PtFrameData frame;
  prepare(list, frame);
  const EmbreeScene& scene = *frame.scene;
  const CutOutTest* cutOuts = frame.cutOuts();
  // Streams: each thread's rays in chunks of 1,024, each chunk's rays
  // grouped by kind (camera, bounce, shadow), as a wavefront tracer would
  // cast them; arranged before the clock starts.
  constexpr size_t kChunk = 1024;
  struct Run {
    size_t first, count;
    TracedRayKind kind;
  };
  const size_t threads = log.perThread.size();
  std::vector<std::vector<PtRay>> rays(threads);
  std::vector<std::vector<Run>> runs(threads);
  size_t total = 0;
  for (size_t t = 0; t < threads; ++t) {
    const std::vector<TracedRay>& in = log.perThread[t];
    total += in.size();
    for (size_t first = 0; first < in.size(); first += kChunk) {
      const size_t end = std::min(in.size(), first + kChunk);
      for (TracedRayKind kind : {TracedRayKind::Camera, TracedRayKind::Bounce, TracedRayKind::Shadow}) {
        const size_t start = rays[t].size();
        for (size_t i = first; i < end; ++i)
          if (in[i].kind == kind || !streams) rays[t].push_back(in[i].ray);
        if (!streams) {
          for (size_t i = first; i < end; ++i) runs[t].push_back(Run{start + (i - first), 1, in[i].kind});
          break;
        }
        if (rays[t].size() > start) runs[t].push_back(Run{start, rays[t].size() - start, kind});
      }
    }
  }
  std::vector<std::vector<SurfaceHit>> hits(threads, std::vector<SurfaceHit>(kChunk));
  std::vector<std::vector<uint8_t>> found(threads, std::vector<uint8_t>(kChunk));
  std::vector<uint64_t> hitCount(threads, 0);  // keeps the casting from being optimised away
  const auto start = std::chrono::steady_clock::now();
  for (int r = 0; r < std::max(repeats, 1); ++r)
    forEachTile(int(threads), int(threads), [&](int, int t) {
      const std::vector<PtRay>& in = rays[size_t(t)];
      SurfaceHit* hit = hits[size_t(t)].data();
      uint8_t* yes = found[size_t(t)].data();
      uint64_t& count = hitCount[size_t(t)];
      for (const Run& run : runs[size_t(t)]) {
        const PtRay* first = in.data() + run.first;
        if (!streams) {
          count += run.kind == TracedRayKind::Shadow ? scene.occluded(*first, cutOuts)
                                                      : scene.intersect(*first, cutOuts, *hit);
          continue;
        }
        if (run.kind == TracedRayKind::Shadow) scene.occludedMany(first, run.count, false, cutOuts, yes);
        else scene.intersectMany(first, run.count, run.kind == TracedRayKind::Camera, cutOuts, hit, yes);
        count += yes[0];
      }
    });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return double(std::max(repeats, 1)) * double(total) / seconds;
}

void toneMap(const PathTracedFrame& frame, float exposureScale, uint8_t* rgba) {
  const size_t pixels = size_t(frame.width) * size_t(frame.height);
  for (size_t p = 0; p < pixels; ++p) {
    for (int c = 0; c < 3; ++c) {
      // The rasterizer's displayColor(): the curve, sRGB, then GL's
      // rounding to 8 bits.
      const float mapped = 1.0f - std::exp(-frame.radiance[3 * p + size_t(c)] * exposureScale);
      const float srgb = mapped <= 0.0031308f ? mapped * 12.92f : 1.055f * std::pow(mapped, 1.0f / 2.4f) - 0.055f;
      const float clamped = std::isnan(srgb) ? 0.0f : std::clamp(srgb, 0.0f, 1.0f);
      rgba[4 * p + size_t(c)] = uint8_t(std::lround(clamped * 255.0f));
    }
    rgba[4 * p + 3] = 255;
  }
}

}  // namespace sdg
