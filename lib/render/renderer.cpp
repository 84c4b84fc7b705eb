#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "assets/image.h"
#include "assets/mipmaps.h"
#include "core/diagnostics.h"
#include "render/camera_math.h"
#include "render/shaders.h"
#include "render/shadow_casters.h"
#include "render/shadow_frusta.h"
#include "stage/xform.h"

namespace sdg {

void FramePasses::resize(int w, int h, const PassSelection& passes) {
  width = w;
  height = h;
  const size_t n = size_t(w) * size_t(h);
  rgba.resize(n * 4);
  if (passes.normals) {
    normals.resize(n * 4);
    distanceToCamera.resize(n);
  }
  if (passes.imagePlane) distanceToImagePlane.resize(n);
  if (passes.ids) instanceIds.resize(n);
}

#define SDG_SCENE_UNIFORMS(X) X(uAmbient) X(uCameraForward) X(uCameraPosition) X(uDome) X(uDomeFromWorld) X(uDomeLod) X(uDomeScale) X(uExposureScale) X(uLightDirection) X(uLightParams) X(uLightPosition) X(uLightRadiance) X(uMetersPerUnit) X(uPartBaseColor) X(uPartSurface) X(uShadowAtlas) X(uShadowMatrix) X(uShadowTexel) X(uTexture) X(uUsePartMaterial) X(uViewProjection) X(uWorldFromClip)

// Uniform locations, looked up once per program instead of per draw (the
// sky program uses a few of the same names; the rest stay -1 for it).
struct Renderer::Uniforms {
#define SDG_UNIFORM_FIELD(name) int name = -1;
  SDG_SCENE_UNIFORMS(SDG_UNIFORM_FIELD)
#undef SDG_UNIFORM_FIELD
};

struct Renderer::GpuMesh {
  uint32_t slot = 0;  // index in meshBySlot_
  unsigned vao = 0;
  unsigned buffers[4] = {0, 0, 0, 0};
  std::vector<MeshPart> parts;
  Eigen::AlignedBox3f bounds;
};

namespace {

unsigned compile(const GlApi& gl, GLenum type, std::initializer_list<const char*> sources) {
  unsigned shader = gl.glCreateShader(type);
  std::vector<const char*> parts(sources);
  gl.glShaderSource(shader, GLsizei(parts.size()), parts.data(), nullptr);
  gl.glCompileShader(shader);
  GLint ok = 0;
  gl.glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096];
    gl.glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    throw RunError(std::string("renderer: shader compilation failed: ") + log);
  }
  return shader;
}

// Vertex shaders are one string; fragment shaders get the shared header,
// `defines` and the common functions first.
unsigned link(const GlApi& gl, const char* vertex, const char* fragmentBody, bool common = true, const char* defines = "") {
  unsigned vs = compile(gl, GL_VERTEX_SHADER, {vertex});
  unsigned fs = common ? compile(gl, GL_FRAGMENT_SHADER,
                                 {shaders::kFragmentHeader, defines, shaders::kCommonFunctions, fragmentBody})
                       : compile(gl, GL_FRAGMENT_SHADER, {fragmentBody});
  unsigned program = gl.glCreateProgram();
  gl.glAttachShader(program, vs);
  gl.glAttachShader(program, fs);
  gl.glLinkProgram(program);
  gl.glDeleteShader(vs);
  gl.glDeleteShader(fs);
  GLint ok = 0;
  gl.glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096];
    gl.glGetProgramInfoLog(program, sizeof log, nullptr, log);
    throw RunError(std::string("renderer: shader linking failed: ") + log);
  }
  return program;
}

Eigen::Matrix4f toFloat(const Matrix4d& m) { return m.cast<float>(); }

void setMatrix(const GlApi& gl, int location, const Matrix4d& m) {
  Eigen::Matrix4f f = toFloat(m);  // Eigen is column-major, as GL expects
  gl.glUniformMatrix4fv(location, 1, GL_FALSE, f.data());
}

// An sRGB texture with its mip chain, sampled trilinear with repeat: how
// every scene texture is stored and sampled.
unsigned makeSrgbTexture(const GlApi& gl, const ImageRgba8& image) {
  unsigned t = 0;
  gl.glGenTextures(1, &t);
  gl.glBindTexture(GL_TEXTURE_2D, t);
  gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  // sRGB storage: sampling returns linear colour for shading.
  gl.glTexImage2D(GL_TEXTURE_2D, 0, GL_SRGB8_ALPHA8, GLsizei(image.width), GLsizei(image.height), 0, GL_RGBA,
                  GL_UNSIGNED_BYTE, image.pixels.data());
  const std::vector<ImageRgba8> levels = srgbMipLevels(image);
  for (size_t i = 0; i < levels.size(); ++i)
    gl.glTexImage2D(GL_TEXTURE_2D, GLint(i + 1), GL_SRGB8_ALPHA8, GLsizei(levels[i].width), GLsizei(levels[i].height),
                    0, GL_RGBA, GL_UNSIGNED_BYTE, levels[i].pixels.data());
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return t;
}

unsigned makeTexture(const GlApi& gl, GLint internalFormat, int w, int h, GLenum format, GLenum type) {
  unsigned t = 0;
  gl.glGenTextures(1, &t);
  gl.glBindTexture(GL_TEXTURE_2D, t);
  gl.glTexImage2D(GL_TEXTURE_2D, 0, internalFormat, w, h, 0, format, type, nullptr);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return t;
}

// Low-discrepancy sub-pixel offsets in [-0.5, 0.5) (Halton bases 2 and 3).
double halton(int index, int base) {
  double f = 1, r = 0;
  for (int i = index; i > 0; i /= base) {
    f /= base;
    r += f * (i % base);
  }
  return r;
}

int lightTypeCode(LightKind kind) {
  switch (kind) {
    case LightKind::Distant: return 0;
    case LightKind::Sphere: return 1;
    case LightKind::Rect: return 2;
    case LightKind::Disk: return 3;
    case LightKind::Cylinder: return 4;
    case LightKind::Dome: return 5;
  }
  return 0;
}

