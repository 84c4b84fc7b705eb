#include "render/pathtrace/gpu/gpu_path_tracer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <vector>

#include "core/diagnostics.h"
#include "render/camera_math.h"
#include "render/pathtrace/gpu/gl_compute.h"
#include "render/pathtrace/gpu/gpu_scene.h"
#include "render/pathtrace/sampler.h"

// The kernel's parts, compiled in (lib/CMakeLists.txt's sdg_embed).
extern const char kPtCommonGlsl[];
extern const char kPtBsdfGlsl[];
extern const char kPtSceneGlsl[];
extern const char kPtLightsGlsl[];
extern const char kPtTraceGlsl[];
extern const char kPtDenoiseGlsl[];
extern const char kPtDisplayGlsl[];

namespace sdg {
namespace {

// The tracing kernel's work group size is pt_common.glsl's (asked of the
// compiled program, so the GLSL alone decides it): 8 x 4, one 32-wide warp
// per group, traced 28-31 % faster than 8 x 8 on an H100 (docs/performance.md).
constexpr int kDenoiseGroup = 8;  // pt_denoise.glsl's local size, both axes
// Samples per dispatch: about 4 million paths (16 samples of 512 x 512
// pixels, about 7 ms on an H100), so no dispatch runs long enough for a
// display driver's watchdog to call the device hung. Each dispatch ends with
// the GPU draining (its last warps run alone), so fewer are faster when the
// tracer has the GPU alone (the demo at 64 samples: 28.4 ms a frame with 1
// million paths a dispatch, 26.3 with 4, 25.3 with 16); but in a run the
// rasterizer's label passes share the GPU and wait for the dispatch under
// way: there 4 million did best (120 frames of the demo at 64 samples:
// render 4.25 s, against 4.45 s with 1 million and 4.77 s with 16). Any
// split gives the same sums (each pixel adds its samples in order).
constexpr int64_t kPathsPerDispatch = 1 << 22;
// Mesa's llvmpipe ends a shader invocation's loops after 65,535 iterations
// in all (a guard against endless loops), silently: a pixel's later samples
// would be lost (32 x 32 pixels of the Cornell box at 1,024 samples, all in
// one dispatch, kept about a quarter of them). A path vertex takes a few
// dozen iterations there (each traversal step is one), so a software device
// gets at most 36 vertices' worth of samples a dispatch: 4 samples at the
// default 8 bounces, 1 at 32; a wide margin, for about 20 % more time.
constexpr int kSoftwareVerticesPerDispatch = 36;

enum Binding : GLuint {
  kParams = 0, kFilm, kNodes, kTopNodes, kTriangles, kVertices, kIndices, kMeshes, kInstances, kMaterials,
  kTextureTable, kTexels, kLights, kBindingCount
};
constexpr GLuint kDenoiseWork = 2;  // the denoise kernel's binding of `denoiseWork`
constexpr GLuint kDisplayBinding = 13;  // pt_display.glsl's `display`
constexpr int kDisplayGroup = 8;  // pt_display.glsl's local size, both axes

// SDG_GPU_KERNEL_DIR=DIR: the kernels' GLSL read from DIR's pt_*.glsl
// instead of the compiled-in copies, so kernel variants can be timed on a
// GPU machine without a build there (for kernel development only).
std::string kernelSource(const char* compiledIn, const char* name) {
  const char* dir = std::getenv("SDG_GPU_KERNEL_DIR");
  if (!dir || !*dir) return compiledIn;
  std::ifstream in(std::string(dir) + "/" + name, std::ios::binary);
  if (!in) throw RunError(std::string("SDG_GPU_KERNEL_DIR: cannot read ") + dir + "/" + name);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// pt_common.glsl's switch for each GpuKernelFeature.
struct FeatureSwitch {
  const char* name;
  GpuKernelFeature bit;
};
constexpr FeatureSwitch kFeatureSwitches[] = {
    {"SDG_DOME_MAPS", kGpuDomeMaps},           {"SDG_OPACITY", kGpuOpacity},
    {"SDG_NORMAL_MAPS", kGpuNormalMaps},       {"SDG_TRIPLANAR", kGpuTriplanar},
    {"SDG_LOBE_MULTIPLIERS", kGpuLobeMultipliers}, {"SDG_SPHERE_LIGHTS", kGpuSphereLights},
    {"SDG_SHAPE_LIGHTS", kGpuShapeLights},     {"SDG_DISTANT_LIGHTS", kGpuDistantLights},
    {"SDG_DOME_LIGHTS", kGpuDomeLights},       {"SDG_BASE_COLOR_MAPS", kGpuBaseColorMaps},
    {"SDG_SURFACE_MAPS", kGpuSurfaceMaps},     {"SDG_VERTEX_COLORS", kGpuVertexColors},
};
constexpr uint32_t switchedFeatures() {
  uint32_t all = 0;
  for (const FeatureSwitch& f : kFeatureSwitches) all |= f.bit;
  return all;
}
static_assert(switchedFeatures() == kGpuAllFeatures, "every GpuKernelFeature has its switch");

// The denoise and display kernels' uniforms, by index into the names
// below: their locations are looked up once, when the program is built,
// not by name in every pass of every frame.
enum DenoiseUniform { kDenoiseWidth, kDenoiseHeight, kDenoiseSamples, kUseVariance, kSigmaColor, kSigmaNormal,
                      kSigmaDepth, kPass, kIteration, kSource };
constexpr const char* kDenoiseUniformNames[] = {"width",       "height",     "samples", "useVariance",
                                                "sigmaColor",  "sigmaNormal", "sigmaDepth", "pass_",
                                                "iteration",   "source"};
enum DisplayUniform { kDisplayWidth, kDisplayHeight, kWithRadiance, kRadianceDivisor, kExposureScale };
constexpr const char* kDisplayUniformNames[] = {"width", "height", "withRadiance", "radianceDivisor", "exposureScale"};
static_assert(std::size(kDenoiseUniformNames) == kSource + 1 && std::size(kDisplayUniformNames) == kExposureScale + 1,
              "one name per uniform");

template <size_t N>
std::array<GLint, N> uniformLocations(const GlComputeApi& g, GLuint program, const char* const (&names)[N]) {
  std::array<GLint, N> at{};
  for (size_t k = 0; k < N; ++k) at[k] = g.glGetUniformLocation(program, names[k]);
  return at;
}

// SDG_GPU_TIMING=1: each frame's stages on stderr (GL timestamps), for profiling.
bool timingRequested() {
  const char* v = std::getenv("SDG_GPU_TIMING");
  return v && *v && std::string(v) != "0";
}

// pt_common.glsl's Params header (std430), before the float tables.
struct ParamsHeader {
  float camNear0[4], camNearX[4], camNearY[4], camFar0[4], camFarX[4], camFarY[4], eye[4];
  int32_t size[4];
  int32_t counts[4];
  uint32_t seed[4];
  int32_t dome[4];
  int32_t domeTables[4];
  uint32_t sampling[4];
};
static_assert(sizeof(ParamsHeader) == 208, "the kernel's Params header is 208 bytes");

struct FilmPixel {  // pt_common.glsl's FilmPixel
  float sum[4], albedo[4], normalDepth[4];
  uint32_t rays[4];
};
static_assert(sizeof(FilmPixel) == 64, "the kernel's film pixel is 64 bytes");

void put(float* out, const Vec3d& v) {
  for (int k = 0; k < 3; ++k) out[k] = float(v[k]);
  out[3] = 0.0f;
}

// The CPU tracer's camera rays (path_tracer.cpp's CameraRays): the points
// on the near and far planes through image point (px, py). Both are affine
// in (px, py) (the projection's w is constant over each plane), so the
// kernel gets them as a point and two steps per pixel, worked out here in
// double precision.
void cameraPlanes(const RenderCamera& camera, int width, int height, ParamsHeader& p) {
  const Matrix4d cameraFromClip = projectionMatrix(camera, width, height).inverse();
  const Eigen::Matrix3d rotation = camera.worldFromCamera.block<3, 3>(0, 0);
  const Vec3d eye = camera.worldFromCamera.block<3, 1>(0, 3);
  auto at = [&](double px, double py, double z) {
    const double x = 2.0 * px / width - 1.0, y = 1.0 - 2.0 * py / height;
    const Eigen::Vector4d h = cameraFromClip * Eigen::Vector4d(x, y, z, 1.0);
    return Vec3d(h.head<3>() / h.w());
  };
  const Vec3d n0 = at(0, 0, -1), nx = at(1, 0, -1) - n0, ny = at(0, 1, -1) - n0;
  const Vec3d f0 = at(0, 0, 1), fx = at(1, 0, 1) - f0, fy = at(0, 1, 1) - f0;
  put(p.camNear0, rotation * n0 + eye);
  put(p.camNearX, rotation * nx);
  put(p.camNearY, rotation * ny);
  put(p.camFar0, rotation * f0 + eye);
  put(p.camFarX, rotation * fx);
  put(p.camFarY, rotation * fy);
  put(p.eye, eye);
}

}  // namespace

struct GpuPathTracer::Impl {
  Impl(const AssetResolver& assets, const PathTraceSettings& s)
      : settings(s), context(createGlComputeContext(s.gpu)), scene(assets) {}

