#include "render/raster/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "core/diagnostics.h"
#include "render/camera_math.h"
#include "render/raster/renderer_internal.h"
#include "render/raster/shaders.h"
#include "render/raster/environment_map.h"
#include "render/raster/gl_textures.h"
#include "stage/xform.h"

namespace sdg {

using namespace raster_detail;

namespace {

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
void appendLightCall(std::string& calls, int index, int type, int shadowSlot, bool scaledLobes) {
  calls += scaledLobes ? " radiance += lightContributionScaled(" : " radiance += lightContribution(";
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
  brdfLut_ = makeLutTexture(gl_, integrateSplitSumLut());
  for (int unit : {kBaseUnit, kDomeSpecularUnit, kRoughnessUnit, kMetallicUnit, kOrmUnit, kNormalUnit, kOpacityUnit,
                   kDomeIrradianceUnit, kDomeBackgroundUnit}) {
    gl_.glActiveTexture(GLenum(GL_TEXTURE0 + unit));
    gl_.glBindTexture(GL_TEXTURE_2D, whiteTexture_);
  }
  gl_.glActiveTexture(GL_TEXTURE0 + kBrdfLutUnit);
  gl_.glBindTexture(GL_TEXTURE_2D, brdfLut_);
  gl_.glActiveTexture(GL_TEXTURE0);
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
    if (m->colorBuffer) gl_.glDeleteBuffers(1, &m->colorBuffer);
  }
  for (auto* cache : {&colorTextures_, &dataTextures_})
    for (auto& [key, t] : *cache) gl_.glDeleteTextures(1, &t.id);
  for (auto& [key, d] : domes_) {
    unsigned ids[] = {d.background, d.specular, d.irradiance};
    gl_.glDeleteTextures(3, ids);
  }
  gl_.glDeleteTextures(1, &brdfLut_);
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
  if (!data.colors.empty()) {
    gl_.glGenBuffers(1, &m->colorBuffer);
    upload(m->colorBuffer, 14, 4, data.colors.data(), data.colors.size() * sizeof(Eigen::Vector4f));
  }
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
  for (EmbeddedImage& image : data.embeddedImages) embeddedImages_.try_emplace(image.key, std::move(image));
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

void Renderer::markCutOutBatches(const RenderList& list) {
  const std::vector<InstanceBatch>& byMesh = batches_.byMesh();
  skipInDepth_.assign(byMesh.size(), 0);
  size_t b = 0;
  for (const InstanceBatch& batch : batches_.byMaterial()) {
    while (b + 1 < byMesh.size() && byMesh[b + 1].first <= batch.first) ++b;
    const RenderItem& item = list.items[batch.item];
    bool cutOut = item.material.cutOut();
    if (!item.material.fromPrim)
      for (const MeshPart& part : meshBySlot_[batch.meshSlot]->parts)
        cutOut = cutOut || (part.hasMaterial && part.opacity != OpacitySource::None);
    if (cutOut) skipInDepth_[b] = 1;
  }
}

Renderer::Uniforms Renderer::uniformsOf(unsigned program) const {
  Uniforms u;
#define SDG_UNIFORM_LOOKUP(name) u.name = gl_.glGetUniformLocation(program, #name);
  SDG_SCENE_UNIFORMS(SDG_UNIFORM_LOOKUP)
#undef SDG_UNIFORM_LOOKUP
  return u;
}

const Renderer::Uniforms& Renderer::sceneVariant(const ShadingVariant& shading) {
  const SceneProgram*& variant = frameVariants_[size_t(shading.index())];
  if (variant) {
    gl_.glUseProgram(variant->program);
    return *variant->uniforms;
  }
  variantKey_.assign(lightCalls_);
  shading.appendDefines(variantKey_);
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
  gl_.glUniform3fv(u.uAmbientSpecular, 1, f.ambientSpecular);
  gl_.glUniform1f(u.uShadowTexel, f.shadowTexel);
  gl_.glUniform3fv(u.uLightRadiance, shaders::kMaxLights, f.radiance);
  gl_.glUniform3fv(u.uLightPosition, shaders::kMaxLights, f.position);
  gl_.glUniform3fv(u.uLightDirection, shaders::kMaxLights, f.direction);
  gl_.glUniform4fv(u.uLightParams, shaders::kMaxLights, f.params);
  gl_.glUniform2fv(u.uLightResponse, shaders::kMaxLights, f.response);
  gl_.glUniformMatrix4fv(u.uShadowMatrix, 4, GL_FALSE, f.shadowMatrices);
  gl_.glUniform1i(u.uTexture, kBaseUnit);
  gl_.glUniform1i(u.uDome, kDomeSpecularUnit);
  gl_.glUniform1i(u.uShadowAtlas, kShadowUnit);
  gl_.glUniform1i(u.uRoughnessMap, kRoughnessUnit);
  gl_.glUniform1i(u.uMetallicMap, kMetallicUnit);
  gl_.glUniform1i(u.uOrmMap, kOrmUnit);
  gl_.glUniform1i(u.uNormalMap, kNormalUnit);
  gl_.glUniform1i(u.uOpacityMap, kOpacityUnit);
  gl_.glUniform1i(u.uDomeIrradiance, kDomeIrradianceUnit);
  gl_.glUniform1i(u.uBrdfLut, kBrdfLutUnit);
  if (f.dome) {
    gl_.glUniformMatrix3fv(u.uDomeFromWorld, 1, GL_FALSE, f.domeFromWorld.data());
    gl_.glUniform1f(u.uDomeLod, f.domeLod);
    gl_.glUniform3fv(u.uDomeScale, 1, f.domeScale);
    gl_.glUniform2fv(u.uDomeResponse, 1, f.domeResponse);
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

void Renderer::drawScene(const RenderList& list, const RenderCamera& camera, const Eigen::Vector2d& jitter) {
  const int w = settings_.width, h = settings_.height;
  gl_.glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl_.glViewport(0, 0, w, h);
  // Domes: the first with a texture lights through it; others are uniform.
  // The surfaces see each dome through its diffuse and specular multipliers;
  // the background shows the dome itself.
  Vec3f ambient = Vec3f::Zero(), ambientDiffuse = Vec3f::Zero(), ambientSpecular = Vec3f::Zero();
  const RenderLight* texturedDome = nullptr;
  for (const RenderLight& l : list.lights) {
    if (l.kind != LightKind::Dome) continue;
    if (!texturedDome && !l.texture.empty()) {
      texturedDome = &l;
    } else {
      ambient += l.radiance;
      ambientDiffuse += l.radiance * l.diffuse;
      ambientSpecular += l.radiance * l.specular;
    }
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
  std::fill(std::begin(f.response), std::end(f.response), 1.0f);
  int count = 0;
  lightCalls_.assign("#define ADD_LIGHTS");
  for (size_t i = 0; i < list.lights.size() && count < shaders::kMaxLights; ++i) {
    const RenderLight& l = list.lights[i];
    if (l.kind == LightKind::Dome) continue;
    int shadowSlot = -1;
    for (size_t k = 0; k < shadowSlots_.size(); ++k)
      if (shadowSlots_[k].light == i) shadowSlot = int(k);
    appendLightCall(lightCalls_, count, lightTypeCode(l.kind), shadowSlot, l.diffuse != 1.0f || l.specular != 1.0f);
    f.response[2 * count + 0] = l.diffuse;
    f.response[2 * count + 1] = l.specular;
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
  markCutOutBatches(list);
  drawWholeMeshes(batches_, instanceBuffer_, &skipInDepth_);
  gl_.glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  gl_.glDepthFunc(GL_LEQUAL);

  f.viewProjection = toFloat(viewProjection);
  const Vec3d eye = camera.worldFromCamera.block<3, 1>(0, 3);
  const Vec3d forward = -camera.worldFromCamera.block<3, 1>(0, 2).normalized();
  for (int c = 0; c < 3; ++c) {
    f.eye[c] = float(eye[c]);
    f.forward[c] = float(forward[c]);
    f.ambient[c] = ambientDiffuse[c];
    f.ambientSpecular[c] = ambientSpecular[c];
  }
  f.metersPerUnit = float(list.metersPerUnit);
  f.shadowTexel = 1.0f / float(2 * shadowMapSize());
  std::fill(std::begin(f.shadowMatrices), std::end(f.shadowMatrices), 0.0f);
  for (size_t k = 0; k < shadowSlots_.size(); ++k) {
    Eigen::Matrix4f m = shadowSlots_[k].viewProjection.cast<float>();
    std::copy_n(m.data(), 16, f.shadowMatrices + 16 * k);
  }
  gl_.glActiveTexture(GL_TEXTURE0 + kShadowUnit);
  gl_.glBindTexture(GL_TEXTURE_2D, shadowAtlas_);
  f.dome = texturedDome != nullptr;
  if (texturedDome) {
    const DomeTextures& d = dome(*texturedDome);
    const std::pair<int, unsigned> units[] = {
        {kDomeSpecularUnit, d.specular}, {kDomeIrradianceUnit, d.irradiance}, {kDomeBackgroundUnit, d.background}};
    for (auto [unit, id] : units) {
      gl_.glActiveTexture(GLenum(GL_TEXTURE0 + unit));
      gl_.glBindTexture(GL_TEXTURE_2D, id);
    }
    f.domeFromWorld = texturedDome->worldRotation.transpose().cast<float>();
    f.domeLod = float(d.specularLevels - 1);
    for (int c = 0; c < 3; ++c) f.domeScale[c] = texturedDome->radiance[c];
    f.domeResponse[0] = texturedDome->diffuse;
    f.domeResponse[1] = texturedDome->specular;
  }
  gl_.glActiveTexture(GL_TEXTURE0);
  frameVariants_.fill(nullptr);

  // The first part drawn in a warm-up frame also goes through the plain,
  // UV-textured and triplanar programs (see compileFor()).
  ShadingVariant warmUps[3];
  warmUps[1].baseMap = 1;
  warmUps[2].baseMap = 1;
  warmUps[2].projection = 2;
  bool warmed = !warmAllTextureModes_;
  for (const InstanceBatch& batch : batches_.byMaterial()) {
    const GpuMesh& m = bindBatch(batch, instanceBuffer_);
    const RenderItem& item = list.items[batch.item];  // the batch shares its material source
    for (const MeshPart& part : m.parts) {
      // The prim's bound material wins; else the file's; else displayColor
      // (the last two and the texture transform travel per instance).
      const bool useFile = !item.material.fromPrim && part.hasMaterial;
      const MaterialMaps& maps = useFile ? part.maps : item.material.maps;
      const OpacitySource opacity = useFile ? part.opacity : item.material.opacity;
      ShadingVariant shading = ShadingVariant::of(maps, !useFile && item.material.projectUvw, opacity);
      shading.vertexColors = m.colorBuffer != 0 && (useFile ? part.vertexColors : item.material.vertexColors);
      bindMaps(maps, item.primPath);
      const GLsizei indexCount = GLsizei(part.indexCount);
      const void* firstIndex = reinterpret_cast<const void*>(uintptr_t(part.firstIndex) * sizeof(uint32_t));
      auto draw = [&](const ShadingVariant& variant) {
        const Uniforms& u = sceneVariant(variant);
        gl_.glUniform1i(u.uUsePartMaterial, useFile ? 1 : 0);
        if (useFile) {
          gl_.glUniform3f(u.uPartBaseColor, part.baseColor.x(), part.baseColor.y(), part.baseColor.z());
          gl_.glUniform2f(u.uPartSurface, part.roughness, part.metallic);
        }
        gl_.glUniform1f(u.uNormalScale, useFile ? part.normalScale : item.material.normalScale);
        gl_.glUniform1f(u.uSpecularLevel, useFile ? 0.5f : item.material.specularLevel);
        gl_.glUniform1f(u.uOpacityConstant, useFile ? part.opacityConstant : item.material.opacityConstant);
        gl_.glUniform1f(u.uOpacityCutoff, useFile ? part.opacityCutoff : item.material.opacityCutoff);
        gl_.glDrawElementsInstanced(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, firstIndex, GLsizei(batch.count));
      };
      if (!warmed)
        for (const ShadingVariant& w : warmUps)
          if (w.index() != shading.index()) draw(w);
      draw(shading);
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
    gl_.glUniformMatrix3fv(sky.uDomeFromWorld, 1, GL_FALSE, f.domeFromWorld.data());
    gl_.glUniform3fv(sky.uDomeScale, 1, f.domeScale);
    gl_.glUniform1f(sky.uExposureScale, settings_.exposureScale);
    gl_.glUniform1i(sky.uDomeBackground, kDomeBackgroundUnit);
    gl_.glBindVertexArray(emptyVao_);
    gl_.glDrawArrays(GL_TRIANGLES, 0, 3);
    gl_.glDepthFunc(GL_LESS);
  }
  gl_.glBindVertexArray(0);
}

// Shadow maps, then the un-jittered frame: labels come from it, exact.
void Renderer::drawFrame(const RenderList& list, size_t cameraIndex, const PassSelection& passes) {
  if (cameraIndex >= list.cameras.size()) throw RunError("renderer: no camera to render");
  drawFrame(list, list.cameras[cameraIndex], passes);
}

void Renderer::drawFrame(const RenderList& list, const RenderCamera& camera, const PassSelection& passes) {
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
  if (!shadowSlots_.empty()) drawShadowMaps(list, camera);
  drawScene(list, camera, {0, 0});
}

void Renderer::render(const RenderList& list, size_t cameraIndex, FramePasses& out, const PassSelection& passes) {
  if (cameraIndex < list.cameras.size() && list.cameras[cameraIndex].lens.calibrated()) {
    renderLens(list, list.cameras[cameraIndex], out, passes);
    return;
  }
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

// Nearest resampling of pinhole views; subframes' jitter is not applied
// (each view is drawn once, un-jittered).
void Renderer::renderLens(const RenderList& list, const RenderCamera& camera, FramePasses& out,
                          const PassSelection& passes) {
  const int w = settings_.width, h = settings_.height;
  LensViewPlan& plan = lensPlans_[camera.path];
  if (!lensPlanFits(plan, camera, w, h)) plan = planLensViews(camera, w, h);
  if (lensViews_.size() < plan.viewTemplates.size()) lensViews_.resize(plan.viewTemplates.size());
  for (size_t i = 0; i < plan.viewTemplates.size(); ++i) {
    lensViews_[i].resize(w, h, passes);
    drawFrame(list, lensView(plan, camera, i), passes);
    readBack(lensViews_[i], false, passes);
  }
  resampleLensViews(plan, lensViews_, passes, out);
}

Eigen::AlignedBox3f Renderer::meshBounds(const RenderItem& item) { return mesh(item).bounds; }

}  // namespace sdg