// The scene shader's ADD_LIGHTS line gets one call per light, its type and
// shadow slot as literals.
void appendLightCall(std::string& calls, int index, int type, int shadowSlot) {
  calls += " radiance += lightContribution(";
  calls += std::to_string(index);
  calls += ", ";
  calls += std::to_string(type);
  calls += ", ";
  calls += std::to_string(shadowSlot);
  calls += ", n, v, base, roughness, metallic);";
}

}  // namespace


Renderer::Renderer(GlContext& context, const AssetResolver& assets, const RenderSettings& settings)
    : context_(context), gl_(context.gl()), assets_(assets), settings_(settings) {
  shadowProgram_ = link(gl_, shaders::kShadowVertex, shaders::kShadowFragment, false);
  shadowLightViewProjection_ = gl_.glGetUniformLocation(shadowProgram_, "uLightViewProjection");
  gl_.glGenFramebuffers(1, &framebuffer_);
  gl_.glGenFramebuffers(1, &shadowFramebuffer_);
  skyProgram_ = link(gl_, shaders::kSkyVertex, shaders::kSkyFragment);
  skyUniforms_ = std::make_unique<Uniforms>(uniformsOf(skyProgram_));
  maskProgram_ = link(gl_, shaders::kShadowVertex, shaders::kMaskFragment, false);
  depthProgram_ = link(gl_, shaders::kDepthVertex, shaders::kShadowFragment, false);
  depthViewProjection_ = gl_.glGetUniformLocation(depthProgram_, "uViewProjection");
  maskViewProjection_ = gl_.glGetUniformLocation(maskProgram_, "uLightViewProjection");
  gl_.glGenFramebuffers(1, &maskFramebuffer_);
  gl_.glGenVertexArrays(1, &emptyVao_);
  gl_.glGenBuffers(1, &instanceBuffer_);
  gl_.glGenBuffers(1, &maskInstanceBuffer_);
  gl_.glBindFramebuffer(GL_FRAMEBUFFER, shadowFramebuffer_);
  GLenum none = GL_NONE;
  gl_.glDrawBuffers(1, &none);
  // Bound where a material has no texture (that program never samples it).
  // It has the format, a full mip chain and the sampling of a loaded
  // texture: llvmpipe compiles a shader variant per texture state (a 1 x 1
  // or 2 x 2 texture gets its own), so a warm-up frame that draws the
  // textured programs with it bound compiles what textured frames use.
  whiteTexture_ = makeSrgbTexture(gl_, ImageRgba8{64, 64, std::vector<uint8_t>(64 * 64 * 4, 255)});
}

Renderer::~Renderer() {
  for (ReadSlot& r : readSlots_) {
    gl_.glDeleteBuffers(4, r.buffers);
    if (r.maskBuffer) gl_.glDeleteBuffers(1, &r.maskBuffer);
  }
  gl_.glDeleteBuffers(1, &instanceBuffer_);
  gl_.glDeleteBuffers(1, &maskInstanceBuffer_);
  for (auto& [key, m] : meshes_) {
    gl_.glDeleteVertexArrays(1, &m->vao);
    gl_.glDeleteBuffers(4, m->buffers);
  }
  for (auto& [key, t] : textures_) gl_.glDeleteTextures(1, &t.id);
  unsigned textures[] = {colorTexture_, normalTexture_, planeTexture_, idTexture_, depthTexture_, whiteTexture_};
  gl_.glDeleteTextures(6, textures);
  if (shadowAtlas_) gl_.glDeleteTextures(1, &shadowAtlas_);
  gl_.glDeleteVertexArrays(1, &emptyVao_);
  gl_.glDeleteProgram(skyProgram_);
  gl_.glDeleteProgram(maskProgram_);
  unsigned maskTextures[] = {maskTexture_, maskDepth_};
  gl_.glDeleteTextures(2, maskTextures);
  gl_.glDeleteFramebuffers(1, &maskFramebuffer_);
  gl_.glDeleteFramebuffers(1, &framebuffer_);
  gl_.glDeleteFramebuffers(1, &shadowFramebuffer_);
  for (auto& [lights, p] : scenePrograms_) gl_.glDeleteProgram(p.program);
  gl_.glDeleteProgram(shadowProgram_);
}

const Renderer::GpuMesh& Renderer::mesh(const RenderItem& item) {
  // Lists built by hand (tests, tools) may leave meshId empty.
  const std::string key = item.meshId.empty() ? item.mesh.id() : item.meshId;
  auto it = meshes_.find(key);
  if (it != meshes_.end()) return *it->second;
  MeshData data = meshDataFor(item.mesh, assets_, item.primPath);
  auto m = std::make_unique<GpuMesh>();
  gl_.glGenVertexArrays(1, &m->vao);
  gl_.glBindVertexArray(m->vao);
  gl_.glGenBuffers(4, m->buffers);
  auto upload = [&](unsigned buffer, unsigned location, int components, const void* data_, size_t bytes) {
    gl_.glBindBuffer(GL_ARRAY_BUFFER, buffer);
    gl_.glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(bytes), data_, GL_STATIC_DRAW);
    gl_.glEnableVertexAttribArray(location);
    gl_.glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, 0, nullptr);
  };
  upload(m->buffers[0], 0, 3, data.positions.data(), data.positions.size() * sizeof(Vec3f));
  upload(m->buffers[1], 1, 3, data.normals.data(), data.normals.size() * sizeof(Vec3f));
  upload(m->buffers[2], 2, 2, data.uvs.data(), data.uvs.size() * sizeof(Eigen::Vector2f));
  gl_.glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->buffers[3]);
  gl_.glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(data.indices.size() * sizeof(uint32_t)), data.indices.data(),
                   GL_STATIC_DRAW);
  // Attributes 3-13 come from the instance buffer, one record per instance;
  // bindBatch() points them at a batch's records.
  for (unsigned location = 3; location <= 13; ++location) {
    gl_.glEnableVertexAttribArray(location);
    gl_.glVertexAttribDivisor(location, 1);
  }
  gl_.glBindVertexArray(0);
  m->parts = std::move(data.parts);
  m->bounds = data.bounds;
  m->slot = uint32_t(meshBySlot_.size());
  meshBySlot_.push_back(m.get());
  return *meshes_.emplace(key, std::move(m)).first->second;
}