  PathTraceSettings settings;
  std::unique_ptr<GlComputeContext> context;
  GpuSceneData scene;
  // The tracing kernel compiled per set of stage features (gpu_scene.h's
  // GpuKernelFeature): each frame runs the one for its own stage's.
  struct TraceProgram {
    GLuint id = 0;
    GLint group[3] = {8, 4, 1};  // the program's local size
  };
  std::map<uint32_t, TraceProgram> programs;
  bool everyFeature = false;  // setEveryKernelFeature(): one kernel with all of them
  std::array<GLuint, kBindingCount> buffers{};
  std::array<size_t, kBindingCount> capacity{};
  std::vector<FilmPixel> film;  // the read-back's copy where there is no pinned buffer
  // The read-back's pinned host copy of the film (GL 4.4), mapped for good:
  // the device copies into it at bus speed, where glGetBufferSubData into
  // pageable memory took 4-5 ms a 512 x 512 frame on an H100.
  GLuint pinned = 0;
  size_t pinnedBytes = 0;
  const FilmPixel* pinnedFilm = nullptr;
  PathTraceStats stats;
  int samplesPerDispatch = 0;
  std::optional<DenoiseSettings> denoise;
  GLuint denoiseProgram = 0;
  std::array<GLint, std::size(kDenoiseUniformNames)> denoiseUniforms{};
  GLuint denoiseWork = 0;  // five vec4 planes (pt_denoise.glsl); never read back
  bool denoiseWithVariance = false;
  size_t denoiseCapacity = 0;
  // The display kernel (pt_display.glsl) and, per queued frame, its
  // output on the device and its pinned, persistently mapped host copy.
  GLuint displayProgram = 0;
  std::array<GLint, std::size(kDisplayUniformNames)> displayUniforms{};
  struct DisplaySlot {
    GLuint device = 0, pinned = 0;
    size_t bytes = 0;
    const uint32_t* host = nullptr;
    GLsync done = nullptr;
    int width = 0, height = 0;
    bool radiance = false, queued = false;
  };
  std::array<DisplaySlot, 2> slots{};
  std::chrono::steady_clock::time_point lastTraceStart;  // submit()'s, for stats
  bool timing = timingRequested();
  std::array<GLuint, 3> timestamps{};  // before tracing, after tracing, after denoising

  const GlComputeApi& gl() const { return context->gl(); }

  void checkMemory(const char* what) {
    const GLenum error = gl().glGetError();
    if (error == GL_OUT_OF_MEMORY)
      throw GpuUnavailable(std::string("GPU path tracer: out of GPU memory while uploading ") + what);
    if (error != GL_NO_ERROR)
      throw RunError("GPU path tracer: OpenGL error " + std::to_string(error) + " while uploading " + what);
  }

  // Replaces the buffer's contents from `offset` on; grows it (keeping
  // nothing) when they do not fit, so callers that grow upload everything.
  void upload(Binding b, const void* data, size_t bytes, size_t offset = 0, size_t reserve = 0) {
    const GlComputeApi& g = gl();
    g.glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[b]);
    if (offset + bytes > capacity[b] || capacity[b] == 0) {
      const size_t size = std::max<size_t>({offset + bytes, reserve, 16});
      g.glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(size), nullptr, GL_DYNAMIC_DRAW);
      capacity[b] = size;
    }
    if (bytes > 0) g.glBufferSubData(GL_SHADER_STORAGE_BUFFER, GLintptr(offset), GLsizeiptr(bytes), data);
    checkMemory("the scene");
  }

  // Compiles and links one kernel; a failure is a bug, reported with the driver's log.
  GLuint build(const char* const* parts, size_t count, const char* what) {
    const GlComputeApi& g = gl();
    const GLuint shader = g.glCreateShader(GL_COMPUTE_SHADER);
    g.glShaderSource(shader, GLsizei(count), parts, nullptr);
    g.glCompileShader(shader);
    GLint ok = 0;
    g.glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    auto log = [&](bool ofShader, GLuint id) {
      GLint length = 0;
      (ofShader ? g.glGetShaderiv : g.glGetProgramiv)(id, GL_INFO_LOG_LENGTH, &length);
      std::string text(size_t(std::max(length, 1)), '\0');
      (ofShader ? g.glGetShaderInfoLog : g.glGetProgramInfoLog)(id, GLsizei(text.size()), nullptr, text.data());
      return std::string(text.c_str());
    };
    if (!ok) {
      const std::string text = log(true, shader);
      g.glDeleteShader(shader);
      throw RunError(std::string("GPU path tracer: the ") + what + " kernel does not compile on " +
                     context->description() + " (a bug in sdgbehave; please report it with this log):\n" + text);
    }
    const GLuint id = g.glCreateProgram();
    g.glAttachShader(id, shader);
    g.glLinkProgram(id);
    g.glDeleteShader(shader);
    g.glGetProgramiv(id, GL_LINK_STATUS, &ok);
    if (!ok)
      throw RunError(std::string("GPU path tracer: the ") + what + " kernel does not link on " +
                     context->description() + " (a bug in sdgbehave; please report it with this log):\n" + log(false, id));
    return id;
  }