void Renderer::resolveMeshes(const RenderList& list) {
  meshSlots_.resize(list.items.size());
  for (size_t i = 0; i < list.items.size(); ++i) meshSlots_[i] = mesh(list.items[i]).slot;
}

void Renderer::uploadInstances(const InstanceBatches& batches, unsigned buffer) {
  gl_.glBindBuffer(GL_ARRAY_BUFFER, buffer);
  // A fresh store each frame: the driver need not wait for draws that still
  // read the previous frame's records.
  gl_.glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(batches.records().size() * sizeof(InstanceRecord)),
                   batches.records().data(), GL_STREAM_DRAW);
}

const Renderer::GpuMesh& Renderer::bindBatch(const InstanceBatch& batch, unsigned buffer) {
  const GpuMesh& m = *meshBySlot_[batch.meshSlot];
  gl_.glBindVertexArray(m.vao);
  gl_.glBindBuffer(GL_ARRAY_BUFFER, buffer);
  const GLsizei stride = sizeof(InstanceRecord);
  const size_t base = size_t(batch.first) * sizeof(InstanceRecord);
  auto at = [&](size_t offset) { return reinterpret_cast<const void*>(base + offset); };
  for (unsigned c = 0; c < 4; ++c)
    gl_.glVertexAttribPointer(3 + c, 4, GL_FLOAT, GL_FALSE, stride, at(offsetof(InstanceRecord, worldFromLocal) + 16 * c));
  for (unsigned c = 0; c < 3; ++c)
    gl_.glVertexAttribPointer(7 + c, 3, GL_FLOAT, GL_FALSE, stride, at(offsetof(InstanceRecord, normalMatrix) + 12 * c));
  gl_.glVertexAttribPointer(10, 3, GL_FLOAT, GL_FALSE, stride, at(offsetof(InstanceRecord, baseColor)));
  gl_.glVertexAttribPointer(11, 4, GL_FLOAT, GL_FALSE, stride, at(offsetof(InstanceRecord, surface)));
  gl_.glVertexAttribPointer(12, 4, GL_FLOAT, GL_FALSE, stride, at(offsetof(InstanceRecord, textureTransform)));
  gl_.glVertexAttribIPointer(13, 1, GL_UNSIGNED_INT, stride, at(offsetof(InstanceRecord, id)));
  return m;
}

void Renderer::drawWholeMeshes(const InstanceBatches& batches, unsigned buffer, const std::vector<uint8_t>* skip) {
  const std::vector<InstanceBatch>& byMesh = batches.byMesh();
  for (size_t b = 0; b < byMesh.size(); ++b) {
    if (skip && (*skip)[b]) continue;
    const InstanceBatch& batch = byMesh[b];
    const GpuMesh& m = bindBatch(batch, buffer);
    GLsizei count = 0;
    for (const MeshPart& part : m.parts) count = std::max<GLsizei>(count, GLsizei(part.firstIndex + part.indexCount));
    gl_.glDrawElementsInstanced(GL_TRIANGLES, count, GL_UNSIGNED_INT, nullptr, GLsizei(batch.count));
  }
}

const Renderer::GpuTexture& Renderer::texture(const std::string& path, const std::string& primPath) {
  auto it = textures_.find(path);
  if (it != textures_.end()) return it->second;
  std::optional<std::string> resolved = assets_.resolve(path);
  if (!resolved) throw RunError(primPath + ": texture '" + path + "' not found; " + assets_.describeSearch(path));
  ImageRgba8 image;
  try {
    image = loadPng(*resolved);
  } catch (const RunError& e) {
    throw RunError(primPath + ": " + e.what());
  }
  const unsigned t = makeSrgbTexture(gl_, image);
  int levels = 1 + int(std::floor(std::log2(double(std::max(image.width, image.height)))));
  return textures_.emplace(path, GpuTexture{t, levels}).first->second;
}

Renderer::Uniforms Renderer::uniformsOf(unsigned program) const {
  Uniforms u;
#define SDG_UNIFORM_LOOKUP(name) u.name = gl_.glGetUniformLocation(program, #name);
  SDG_SCENE_UNIFORMS(SDG_UNIFORM_LOOKUP)
#undef SDG_UNIFORM_LOOKUP
  return u;
}

const Renderer::Uniforms& Renderer::sceneVariant(int textureMode) {
  const SceneProgram*& variant = frameVariants_[textureMode];
  if (variant) {
    gl_.glUseProgram(variant->program);
    return *variant->uniforms;
  }
  variantKey_.assign(lightCalls_);
  variantKey_ += "#define TEXTURE_MODE ";
  variantKey_ += char('0' + textureMode);
  variantKey_ += '\n';
  auto it = scenePrograms_.find(variantKey_);
  if (it == scenePrograms_.end()) {
    SceneProgram p;
    p.program = link(gl_, shaders::kSceneVertex, shaders::kSceneFragment, true, variantKey_.c_str());
    p.uniforms = std::make_unique<Uniforms>(uniformsOf(p.program));
    it = scenePrograms_.emplace(variantKey_, std::move(p)).first;
  }
  variant = &it->second;
  gl_.glUseProgram(variant->program);
  uploadFrameUniforms(*variant->uniforms);
  return *variant->uniforms;
}

void Renderer::uploadFrameUniforms(const Uniforms& u) const {
  const FrameUniforms& f = frame_;
  static_assert(sizeof(f.radiance) == 3 * shaders::kMaxLights * sizeof(float));
  gl_.glUniformMatrix4fv(u.uViewProjection, 1, GL_FALSE, f.viewProjection.data());
  gl_.glUniform3fv(u.uCameraPosition, 1, f.eye);
  gl_.glUniform3fv(u.uCameraForward, 1, f.forward);
  gl_.glUniform1f(u.uMetersPerUnit, f.metersPerUnit);
  gl_.glUniform1f(u.uExposureScale, settings_.exposureScale);
  gl_.glUniform3fv(u.uAmbient, 1, f.ambient);
  gl_.glUniform1f(u.uShadowTexel, f.shadowTexel);
  gl_.glUniform3fv(u.uLightRadiance, shaders::kMaxLights, f.radiance);
  gl_.glUniform3fv(u.uLightPosition, shaders::kMaxLights, f.position);
  gl_.glUniform3fv(u.uLightDirection, shaders::kMaxLights, f.direction);
  gl_.glUniform4fv(u.uLightParams, shaders::kMaxLights, f.params);
  gl_.glUniformMatrix4fv(u.uShadowMatrix, 4, GL_FALSE, f.shadowMatrices);
  // Texture units: 0 surface, 1 dome, 2 the shadow atlas.
  gl_.glUniform1i(u.uTexture, 0);
  gl_.glUniform1i(u.uDome, 1);
  gl_.glUniform1i(u.uShadowAtlas, 2);
  if (f.dome) {
    gl_.glUniformMatrix3fv(u.uDomeFromWorld, 1, GL_FALSE, f.domeFromWorld.data());
    gl_.glUniform1f(u.uDomeLod, f.domeLod);
    gl_.glUniform3fv(u.uDomeScale, 1, f.domeScale);
  }
}