  // The kernel with the code of `features` only: their SDG_* switches
  // defined between the #version line and the first part's body.
  const TraceProgram& programFor(uint32_t features) {
    auto found = programs.find(features);
    if (found != programs.end()) return found->second;
    const std::string common = kernelSource(kPtCommonGlsl, "pt_common.glsl");
    const size_t versionEnd = common.find('\n') + 1;
    std::string switches;
    for (const FeatureSwitch& f : kFeatureSwitches)
      switches += std::string("#define ") + f.name + ((features & f.bit) ? " 1\n" : " 0\n");
    const std::string sources[] = {common.substr(0, versionEnd), switches,
                                   common.substr(versionEnd),
                                   kernelSource(kPtBsdfGlsl, "pt_bsdf.glsl"),
                                   kernelSource(kPtSceneGlsl, "pt_scene.glsl"),
                                   kernelSource(kPtLightsGlsl, "pt_lights.glsl"),
                                   kernelSource(kPtTraceGlsl, "pt_trace.glsl")};
    const char* parts[std::size(sources)];
    for (size_t k = 0; k < std::size(sources); ++k) parts[k] = sources[k].c_str();
    TraceProgram program;
    program.id = build(parts, std::size(parts), "path tracing");
    gl().glGetProgramiv(program.id, GL_COMPUTE_WORK_GROUP_SIZE, program.group);
    return programs.emplace(features, program).first->second;
  }

  // The buffers, and the kernel of a stage with none of the optional
  // features, so a kernel that does not compile here fails at once.
  void compile() {
    const GlComputeApi& g = gl();
    programFor(0);
    g.glGenBuffers(GLsizei(buffers.size()), buffers.data());
    // Every block gets a store before the first dispatch, even one a scene leaves empty.
    for (GLuint b = 0; b < kBindingCount; ++b) upload(Binding(b), nullptr, 0);
  }