int Renderer::shadowMapSize() const {
  if (settings_.shadowMapSize > 0) return settings_.shadowMapSize;
  return std::clamp(std::max(settings_.width, settings_.height), 256, 4096);
}

Eigen::AlignedBox3d Renderer::sceneBounds(const RenderList& list) {
  itemBounds_.resize(list.items.size());
  Eigen::AlignedBox3d box;
  for (size_t i = 0; i < list.items.size(); ++i) {
    const RenderItem& item = list.items[i];
    const Eigen::AlignedBox3f& b = meshBySlot_[meshSlots_[i]]->bounds;
    Eigen::AlignedBox3d& world = itemBounds_[i];
    world.setEmpty();
    if (!b.isEmpty())
      for (int c = 0; c < 8; ++c) {
        Vec3d corner = b.corner(static_cast<Eigen::AlignedBox3f::CornerType>(c)).cast<double>();
        world.extend((item.worldFromLocal * corner.homogeneous()).head<3>());
      }
    box.extend(world);
  }
  if (box.isEmpty()) box.extend(Vec3d::Zero());
  return box;
}

void Renderer::markShadowlessBatches(const RenderLight& light, const Eigen::AlignedBox3d& scene) {
  // Each flat instance tested costs a pass over every item's bounds, so a
  // frame tests a few (ground planes, backdrops) and draws the rest.
  constexpr int kMaxFlatInstancesTested = 8;
  const double tolerance = 1e-6 * std::max(1.0, scene.diagonal().norm());
  const std::vector<InstanceBatch>& byMesh = batches_.byMesh();
  const std::vector<InstanceRecord>& records = batches_.records();
  skipInShadow_.assign(byMesh.size(), 0);
  int budget = kMaxFlatInstancesTested;
  for (size_t b = 0; b < byMesh.size(); ++b) {
    const InstanceBatch& batch = byMesh[b];
    const Eigen::AlignedBox3f& local = meshBySlot_[batch.meshSlot]->bounds;
    if (int(batch.count) > budget || !flatAxis(local)) continue;
    bool skip = true;
    for (uint32_t k = 0; k < batch.count && skip; ++k) {
      --budget;
      const std::optional<FlatSurface> surface = flatSurface(local, records[batch.first + k].worldFromLocal);
      skip = surface && shadowsNothing(*surface, light, itemBounds_, tolerance);
    }
    skipInShadow_[b] = skip ? 1 : 0;
  }
}

void Renderer::compileFor(const RenderList& list, size_t cameraIndex, const PassSelection& passes,
                          const std::vector<std::vector<size_t>>* coverageGroups) {
  resolveMeshes(list);
  const Eigen::AlignedBox3d bounds = sceneBounds(list);
  RenderList away = list;
  RenderCamera& camera = away.cameras.at(cameraIndex);
  // Beyond the scene along the view direction, still looking that way:
  // every item lies behind the camera and is clipped before rasterising.
  const Vec3d forward = -camera.worldFromCamera.block<3, 1>(0, 2).normalized();
  const double past = bounds.diagonal().norm() + double(camera.nearClip) + 1.0;
  camera.worldFromCamera.block<3, 1>(0, 3) = bounds.center() + forward * past;
  FramePasses frame;
  warmAllTextureModes_ = true;
  try {
    queue(away, cameraIndex, passes, 0);
  } catch (...) {
    warmAllTextureModes_ = false;
    throw;
  }
  warmAllTextureModes_ = false;
  if (coverageGroups) queueCoverage(away, cameraIndex, *coverageGroups, 0);
  collect(0, frame);
  if (coverageGroups) {
    CoverageMasks masks;
    collectCoverage(0, masks);
  }
}

void Renderer::drawShadowMaps(const RenderList& list, const RenderCamera& camera) {
  const Eigen::AlignedBox3d scene = sceneBounds(list);
  const Eigen::AlignedBox3d receivers = visibleRegion(camera, settings_.width, settings_.height, scene);
  for (ShadowSlot& slot : shadowSlots_)
    slot.viewProjection = shadowViewProjection(list.lights[slot.light], receivers, scene);
  const int size = shadowMapSize();
  if (!shadowAtlas_) {
    shadowAtlas_ = makeTexture(gl_, GL_DEPTH_COMPONENT24, 2 * size, 2 * size, GL_DEPTH_COMPONENT, GL_FLOAT);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl_.glBindFramebuffer(GL_FRAMEBUFFER, shadowFramebuffer_);
    gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadowAtlas_, 0);
  }
  // One framebuffer, one clear, a viewport per light: llvmpipe flushes on
  // every framebuffer switch, so tiles of one atlas cost far less than maps.
  // The clear covers the whole atlas, unused tiles too: llvmpipe clears a
  // whole framebuffer by filling its tiles, but a scissored clear by drawing
  // a quad through the depth pipeline (1.2 ms a frame for three tiles).
  gl_.glBindFramebuffer(GL_FRAMEBUFFER, shadowFramebuffer_);
  const float one = 1.0f;
  gl_.glClearBufferfv(GL_DEPTH, 0, &one);
  gl_.glEnable(GL_SCISSOR_TEST);  // each light draws only into its tile
  gl_.glEnable(GL_DEPTH_TEST);
  gl_.glDepthFunc(GL_LESS);
  gl_.glEnable(GL_POLYGON_OFFSET_FILL);
  gl_.glPolygonOffset(2.0f, 4.0f);
  gl_.glUseProgram(shadowProgram_);
  for (size_t k = 0; k < shadowSlots_.size(); ++k) {
    gl_.glViewport(GLint(k % 2) * size, GLint(k / 2) * size, size, size);
    gl_.glScissor(GLint(k % 2) * size, GLint(k / 2) * size, size, size);
    setMatrix(gl_, shadowLightViewProjection_, shadowSlots_[k].viewProjection);
    markShadowlessBatches(list.lights[shadowSlots_[k].light], scene);
    drawWholeMeshes(batches_, instanceBuffer_, &skipInShadow_);
  }
  gl_.glDisable(GL_POLYGON_OFFSET_FILL);
  gl_.glDisable(GL_SCISSOR_TEST);
}

void Renderer::drawScene(const RenderList& list, const RenderCamera& camera, const Eigen::Vector2d& jitter) {
  const int w = settings_.width, h = settings_.height;
  gl_.glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl_.glViewport(0, 0, w, h);
  // Domes: the first with a texture lights through it; others are uniform.
  Vec3f ambient = Vec3f::Zero();
  const RenderLight* texturedDome = nullptr;
  for (const RenderLight& l : list.lights) {
    if (l.kind != LightKind::Dome) continue;
    if (!texturedDome && !l.texture.empty()) texturedDome = &l;
    else ambient += l.radiance;
  }
  // The background shows the dome's colour through the same tone curve.
  float background[4] = {0, 0, 0, 1};
  for (int c = 0; c < 3; ++c) {
    float mapped = 1.0f - std::exp(-ambient[c] * settings_.exposureScale);
    background[c] = mapped <= 0.0031308f ? mapped * 12.92f : 1.055f * std::pow(mapped, 1.0f / 2.4f) - 0.055f;
  }
  const float inf = std::numeric_limits<float>::infinity();
  const float normalClear[4] = {0, 0, 0, inf}, planeClear[4] = {inf, 0, 0, 0};
  const unsigned idClear[4] = {0, 0, 0, 0};
  const float depthClear = 1.0f;
  gl_.glClearBufferfv(GL_COLOR, 0, background);
  gl_.glClearBufferfv(GL_COLOR, 1, normalClear);
  gl_.glClearBufferfv(GL_COLOR, 2, planeClear);
  gl_.glClearBufferuiv(GL_COLOR, 3, idClear);
  gl_.glClearBufferfv(GL_DEPTH, 0, &depthClear);
  gl_.glEnable(GL_DEPTH_TEST);
  gl_.glDepthFunc(GL_LESS);

  // Lights (the dome is the ambient term above).
  FrameUniforms& f = frame_;
  std::fill(std::begin(f.radiance), std::end(f.radiance), 0.0f);
  std::fill(std::begin(f.position), std::end(f.position), 0.0f);
  std::fill(std::begin(f.direction), std::end(f.direction), 0.0f);
  std::fill(std::begin(f.params), std::end(f.params), 0.0f);
  int count = 0;
  lightCalls_.assign("#define ADD_LIGHTS");
  for (size_t i = 0; i < list.lights.size() && count < shaders::kMaxLights; ++i) {
    const RenderLight& l = list.lights[i];
    if (l.kind == LightKind::Dome) continue;
    int shadowSlot = -1;
    for (size_t k = 0; k < shadowSlots_.size(); ++k)
      if (shadowSlots_[k].light == i) shadowSlot = int(k);
    appendLightCall(lightCalls_, count, lightTypeCode(l.kind), shadowSlot);
    for (int c = 0; c < 3; ++c) {
      f.radiance[3 * count + c] = l.radiance[c];
      f.position[3 * count + c] = float(l.position[c]);
      f.direction[3 * count + c] = float(l.direction[c]);
    }
    f.params[4 * count + 0] = l.radius;
    f.params[4 * count + 1] = l.width;
    f.params[4 * count + 2] = l.height;
    f.params[4 * count + 3] = l.length;
    ++count;
  }
  lightCalls_ += texturedDome ? "\n#define HAS_DOME 1\n" : "\n#define HAS_DOME 0\n";
  const Matrix4d viewProjection = projectionMatrix(camera, w, h, jitter) * viewMatrix(camera);
  // Depth first, colour writes off: the expensive lighting below then runs
  // once per visible pixel instead of once per covering triangle.
  gl_.glUseProgram(depthProgram_);
  setMatrix(gl_, depthViewProjection_, viewProjection);
  gl_.glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  drawWholeMeshes(batches_, instanceBuffer_);
  gl_.glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  gl_.glDepthFunc(GL_LEQUAL);

  f.viewProjection = toFloat(viewProjection);
  const Vec3d eye = camera.worldFromCamera.block<3, 1>(0, 3);
  const Vec3d forward = -camera.worldFromCamera.block<3, 1>(0, 2).normalized();
  for (int c = 0; c < 3; ++c) {
    f.eye[c] = float(eye[c]);
    f.forward[c] = float(forward[c]);
    f.ambient[c] = ambient[c];
  }
  f.metersPerUnit = float(list.metersPerUnit);
  f.shadowTexel = 1.0f / float(2 * shadowMapSize());
  std::fill(std::begin(f.shadowMatrices), std::end(f.shadowMatrices), 0.0f);
  for (size_t k = 0; k < shadowSlots_.size(); ++k) {
    Eigen::Matrix4f m = shadowSlots_[k].viewProjection.cast<float>();
    std::copy_n(m.data(), 16, f.shadowMatrices + 16 * k);
  }
  gl_.glActiveTexture(GL_TEXTURE2);
  gl_.glBindTexture(GL_TEXTURE_2D, shadowAtlas_);
  gl_.glActiveTexture(GL_TEXTURE1);
  f.dome = texturedDome != nullptr;
  if (texturedDome) {
    const GpuTexture& dome = texture(texturedDome->texture, texturedDome->path);
    gl_.glBindTexture(GL_TEXTURE_2D, dome.id);
    f.domeFromWorld = texturedDome->worldRotation.transpose().cast<float>();
    f.domeLod = float(std::max(0, dome.levels - 3));  // a 4 x 2 texel average
    for (int c = 0; c < 3; ++c) f.domeScale[c] = texturedDome->radiance[c];
  } else {
    gl_.glBindTexture(GL_TEXTURE_2D, whiteTexture_);
  }
  gl_.glActiveTexture(GL_TEXTURE0);
  std::fill(std::begin(frameVariants_), std::end(frameVariants_), nullptr);

  bool warmed = !warmAllTextureModes_;
  for (const InstanceBatch& batch : batches_.byMaterial()) {
    const GpuMesh& m = bindBatch(batch, instanceBuffer_);
    const RenderItem& item = list.items[batch.item];  // the batch shares its material source
    for (const MeshPart& part : m.parts) {
      // The prim's bound material wins; else the file's; else displayColor
      // (the last two and the texture transform travel per instance).
      const bool useFile = !item.material.fromPrim && part.hasMaterial;
      const std::string& tex = useFile ? part.texture : item.material.texture;
      const int textureMode = tex.empty() ? 0 : item.material.projectUvw ? 2 : 1;
      gl_.glBindTexture(GL_TEXTURE_2D, tex.empty() ? whiteTexture_ : texture(tex, item.primPath).id);
      const GLsizei indexCount = GLsizei(part.indexCount);
      const void* firstIndex = reinterpret_cast<const void*>(uintptr_t(part.firstIndex) * sizeof(uint32_t));
      // The part's own mode; the warm-up's first part is drawn in all three.
      for (int mode = warmed ? textureMode : 0; mode < (warmed ? textureMode + 1 : 3); ++mode) {
        const Uniforms& u = sceneVariant(mode);
        gl_.glUniform1i(u.uUsePartMaterial, useFile ? 1 : 0);
        if (useFile) {
          gl_.glUniform3f(u.uPartBaseColor, part.baseColor.x(), part.baseColor.y(), part.baseColor.z());
          gl_.glUniform2f(u.uPartSurface, part.roughness, part.metallic);
        }
        gl_.glDrawElementsInstanced(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, firstIndex, GLsizei(batch.count));
      }
      warmed = true;
    }
  }
  if (texturedDome) {
    // The sky fills what geometry left at the far plane.
    gl_.glDepthFunc(GL_LEQUAL);
    gl_.glUseProgram(skyProgram_);
    const Uniforms& sky = *skyUniforms_;
    setMatrix(gl_, sky.uWorldFromClip, viewProjection.inverse());
    gl_.glUniform3f(sky.uCameraPosition, float(eye.x()), float(eye.y()), float(eye.z()));
    Eigen::Matrix3f domeFromWorld = texturedDome->worldRotation.transpose().cast<float>();
    gl_.glUniformMatrix3fv(sky.uDomeFromWorld, 1, GL_FALSE, domeFromWorld.data());
    gl_.glUniform3f(sky.uDomeScale, texturedDome->radiance.x(), texturedDome->radiance.y(), texturedDome->radiance.z());
    gl_.glUniform1f(sky.uExposureScale, settings_.exposureScale);
    gl_.glUniform1i(sky.uDome, 1);
    gl_.glBindVertexArray(emptyVao_);
    gl_.glDrawArrays(GL_TRIANGLES, 0, 3);
    gl_.glDepthFunc(GL_LESS);
  }
  gl_.glBindVertexArray(0);
}