  // denoiser.cpp's passes on the film, each a dispatch over the image.
  void runDenoiser(int width, int height, int samples, GLuint groupsX, GLuint groupsY) {
    const GlComputeApi& g = gl();
    if (!denoiseProgram) {
      const char* parts[] = {kPtDenoiseGlsl};
      denoiseProgram = build(parts, 1, "denoising");
      denoiseUniforms = uniformLocations(g, denoiseProgram, kDenoiseUniformNames);
      g.glGenBuffers(1, &denoiseWork);
    }
    const size_t pixels = size_t(width) * size_t(height), bytes = 5 * pixels * 4 * sizeof(float);
    g.glBindBuffer(GL_SHADER_STORAGE_BUFFER, denoiseWork);
    if (bytes > denoiseCapacity) {
      g.glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_DRAW);
      checkMemory("the denoiser's planes");
      denoiseCapacity = bytes;
    }
    g.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDenoiseWork, denoiseWork);
    g.glUseProgram(denoiseProgram);
    auto set = [&](DenoiseUniform u, int v) { g.glUniform1i(denoiseUniforms[u], v); };
    auto setF = [&](DenoiseUniform u, float v) { g.glUniform1f(denoiseUniforms[u], v); };
    set(kDenoiseWidth, width);
    set(kDenoiseHeight, height);
    set(kDenoiseSamples, samples);
    set(kUseVariance, denoiseWithVariance ? 1 : 0);
    setF(kSigmaNormal, denoise->sigmaNormal);
    setF(kSigmaDepth, denoise->sigmaDepth);
    auto pass = [&](int which, int iteration, int source) {
      set(kPass, which);
      set(kIteration, iteration);
      set(kSource, source);
      g.glDispatchCompute(groupsX, groupsY, 1);
      g.glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    };
    pass(0, 0, 0);
    pass(1, 0, 0);
    int source = 0;
    for (int i = 0; i < denoise->iterations; ++i, source = 1 - source) {
      setF(kSigmaColor, denoisePassSigmaColor(*denoise, i, denoiseWithVariance));
      pass(4, i, source);  // the weight sums W
      pass(2, i, source);  // the filter, which reads its neighbours' W
    }
    pass(3, 0, source);
    // The tracer's bindings again for the next frame (binding 2 is its node buffer).
    g.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kNodes, buffers[kNodes]);
  }

  // The film as the kernels left it, on the host: through the pinned
  // buffer where GL 4.4 offers one, else read into `film`.
  const FilmPixel* readFilm(size_t pixels) {
    const GlComputeApi& g = gl();
    const size_t bytes = pixels * sizeof(FilmPixel);
    if (!g.glBufferStorage) {
      film.resize(pixels);
      g.glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[kFilm]);
      g.glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(bytes), film.data());
      return film.data();
    }
    if (bytes > pinnedBytes) {  // immutable storage: a bigger film needs a new buffer
      if (pinned) g.glDeleteBuffers(1, &pinned);
      g.glGenBuffers(1, &pinned);
      g.glBindBuffer(GL_COPY_WRITE_BUFFER, pinned);
      const GLbitfield flags = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
      g.glBufferStorage(GL_COPY_WRITE_BUFFER, GLsizeiptr(bytes), nullptr, flags | GL_CLIENT_STORAGE_BIT);
      checkMemory("the film's read-back buffer");
      pinnedFilm = static_cast<const FilmPixel*>(g.glMapBufferRange(GL_COPY_WRITE_BUFFER, 0, GLsizeiptr(bytes), flags));
      if (!pinnedFilm) throw RunError("GPU path tracer: cannot map the film's read-back buffer");
      pinnedBytes = bytes;
    }
    g.glBindBuffer(GL_COPY_READ_BUFFER, buffers[kFilm]);
    g.glBindBuffer(GL_COPY_WRITE_BUFFER, pinned);
    g.glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, GLsizeiptr(bytes));
    g.glMemoryBarrier(GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
    GLsync done = g.glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    wait(done);
    return pinnedFilm;
  }

  void uploadScene(const ParamsHeader& header) {
    GpuSceneData& s = scene;
    if (s.meshesChanged) {
      upload(kNodes, s.meshNodes.data(), s.meshNodes.size() * sizeof(GpuBvhNode));
      upload(kTriangles, s.triangles.data(), s.triangles.size() * sizeof(float));
      upload(kVertices, s.vertices.data(), s.vertices.size() * sizeof(float));
      upload(kIndices, s.indices.data(), s.indices.size() * sizeof(uint32_t));
      upload(kMeshes, s.meshes.data(), s.meshes.size() * sizeof(GpuMeshRecord));
      s.meshesChanged = false;
    }
    if (s.instancesChanged) {
      upload(kTopNodes, s.topNodes.data(), s.topNodes.size() * sizeof(GpuBvhNode));
      upload(kInstances, s.instances.data(), s.instances.size() * sizeof(GpuInstanceRecord));
      s.instancesChanged = false;
    }
    if (s.texelsChanged) {
      const size_t textureBytes = s.texels.size() * 4, domeBytes = s.domeTexels.size() * 4;
      capacity[kTexels] = 0;  // reallocated: both parts are written again
      upload(kTexels, s.texels.data(), textureBytes, 0, textureBytes + domeBytes);
      upload(kTexels, s.domeTexels.data(), domeBytes, textureBytes);
      upload(kTextureTable, s.textureTable.data(), s.textureTable.size() * sizeof(int32_t));
      s.texelsChanged = false;
    }
    upload(kMaterials, s.materials.data(), s.materials.size() * sizeof(GpuMaterialRecord));
    upload(kLights, s.lights.data(), s.lights.size() * sizeof(GpuLightRecord));
    // Params: the header and the pick cdf every frame; the tables before it only when they changed.
    const size_t pickOffset = sizeof(ParamsHeader) + size_t(s.dome[3]) * sizeof(float);
    const size_t total = sizeof(ParamsHeader) + s.tables.size() * sizeof(float);
    if (s.tablesChanged || total > capacity[kParams]) {
      capacity[kParams] = 0;
      upload(kParams, &header, sizeof header, 0, total);
      upload(kParams, s.tables.data(), s.tables.size() * sizeof(float), sizeof(ParamsHeader));
      s.tablesChanged = false;
    } else {
      upload(kParams, &header, sizeof header);
      upload(kParams, s.tables.data() + s.dome[3], (s.tables.size() - size_t(s.dome[3])) * sizeof(float), pickOffset);
    }
  }

  // A frame's GPU work up to a film ready to read: the scene's changes
  // uploaded, the samples traced, the denoiser run. Queued without waiting
  // for the device, so a caller can overlap its own work with it (only
  // SDG_GPU_TIMING waits, to time each stage alone).
  void submit(const RenderList& list, size_t cameraIndex, int width, int height, uint64_t frameSeed) {
    const auto setupStart = std::chrono::steady_clock::now();
    const GlComputeApi& g = gl();
    scene.update(list);
    const int samples = settings.samples;
    ParamsHeader header{};
    cameraPlanes(list.cameras[cameraIndex], width, height, header);
    const int32_t counts[4] = {settings.maxBounces, int32_t(scene.lights.size()), int32_t(scene.instances.size()),
                               scene.anyLobeMultiplier ? 1 : 0};
    std::copy(counts, counts + 4, header.counts);
    header.seed[0] = uint32_t(frameSeed);
    header.seed[1] = uint32_t(frameSeed >> 32);
    header.seed[2] = uint32_t(scene.topRoot);
    std::copy(scene.dome, scene.dome + 4, header.dome);
    std::copy(scene.domeTables, scene.domeTables + 4, header.domeTables);
    header.size[0] = width;
    header.size[1] = height;
    // The frame's samples, not a dispatch's, place each sample in the stream: any split draws the same numbers.
    const SampleLayout layout{uint32_t(samples)};
    header.sampling[0] = uint32_t(samples);
    header.sampling[1] = layout.sampleBits;
    header.sampling[2] = layout.tileBits;
    uploadScene(header);
    const size_t pixels = size_t(width) * size_t(height);
    if (capacity[kFilm] < pixels * sizeof(FilmPixel)) {
      g.glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[kFilm]);
      // A DRAW hint: drivers may keep a READ buffer in host memory, where every kernel access crosses the bus.
      g.glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(pixels * sizeof(FilmPixel)), nullptr, GL_DYNAMIC_DRAW);
      checkMemory("the film");
      capacity[kFilm] = pixels * sizeof(FilmPixel);
    }
    for (GLuint b = 0; b < kBindingCount; ++b) g.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, buffers[b]);
    const TraceProgram& program = programFor(everyFeature ? uint32_t(kGpuAllFeatures) : scene.kernelFeatures);
    g.glUseProgram(program.id);
    if (timing) {
      g.glFinish();
      if (!timestamps[0]) g.glGenQueries(GLsizei(timestamps.size()), timestamps.data());
      g.glQueryCounter(timestamps[0], GL_TIMESTAMP);
    }
    const auto traceStart = std::chrono::steady_clock::now();
    int perDispatch = samplesPerDispatch > 0 ? std::min(samplesPerDispatch, samples)
                                            : int(std::clamp<int64_t>(kPathsPerDispatch / int64_t(pixels), 1, samples));
    if (!context->onGpu())
      perDispatch = std::min(perDispatch, std::max(1, kSoftwareVerticesPerDispatch / (settings.maxBounces + 1)));
    const GLuint groupsX = GLuint((width + program.group[0] - 1) / program.group[0]),
                 groupsY = GLuint((height + program.group[1] - 1) / program.group[1]);
    for (int first = 0; first < samples; first += perDispatch) {
      header.size[2] = first;
      header.size[3] = std::min(perDispatch, samples - first);
      header.seed[3] = first == 0 ? 1u : 0u;  // the first dispatch also writes the label planes and clears the sums
      g.glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[kParams]);
      g.glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof header, &header);
      g.glDispatchCompute(groupsX, groupsY, 1);
      g.glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    }
    if (timing) g.glQueryCounter(timestamps[1], GL_TIMESTAMP);
    if (denoise)
      runDenoiser(width, height, samples, GLuint((width + kDenoiseGroup - 1) / kDenoiseGroup),
                  GLuint((height + kDenoiseGroup - 1) / kDenoiseGroup));
    if (timing) g.glQueryCounter(timestamps[2], GL_TIMESTAMP);
    stats.setupSeconds = std::chrono::duration<double>(traceStart - setupStart).count();
    lastTraceStart = traceStart;
  }

  void checkTraced() {
    const GLenum error = gl().glGetError();
    if (error == GL_OUT_OF_MEMORY) throw GpuUnavailable("GPU path tracer: out of GPU memory while tracing");
    if (error != GL_NO_ERROR) throw RunError("GPU path tracer: OpenGL error " + std::to_string(error) + " while tracing");
  }

  // SDG_GPU_TIMING's line for the frame just read back.
  void printTiming(double readBackMs) {
    const GlComputeApi& g = gl();
    GLuint64 t[3] = {};
    for (size_t k = 0; k < 3; ++k) g.glGetQueryObjectui64v(timestamps[k], GL_QUERY_RESULT, &t[k]);
    std::fprintf(stderr, "sdg gpu timing: setup %.2f ms (cpu), trace %.2f ms (gpu), denoise %.2f ms (gpu), read-back %.2f ms (cpu)\n",
                 stats.setupSeconds * 1e3, double(t[1] - t[0]) * 1e-6, double(t[2] - t[1]) * 1e-6, readBackMs);
  }

  // Tone maps the film on the device into `slot`'s buffer and starts its
  // copy to the slot's pinned host memory, fenced.
  void queueDisplay(DisplaySlot& slot, int width, int height, float exposureScale, bool radiance) {
    const GlComputeApi& g = gl();
    if (!displayProgram) {
      const char* parts[] = {kPtDisplayGlsl};
      displayProgram = build(parts, 1, "display");
      displayUniforms = uniformLocations(g, displayProgram, kDisplayUniformNames);
    }
    const size_t pixels = size_t(width) * size_t(height);
    const size_t bytes = pixels * 4 * (radiance ? 4 : 1);
    if (bytes > slot.bytes) {  // immutable storage: a bigger frame needs new buffers
      if (slot.device) g.glDeleteBuffers(1, &slot.device);
      if (slot.pinned) g.glDeleteBuffers(1, &slot.pinned);
      slot.pinned = 0;
      g.glGenBuffers(1, &slot.device);
      g.glBindBuffer(GL_SHADER_STORAGE_BUFFER, slot.device);
      g.glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_DRAW);
      checkMemory("the frame's display buffer");
      slot.bytes = bytes;
    }
    if (g.glBufferStorage && !slot.pinned) {
      g.glGenBuffers(1, &slot.pinned);
      g.glBindBuffer(GL_COPY_WRITE_BUFFER, slot.pinned);
      const GLbitfield flags = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
      g.glBufferStorage(GL_COPY_WRITE_BUFFER, GLsizeiptr(bytes), nullptr, flags | GL_CLIENT_STORAGE_BIT);
      checkMemory("the frame's read-back buffer");
      slot.host = static_cast<const uint32_t*>(g.glMapBufferRange(GL_COPY_WRITE_BUFFER, 0, GLsizeiptr(bytes), flags));
      if (!slot.host) throw RunError("GPU path tracer: cannot map the frame's read-back buffer");
    }
    g.glUseProgram(displayProgram);
    g.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDisplayBinding, slot.device);
    g.glUniform1i(displayUniforms[kDisplayWidth], width);
    g.glUniform1i(displayUniforms[kDisplayHeight], height);
    g.glUniform1i(displayUniforms[kWithRadiance], radiance ? 1 : 0);
    g.glUniform1f(displayUniforms[kRadianceDivisor], denoise ? 1.0f : float(settings.samples));
    g.glUniform1f(displayUniforms[kExposureScale], exposureScale);
    g.glDispatchCompute(GLuint((width + kDisplayGroup - 1) / kDisplayGroup), GLuint((height + kDisplayGroup - 1) / kDisplayGroup), 1);
    g.glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    slot.width = width;
    slot.height = height;
    slot.radiance = radiance;
    slot.queued = true;
    if (!g.glBufferStorage) return;  // GL 4.3: collectDisplay() reads the device buffer itself
    g.glBindBuffer(GL_COPY_READ_BUFFER, slot.device);
    g.glBindBuffer(GL_COPY_WRITE_BUFFER, slot.pinned);
    g.glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, GLsizeiptr(pixels * 4 * (radiance ? 4 : 1)));
    g.glMemoryBarrier(GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
    if (slot.done) g.glDeleteSync(slot.done);
    slot.done = g.glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    g.glFlush();  // so the device starts now, while the caller works on
  }

  void wait(GLsync& done) {
    const GlComputeApi& g = gl();
    GLenum waited = GL_TIMEOUT_EXPIRED;
    while (waited == GL_TIMEOUT_EXPIRED) waited = g.glClientWaitSync(done, GL_SYNC_FLUSH_COMMANDS_BIT, 1000000000);
    g.glDeleteSync(done);
    done = nullptr;
    if (waited == GL_WAIT_FAILED) throw RunError("GPU path tracer: waiting for the frame failed");
  }
};