namespace {

// Bytes per pixel of each attachment as it is read back.
constexpr size_t kAttachmentBytes[4] = {4, 16, 4, 4};

void readAttachment(const GlApi& gl, int attachment, int w, int h, void* target) {
  gl.glReadBuffer(GLenum(GL_COLOR_ATTACHMENT0 + attachment));
  switch (attachment) {
    case 0: gl.glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, target); break;
    case 1: gl.glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, target); break;
    case 2: gl.glReadPixels(0, 0, w, h, GL_RED, GL_FLOAT, target); break;
    default: gl.glReadPixels(0, 0, w, h, GL_RED_INTEGER, GL_UNSIGNED_INT, target); break;
  }
}

bool wanted(int attachment, const PassSelection& passes) {
  return attachment == 0 || (attachment == 1 && passes.normals) || (attachment == 2 && passes.imagePlane) ||
         (attachment == 3 && passes.ids);
}

}  // namespace

void Renderer::unpack(int attachment, const void* pixels, FramePasses& out) {
  const int w = settings_.width, h = settings_.height;
  const size_t n = size_t(w) * size_t(h);
  // GL rows run bottom to top; outputs run top to bottom.
  auto flipInto = [&](const auto* source, auto* target, size_t perPixel) {
    const size_t row = size_t(w) * perPixel;
    for (int y = 0; y < h; ++y) std::copy_n(source + size_t(h - 1 - y) * row, row, target + size_t(y) * row);
  };
  switch (attachment) {
    case 0: flipInto(static_cast<const uint8_t*>(pixels), out.rgba.data(), 4); break;
    case 1:
      flipInto(static_cast<const float*>(pixels), out.normals.data(), 4);
      for (size_t i = 0; i < n; ++i) {
        out.distanceToCamera[i] = out.normals[4 * i + 3];
        out.normals[4 * i + 3] = 0.0f;
      }
      break;
    case 2: flipInto(static_cast<const float*>(pixels), out.distanceToImagePlane.data(), 1); break;
    default: flipInto(static_cast<const uint32_t*>(pixels), out.instanceIds.data(), 1); break;
  }
}

void Renderer::readBack(FramePasses& out, bool colorOnly, const PassSelection& passes) {
  const int w = settings_.width, h = settings_.height;
  const size_t n = size_t(w) * size_t(h);
  gl_.glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl_.glPixelStorei(GL_PACK_ALIGNMENT, 1);
  scratchRgba_.resize(n * 4);
  readAttachment(gl_, 0, w, h, scratchRgba_.data());
  if (colorOnly) {
    for (int y = 0; y < h; ++y)
      for (size_t i = 0; i < size_t(w) * 4; ++i) colorSum_[size_t(y) * w * 4 + i] += scratchRgba_[size_t(h - 1 - y) * w * 4 + i];
    return;
  }
  unpack(0, scratchRgba_.data(), out);
  scratchFloat_.resize(n * 4);
  for (int attachment = 1; attachment < 4; ++attachment) {
    if (!wanted(attachment, passes)) continue;
    readAttachment(gl_, attachment, w, h, scratchFloat_.data());
    unpack(attachment, scratchFloat_.data(), out);
  }
}

void Renderer::ensureTargets() {
  const int w = settings_.width, h = settings_.height;
  if (colorTexture_) return;
  colorTexture_ = makeTexture(gl_, GL_RGBA8, w, h, GL_RGBA, GL_UNSIGNED_BYTE);
  normalTexture_ = makeTexture(gl_, GL_RGBA32F, w, h, GL_RGBA, GL_FLOAT);
  planeTexture_ = makeTexture(gl_, GL_R32F, w, h, GL_RED, GL_FLOAT);
  idTexture_ = makeTexture(gl_, GL_R32UI, w, h, GL_RED_INTEGER, GL_UNSIGNED_INT);
  depthTexture_ = makeTexture(gl_, GL_DEPTH_COMPONENT24, w, h, GL_DEPTH_COMPONENT, GL_FLOAT);
  gl_.glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colorTexture_, 0);
  gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, normalTexture_, 0);
  gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, GL_TEXTURE_2D, planeTexture_, 0);
  gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT3, GL_TEXTURE_2D, idTexture_, 0);
  gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depthTexture_, 0);
  const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
  gl_.glDrawBuffers(4, buffers);
  if (gl_.glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw RunError("renderer: the framebuffer for " + std::to_string(w) + " x " + std::to_string(h) +
                   " is incomplete (out of memory?)");
}

// Shadow maps, then the un-jittered frame: labels come from it, exact.
void Renderer::drawFrame(const RenderList& list, size_t cameraIndex, const PassSelection& passes) {
  if (cameraIndex >= list.cameras.size()) throw RunError("renderer: no camera to render");
  ensureTargets();
  // Attachments nobody reads are not written: each costs llvmpipe a store
  // per pixel (16 bytes for normals).
  gl_.glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  GLenum buffers[4] = {GL_COLOR_ATTACHMENT0, GL_NONE, GL_NONE, GL_NONE};
  for (int attachment = 1; attachment < 4; ++attachment)
    if (wanted(attachment, passes)) buffers[attachment] = GLenum(GL_COLOR_ATTACHMENT0 + attachment);
  gl_.glDrawBuffers(4, buffers);
  resolveMeshes(list);
  batches_.build(list, meshSlots_);
  uploadInstances(batches_, instanceBuffer_);
  // Distant and sphere lights cast shadows, in stage order, up to the limit.
  shadowSlots_.clear();
  for (size_t i = 0; i < list.lights.size() && int(shadowSlots_.size()) < std::min(settings_.maxShadowedLights, 4); ++i)
    if (list.lights[i].kind == LightKind::Distant || list.lights[i].kind == LightKind::Sphere)
      shadowSlots_.push_back({i, Matrix4d::Identity()});
  if (!shadowSlots_.empty()) drawShadowMaps(list, list.cameras[cameraIndex]);
  drawScene(list, list.cameras[cameraIndex], {0, 0});
}

void Renderer::queue(const RenderList& list, size_t cameraIndex, const PassSelection& passes, int slot) {
  ReadSlot& r = readSlots_[slot & 1];
  if (settings_.subframes > 1) {
    render(list, cameraIndex, r.frame, passes);
    r.synchronous = true;
    r.pending = true;
    return;
  }
  drawFrame(list, cameraIndex, passes);
  const int w = settings_.width, h = settings_.height;
  gl_.glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl_.glPixelStorei(GL_PACK_ALIGNMENT, 1);
  for (int attachment = 0; attachment < 4; ++attachment) {
    if (!wanted(attachment, passes)) continue;
    if (!r.buffers[attachment]) {
      gl_.glGenBuffers(1, &r.buffers[attachment]);
      gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, r.buffers[attachment]);
      gl_.glBufferData(GL_PIXEL_PACK_BUFFER, GLsizeiptr(size_t(w) * size_t(h) * kAttachmentBytes[attachment]), nullptr,
                       GL_STREAM_READ);
    }
    gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, r.buffers[attachment]);
    readAttachment(gl_, attachment, w, h, nullptr);  // into the bound buffer: returns at once
  }
  gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  r.passes = passes;
  r.synchronous = false;
  r.pending = true;
}

void Renderer::collect(int slot, FramePasses& out) {
  ReadSlot& r = readSlots_[slot & 1];
  if (!r.pending) throw RunError("renderer: nothing was queued in read-back slot " + std::to_string(slot));
  r.pending = false;
  if (r.synchronous) {
    std::swap(out, r.frame);
    return;
  }
  const int w = settings_.width, h = settings_.height;
  out.resize(w, h, r.passes);
  for (int attachment = 0; attachment < 4; ++attachment) {
    if (!wanted(attachment, r.passes)) continue;
    const size_t bytes = size_t(w) * size_t(h) * kAttachmentBytes[attachment];
    gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, r.buffers[attachment]);
    const void* pixels = gl_.glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0, GLsizeiptr(bytes), GL_MAP_READ_BIT);
    if (!pixels) throw RunError("renderer: cannot map the read-back buffer of attachment " + std::to_string(attachment));
    unpack(attachment, pixels, out);
    gl_.glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
  }
  gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

void Renderer::render(const RenderList& list, size_t cameraIndex, FramePasses& out, const PassSelection& passes) {
  out.resize(settings_.width, settings_.height, passes);
  drawFrame(list, cameraIndex, passes);
  const RenderCamera& camera = list.cameras[cameraIndex];
  readBack(out, false, passes);
  if (settings_.subframes <= 1) return;
  colorSum_.assign(out.rgba.begin(), out.rgba.end());
  for (int s = 1; s < settings_.subframes; ++s) {
    Eigen::Vector2d jitter(halton(s, 2) - 0.5, halton(s, 3) - 0.5);
    drawScene(list, camera, jitter);
    readBack(out, true, passes);
  }
  const uint32_t k = uint32_t(settings_.subframes);
  for (size_t i = 0; i < out.rgba.size(); ++i) out.rgba[i] = uint8_t((colorSum_[i] + k / 2) / k);
}

}  // namespace sdg