GpuPathTracer::GpuPathTracer(const AssetResolver& assets, const PathTraceSettings& settings)
    : impl_(std::make_unique<Impl>(assets, settings)) {
  impl_->settings.samples = std::max(impl_->settings.samples, 1);
  impl_->settings.maxBounces = std::max(impl_->settings.maxBounces, 0);
  impl_->context->run([this] { impl_->compile(); });
}

GpuPathTracer::~GpuPathTracer() {
  if (!impl_ || !impl_->context) return;
  try {
    impl_->context->run([this] {
      const GlComputeApi& g = impl_->gl();
      g.glDeleteBuffers(GLsizei(impl_->buffers.size()), impl_->buffers.data());
      for (const auto& [features, program] : impl_->programs) g.glDeleteProgram(program.id);
      if (impl_->denoiseProgram) g.glDeleteProgram(impl_->denoiseProgram);
      if (impl_->denoiseWork) g.glDeleteBuffers(1, &impl_->denoiseWork);
      if (impl_->pinned) g.glDeleteBuffers(1, &impl_->pinned);
      if (impl_->displayProgram) g.glDeleteProgram(impl_->displayProgram);
      for (Impl::DisplaySlot& slot : impl_->slots) {
        if (slot.done) g.glDeleteSync(slot.done);
        if (slot.device) g.glDeleteBuffers(1, &slot.device);
        if (slot.pinned) g.glDeleteBuffers(1, &slot.pinned);
      }
      if (impl_->timestamps[0]) g.glDeleteQueries(GLsizei(impl_->timestamps.size()), impl_->timestamps.data());
    });
  } catch (...) {  // the context is going away with the tracer; nothing to report
  }
}