namespace sdg {

void Renderer::queueCoverage(const RenderList& list, size_t cameraIndex, const std::vector<std::vector<size_t>>& groups,
                             int slot) {
  ReadSlot& r = readSlots_[slot & 1];
  const int w = settings_.width, h = settings_.height;
  r.maskGroups = groups.size();
  r.masksPending = true;
  if (groups.empty()) return;
  if (maskWidth_ != w || maskHeight_ != h) {
    unsigned old[] = {maskTexture_, maskDepth_};
    gl_.glDeleteTextures(2, old);
    maskTexture_ = makeTexture(gl_, GL_R32UI, w, h, GL_RED_INTEGER, GL_UNSIGNED_INT);
    maskDepth_ = makeTexture(gl_, GL_DEPTH_COMPONENT24, w, h, GL_DEPTH_COMPONENT, GL_FLOAT);
    gl_.glBindFramebuffer(GL_FRAMEBUFFER, maskFramebuffer_);
    gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, maskTexture_, 0);
    gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, maskDepth_, 0);
    const GLenum buffer = GL_COLOR_ATTACHMENT0;
    gl_.glDrawBuffers(1, &buffer);
    maskWidth_ = w;
    maskHeight_ = h;
  }
  const size_t layers = (groups.size() + 31) / 32;
  const size_t layerBytes = size_t(w) * size_t(h) * sizeof(uint32_t);
  if (!r.maskBuffer) gl_.glGenBuffers(1, &r.maskBuffer);
  gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, r.maskBuffer);
  if (r.maskBufferBytes < layers * layerBytes) {
    r.maskBufferBytes = layers * layerBytes;
    gl_.glBufferData(GL_PIXEL_PACK_BUFFER, GLsizeiptr(r.maskBufferBytes), nullptr, GL_STREAM_READ);
  }
  const RenderCamera& camera = list.cameras[cameraIndex];
  const Matrix4d viewProjection = projectionMatrix(camera, w, h) * viewMatrix(camera);
  gl_.glBindFramebuffer(GL_FRAMEBUFFER, maskFramebuffer_);
  gl_.glViewport(0, 0, w, h);
  // Each entity writes its own bit with OR and no depth test, so one pass
  // (and one read-back) covers 32 entities drawn as if alone.
  gl_.glDisable(GL_DEPTH_TEST);
  gl_.glEnable(GL_COLOR_LOGIC_OP);
  gl_.glLogicOp(GL_OR);
  gl_.glUseProgram(maskProgram_);
  resolveMeshes(list);
  setMatrix(gl_, maskViewProjection_, viewProjection);
  gl_.glPixelStorei(GL_PACK_ALIGNMENT, 1);
  gl_.glReadBuffer(GL_COLOR_ATTACHMENT0);
  const unsigned zero[4] = {0, 0, 0, 0};
  for (size_t layer = 0; layer < layers; ++layer) {
    const size_t first = layer * 32, last = std::min(groups.size(), first + 32);
    gl_.glClearBufferuiv(GL_COLOR, 0, zero);
    maskBatches_.buildMasks(list, meshSlots_, groups, first, last);
    uploadInstances(maskBatches_, maskInstanceBuffer_);
    drawWholeMeshes(maskBatches_, maskInstanceBuffer_);
    gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, r.maskBuffer);
    gl_.glReadPixels(0, 0, w, h, GL_RED_INTEGER, GL_UNSIGNED_INT, reinterpret_cast<void*>(layer * layerBytes));
  }
  gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  gl_.glDisable(GL_COLOR_LOGIC_OP);
  gl_.glEnable(GL_DEPTH_TEST);
  gl_.glBindVertexArray(0);
}

void Renderer::collectCoverage(int slot, CoverageMasks& out) {
  ReadSlot& r = readSlots_[slot & 1];
  if (!r.masksPending) throw RunError("renderer: no coverage was queued in read-back slot " + std::to_string(slot));
  r.masksPending = false;
  out.width = settings_.width;
  out.height = settings_.height;
  out.groups = r.maskGroups;
  const size_t words = (r.maskGroups + 31) / 32 * size_t(out.width) * size_t(out.height);
  out.bits.resize(words);
  if (!words) return;
  gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, r.maskBuffer);
  const void* pixels = gl_.glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0, GLsizeiptr(words * sizeof(uint32_t)), GL_MAP_READ_BIT);
  if (!pixels) throw RunError("renderer: cannot map the coverage read-back buffer");
  std::copy_n(static_cast<const uint32_t*>(pixels), words, out.bits.data());
  gl_.glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
  gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

void Renderer::coverageOf(const CoverageMasks& masks, std::vector<Coverage>& out) {
  const int w = masks.width, h = masks.height;
  out.assign(masks.groups, Coverage{});
  for (auto& c : out) {
    c.xMin = w;
    c.yMin = h;
  }
  const size_t layerWords = size_t(w) * size_t(h);
  for (size_t layer = 0; layer * 32 < masks.groups; ++layer) {
    const uint32_t* pixels = masks.bits.data() + layer * layerWords;
    for (int glY = 0; glY < h; ++glY) {
      const uint32_t* row = pixels + size_t(glY) * size_t(w);
      const int y = h - 1 - glY;  // rows top to bottom
      // A row is long runs of one mask (mostly 0): each run's groups are
      // updated once, not once per pixel.
      for (int x = 0; x < w;) {
        const uint32_t mask = row[x];
        int end = x + 1;
        while (end < w && row[end] == mask) ++end;
        for (uint32_t bits = mask; bits; bits &= bits - 1) {
          Coverage& c = out[layer * 32 + size_t(__builtin_ctz(bits))];
          c.pixels += uint64_t(end - x);
          c.xMin = std::min(c.xMin, x);
          c.xMax = std::max(c.xMax, end - 1);
          c.yMin = std::min(c.yMin, y);
          c.yMax = std::max(c.yMax, y);
        }
        x = end;
      }
    }
  }
  for (auto& c : out)
    if (!c.pixels) c = Coverage{};
}

}  // namespace sdg

namespace sdg {
Eigen::AlignedBox3f Renderer::meshBounds(const RenderItem& item) { return mesh(item).bounds; }
}  // namespace sdg