const PathTraceStats& GpuPathTracer::stats() const { return impl_->stats; }
void GpuPathTracer::setDenoiser(const std::optional<DenoiseSettings>& settings, bool perPixelVariance) {
  if (settings && (settings->iterations < 0 || settings->iterations > 16))
    throw std::invalid_argument("Denoiser: iterations must be 0 to 16");
  impl_->denoise = settings;
  impl_->denoiseWithVariance = perPixelVariance;
}
void GpuPathTracer::setSamplesPerDispatch(int samples) { impl_->samplesPerDispatch = std::max(samples, 0); }
void GpuPathTracer::setEveryKernelFeature(bool every) { impl_->everyFeature = every; }
uint32_t GpuPathTracer::stageFeatures() const { return impl_->scene.kernelFeatures; }
std::string GpuPathTracer::device() const { return impl_->context->description(); }
bool GpuPathTracer::onGpu() const { return impl_->context->onGpu(); }

namespace {
void checkFrame(const RenderList& list, size_t cameraIndex, int width, int height) {
  if (cameraIndex >= list.cameras.size())
    throw std::invalid_argument("path tracer: camera " + std::to_string(cameraIndex) + " of " +
                                std::to_string(list.cameras.size()));
  if (width < 1 || height < 1) throw std::invalid_argument("path tracer: the image size must be at least 1 x 1");
}
}  // namespace

void GpuPathTracer::render(const RenderList& list, size_t cameraIndex, int width, int height, uint64_t frameSeed,
                           PathTracedFrame& out) {
  checkFrame(list, cameraIndex, width, height);
  Impl& m = *impl_;
  // On the context's thread: the caller's own GL context (the rasterizer's) is left alone.
  m.context->run([&] {
    m.submit(list, cameraIndex, width, height, frameSeed);
    const auto readStart = std::chrono::steady_clock::now();
    const size_t pixels = size_t(width) * size_t(height);
    const FilmPixel* film = m.readFilm(pixels);
    m.checkTraced();
    const auto traceEnd = std::chrono::steady_clock::now();
    if (m.timing) m.printTiming(std::chrono::duration<double, std::milli>(traceEnd - readStart).count());
    const int samples = m.settings.samples;
    out.width = width;
    out.height = height;
    out.radiance.resize(3 * pixels);
    out.albedo.resize(3 * pixels);
    out.normal.resize(3 * pixels);
    out.depth.resize(pixels);
    out.instance.resize(pixels);
    out.variance.assign(pixels, 0.0f);
    PathTraceStats stats;
    for (size_t p = 0; p < pixels; ++p) {
      const FilmPixel& f = film[p];
      for (int c = 0; c < 3; ++c) {
        out.radiance[3 * p + size_t(c)] = m.denoise ? f.sum[c] : f.sum[c] / float(samples);  // denoised: the radiance itself
        out.albedo[3 * p + size_t(c)] = f.albedo[c];
        out.normal[3 * p + size_t(c)] = f.normalDepth[c];
      }
      out.depth[p] = f.normalDepth[3];
      if (!m.denoise && samples > 1) {  // path_tracer.cpp's, from float sums
        const double n = samples;
        const double mean = (0.2126 * f.sum[0] + 0.7152 * f.sum[1] + 0.0722 * f.sum[2]) / n;
        out.variance[p] = float(std::max(0.0, double(f.albedo[3]) / n - mean * mean) / (n - 1));
      }
      out.instance[p] = f.rays[3];
      stats.rays += uint64_t(f.rays[0]) | (uint64_t(f.rays[1]) << 32);
      stats.cameraRays += f.rays[2];
      stats.droppedSamples += uint64_t(f.sum[3]);
    }
    stats.samples = uint64_t(pixels) * uint64_t(samples);
    stats.setupSeconds = m.stats.setupSeconds;
    stats.seconds = std::chrono::duration<double>(traceEnd - m.lastTraceStart).count();
    stats.threads = 0;
    m.stats = stats;
  });
}

void GpuPathTracer::queueDisplay(const RenderList& list, size_t cameraIndex, int width, int height, uint64_t frameSeed,
                                 float exposureScale, bool radiance, int slot) {
  checkFrame(list, cameraIndex, width, height);
  if (slot < 0 || slot >= int(impl_->slots.size())) throw std::invalid_argument("GPU path tracer: no display slot " + std::to_string(slot));
  Impl& m = *impl_;
  m.context->run([&] {
    m.submit(list, cameraIndex, width, height, frameSeed);
    m.queueDisplay(m.slots[size_t(slot)], width, height, exposureScale, radiance);
    m.checkTraced();
  });
}

void GpuPathTracer::collectDisplay(int slot, std::vector<uint8_t>& rgba, std::vector<float>* radiance) {
  if (slot < 0 || slot >= int(impl_->slots.size()) || !impl_->slots[size_t(slot)].queued)
    throw std::logic_error("GPU path tracer: nothing queued in display slot " + std::to_string(slot));
  Impl& m = *impl_;
  Impl::DisplaySlot& s = m.slots[size_t(slot)];
  s.queued = false;
  const size_t pixels = size_t(s.width) * size_t(s.height);
  rgba.resize(4 * pixels);
  if (radiance && s.radiance) radiance->resize(3 * pixels);
  m.context->run([&] {
    const GlComputeApi& g = m.gl();
    const auto readStart = std::chrono::steady_clock::now();
    if (s.done) {
      m.wait(s.done);
    } else {  // GL 4.3: no pinned copy; read the device buffer (waits for it)
      g.glBindBuffer(GL_SHADER_STORAGE_BUFFER, s.device);
      g.glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(4 * pixels), rgba.data());
      if (radiance && s.radiance)
        g.glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, GLintptr(4 * pixels), GLsizeiptr(12 * pixels), radiance->data());
    }
    m.checkTraced();
    if (m.timing) m.printTiming(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - readStart).count());
  });
  if (!s.host || s.pinned == 0) return;
  // The pinned copy is coherent and its fence has passed: read here, off the context's thread.
  std::memcpy(rgba.data(), s.host, 4 * pixels);
  if (radiance && s.radiance) std::memcpy(radiance->data(), s.host + pixels, 3 * pixels * sizeof(float));
}

}  // namespace sdg
