#include "run/dataset_run.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <thread>

#include "behavior/runtime.h"
#include "builtin_behaviors/builtin_behaviors.h"
#include "core/diagnostics.h"
#include "core/file_io.h"
#include "core/log.h"
#include "lidar/lidar_caster.h"
#include "render/raster/renderer.h"
#include "run/dataset_finalize.h"
#include "run/color_renderer_choice.h"
#include "run/preroll.h"
#include "run/progress.h"
#include "run/record.h"
#include "run/renderer_bringup.h"
#include "run/run_inputs.h"
#include "run/scene_setup.h"
#include "stage/lidar_pattern.h"
#include "stage/path.h"
#include "writers/contact_sheet.h"
#include "writers/frame_encoder.h"
#include "writers/manifest.h"
#include "writers/png_encoder.h"
#include "writers/write_pool.h"
#include "writers/writer_registry.h"

namespace sdg {
namespace fs = std::filesystem;

namespace {

// The rasterizer's settings for a run. Where a path tracer makes the
// colour, the rasterizer's own colour is drawn but replaced, so it draws
// no shadow maps (the labels do not depend on them): on a GPU, whose time
// the raster labels and the tracing share, that time goes to tracing.
RenderSettings rasterSettings(RenderSettings settings) {
  if (settings.mode == RenderMode::PathTraced) settings.maxShadowedLights = 0;
  return settings;
}

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Frames whose every render product the folder's manifests list with files
// that still match their SHA-256 (what --resume may keep).
std::set<uint64_t> finishedFrames(const std::string& dir, size_t products) {
  std::map<uint64_t, size_t> complete;
  forEachManifestEntry(indexManifests(dir), [&](const ManifestEntry& e) {
    bool ok = true;
    for (const ManifestFile& f : e.files)
      ok = ok && sha256OfFile((fs::path(dir) / f.path).string()) == f.sha256;
    if (ok) ++complete[e.frame];
  });
  std::set<uint64_t> done;
  for (const auto& [frame, count] : complete)
    if (count == products) done.insert(frame);
  return done;
}

// renderSimulation: the colour image of every render product, one file per
// physics step, under <out>/simulation/<camera>/.
void writeSimulationFrame(const Stage& stage, Renderer& renderer, const std::vector<std::string>& cameraPaths,
                          const std::vector<std::string>& productNames, const std::string& outDir, uint64_t index) {
  RenderList list = buildRenderList(stage);
  char name[32];
  std::snprintf(name, sizeof name, "rgb_%06llu.png", static_cast<unsigned long long>(index));
  for (size_t product = 0; product < cameraPaths.size(); ++product)
    for (size_t c = 0; c < list.cameras.size(); ++c) {
      if (list.cameras[c].path != cameraPaths[product]) continue;
      FramePasses passes;
      renderer.render(list, c, passes, PassSelection::colourOnly());
      std::vector<uint8_t> png = encodePng(passes.rgba, uint32_t(passes.width), uint32_t(passes.height),
                                           PngPixels::Rgba8, PngOptions::renderedImage());
      writeFiles(outDir, {{"simulation/" + productNames[product] + "/" + name, std::move(png)}});
    }
}

// True when more than 99.5 % of the pixels are black (every channel below
// 3/255): the frame shows nothing. Stops as soon as enough pixels are lit,
// so a frame that shows something costs a few rows.
bool frameIsBlack(const std::vector<uint8_t>& rgba) {
  const size_t pixels = rgba.size() / 4;
  const size_t litAllowed = pixels / 200;  // 0.5 %
  size_t lit = 0;
  for (size_t i = 0; i < pixels; ++i) {
    const uint8_t* p = &rgba[4 * i];
    if (p[0] >= 3 || p[1] >= 3 || p[2] >= 3)
      if (++lit > litAllowed) return false;
  }
  return pixels > 0;
}

// The lights a frame had, for the black-frame warning.
std::string lightsOf(const RenderList& list) {
  if (list.lights.empty()) return "no light";
  std::string out = list.lights.size() == 1 ? "1 light (" : std::to_string(list.lights.size()) + " lights (";
  for (size_t i = 0; i < list.lights.size() && i < 4; ++i) out += (i ? ", " : "") + list.lights[i].path;
  return out + (list.lights.size() > 4 ? ", ...)" : ")");
}

// Render products: capture.cameras, or every camera of the stage; each is
// named after its camera prim.
std::vector<std::string> productCameras(const Scene& scene, const RenderList& list, const SourceLoc& sceneLoc) {
  std::vector<std::string> cameraPaths = scene.capture.get("cameras").get<std::vector<std::string>>();
  if (cameraPaths.empty())
    for (const RenderCamera& c : list.cameras) cameraPaths.push_back(c.path);
  if (cameraPaths.empty()) throw SceneError(sceneLoc, "the scene has no Camera prim to render from");
  return cameraPaths;
}

std::vector<std::string> productNamesOf(const std::vector<std::string>& cameraPaths, const SourceLoc& sceneLoc) {
  std::vector<std::string> names;
  std::set<std::string> seen;
  for (const std::string& p : cameraPaths) {
    std::string name(path::name(p));
    if (!seen.insert(name).second)
      throw SceneError(sceneLoc, "two cameras are named " + name + "; render products are named after the camera");
    names.push_back(name);
  }
  return names;
}

// The Lidar prims whose sweeps a writer writes: capture.lidars, or every
// Lidar prim of the stage. Listed sensors without such a writer, or a writer
// without a sensor, are errors rather than a silent nothing.
std::vector<std::string> capturedLidars(const Scene& scene, bool written, const SourceLoc& sceneLoc) {
  std::vector<std::string> paths = scene.capture.get("lidars").get<std::vector<std::string>>();
  const SourceLoc* listedAt = scene.capture.locOf("lidars");
  if (!written) {
    if (!paths.empty())
      throw SceneError(listedAt ? *listedAt : sceneLoc,
                       "capture.lidars: no writer writes LiDAR sweeps; set `lidar: true` on a BasicWriter");
    return {};
  }
  if (paths.empty())
    scene.stage.traverse([&](const Prim& p) {
      if (p.type() == PrimType::Lidar) paths.push_back(p.path());
    });
  if (paths.empty()) {
    const SourceLoc* at = nullptr;
    for (const WriterConfig& w : scene.writers)
      if (!at) at = w.options.locOf("lidar");
    throw SceneError(at ? *at : sceneLoc, "writer.lidar: the scene has no Lidar prim to scan with");
  }
  std::set<std::string> names;
  for (const std::string& p : paths)
    if (!names.insert(std::string(path::name(p))).second)
      throw SceneError(listedAt ? *listedAt : sceneLoc,
                       "two Lidar prims are named " + std::string(path::name(p)) + "; sweep files are named after the sensor");
  return paths;
}

}  // namespace

// A run with pixels, in the order it happens: prepare (products, writers,
// folder, renderer), then per iteration the pre-roll and the timeline, per
// frame one render of every product whose read-back overlaps the next draw,
// each collected product submitted to the write pool; then finish. In
// capture mode (DatasetCapture) the caller drives the stage and says when
// a frame is taken.
class DatasetRun {
 public:
  DatasetRun(LoadedScene& loaded, const DatasetRunOptions& options, bool captureMode = false)
      : loaded_(loaded), scene_(loaded.scene), options_(options), plan_(options.plan),
        sceneLoc_{loaded.scene.sourcePath, 0, 0}, original_(loaded.scene.stage), capture_(captureMode) {}

  DatasetRunResult run();
  void prepareCapture() { prepare(); }
  void captureFrame();
  DatasetRunResult finishCapture();
  uint64_t captured() const { return captured_; }

 private:
  void prepare();
  void startRenderer(const RenderList& initialList);
  void runIteration(uint64_t iteration);
  void renderFrame(Renderer& renderer, uint64_t frame, uint64_t iteration, uint64_t first,
                   std::shared_ptr<const RenderList> previous, std::shared_ptr<const RenderList> current);
  void resolveNext(std::shared_ptr<const RenderList> next);
  void renderProduct(Renderer& renderer, const std::shared_ptr<const FrameScene>& scene, uint64_t frame,
                     uint64_t iteration, uint64_t first, size_t product);
  void collectPending();
  void submit(std::shared_ptr<ProductFrame> frame);
  void keepFinishedFramesAfterFailure();
  void finish();
  void castLidars(FrameScene& scene, uint64_t frame);
  void warnOnce(bool& said, const std::string& message);
  void checkLabels();
  void checkBlack(const ProductFrame& frame);

  LoadedScene& loaded_;
  Scene& scene_;
  const DatasetRunOptions& options_;
  const FramePlan& plan_;
  const SourceLoc sceneLoc_;
  const Clock::time_point start_ = Clock::now();
  std::vector<std::string> cameraPaths_, productNames_;
  std::vector<std::string> lidarPaths_;  // sensors swept each frame
  std::unique_ptr<LidarCaster> lidarCaster_;
  RenderSettings settings_;
  RunInfo info_;
  DatasetRunResult result_;
  std::set<uint64_t> finished_;  // --resume: frames kept from an earlier run
  std::set<uint64_t> sheetFrames_;
  unsigned threads_ = 1;
  WriterSet writers_;
  uint64_t runFiles_ = 0;  // files written once per run (metadata.txt, ...)
  bool keepRadiance_ = false;
  PassSelection passes_;
  std::unique_ptr<ManifestWriter> manifest_;
  std::unique_ptr<FrameEncoder> encoder_;
  std::unique_ptr<RendererBringUp> bringUp_;
  // The colour of every product: the rasterizer's, or traced (on `threads`
  // cores, or the GPU) while the pool encodes the frames before it.
  std::unique_ptr<ColorRenderer> color_;
  // color_ while it is being made, on a helper thread during the pre-roll
  // (colorRenderer() takes it over).
  std::future<std::unique_ptr<ColorRenderer>> colorMaking_;
  ColorRenderer& colorRenderer();
  std::unique_ptr<Progress> progress_;
  std::unique_ptr<ChangeRecorder> recorder_;
  const Stage original_;
  const bool capture_;
  uint64_t captured_ = 0;
  std::shared_ptr<const RenderList> previousCapture_;
  // A product drawn and queued for read-back, waiting to be collected.
  struct Pending {
    std::shared_ptr<ProductFrame> frame;
    int slot = 0;
  };
  std::optional<Pending> pending_;
  // Motion: the last rendered frame, waiting for the next frame's poses,
  // and its products collected meanwhile (in order).
  std::shared_ptr<FrameScene> awaitingNext_;
  std::vector<std::shared_ptr<ProductFrame>> held_;
  uint64_t queued_ = 0, sequence_ = 0;
  bool saidNoLabels_ = false, saidBlack_ = false;
  // Declared last: when a write fails and the run unwinds, the pool's
  // destructor joins the workers before what their jobs refer to goes.
  std::unique_ptr<WritePool> pool_;
};

void DatasetRun::prepare() {
  RenderList initialList = buildRenderList(scene_.stage);
  cameraPaths_ = productCameras(scene_, initialList, sceneLoc_);
  productNames_ = productNamesOf(cameraPaths_, sceneLoc_);
  settings_ = renderSettingsFor(scene_, options_.render);
  // Only BOP's models read what behaviors spawn; other runs skip the asset checks it takes.
  const bool bop = std::any_of(scene_.writers.begin(), scene_.writers.end(),
                               [](const WriterConfig& w) { return w.type == "BopWriter"; });
  writers_ = makeWriters(scene_.writers,
                         WriterSetup{productNames_, options_.seed, settings_.width, settings_.height, &scene_.stage,
                                     &loaded_.assets,
                                     bop ? meshesSpawnedByBuiltins(scene_.stage, loaded_.assets)
                                         : std::vector<LabelledMesh>{}},
                         sceneLoc_);
  keepRadiance_ = writers_.needs.radiance;
  lidarPaths_ = capturedLidars(scene_, writers_.needs.lidar, sceneLoc_);
  if (keepRadiance_ && settings_.mode != RenderMode::PathTraced) {
    const SourceLoc* at = nullptr;
    for (const WriterConfig& w : scene_.writers)
      if (!at) at = w.options.locOf("hdr_color");
    throw SceneError(at ? *at : sceneLoc_,
                     "writer.hdr_color: linear radiance comes from the path tracer; set render.mode: pathtraced "
                     "(or --render-mode pathtraced)");
  }

  info_.sceneHash = fileHash(scene_.sourcePath);
  info_.seed = options_.seed;
  info_.iterations = capture_ ? 1 : plan_.iterations;
  info_.framesPerIteration = capture_ ? 0 : plan_.framesPerIteration;  // capture: counted at the end
  info_.width = settings_.width;
  info_.height = settings_.height;
  info_.products = productNames_;
  info_.cocoFile = writers_.parts.cocoFile;
  info_.cocoTaxonomy = writers_.parts.cocoTaxonomy;
  info_.bopSplit = writers_.parts.bopSplit;
  info_.contactSheet = scene_.capture.get("contact_sheet").get<bool>();
  info_.inputs = collectRunInputs(loaded_);
  prepareOutputFolder(options_.outDir, info_,
                      FolderPolicy{options_.overwrite, options_.resume, plan_.shard.sharded(), plan_.shard.tag()});
  result_.info = info_;
  if (options_.resume) {
    removeStaleTemporaries(options_.outDir);
    finished_ = finishedFrames(options_.outDir, productNames_.size());
  }
  for (const auto& writer : writers_.writers) {
    const std::vector<OutputFile> files = writer->runFiles();
    writeFiles(options_.outDir, files);
    runFiles_ += files.size();
  }
  manifest_ = std::make_unique<ManifestWriter>(
      (fs::path(options_.outDir) /
       (plan_.shard.sharded() ? "manifest." + plan_.shard.tag() + ".jsonl" : "manifest.jsonl"))
          .string(),
      options_.outDir);
  encoder_ = std::make_unique<FrameEncoder>(writers_.writers, writers_.needs, *manifest_, options_.outDir);

  threads_ = options_.threads ? options_.threads : std::max(1u, std::thread::hardware_concurrency());
  passes_ = writers_.needs.passes();
  if (!lidarPaths_.empty()) lidarCaster_ = std::make_unique<LidarCaster>(loaded_.assets, threads_);
  startRenderer(initialList);
  const SourceLoc* tracerAt = scene_.render.locOf("pathtracer");
  RendererBringUp& bringUp = *bringUp_;
  // Made on a helper thread while the pre-roll runs, like the rasterizer:
  // the GPU tracer's EGL context and first kernel take 0.06-0.1 s on an
  // H100 machine (more where the driver's shader cache is cold). A failure
  // to make it (render.pathtracer: gpu where it cannot run) is reported
  // when the first frame needs it.
  ColorRendererInputs inputs{loaded_.assets, settings_, int(threads_),
                             [&bringUp]() -> GlContext& { return bringUp.context(); }, anyCalibratedLens(initialList)};
  colorMaking_ = std::async(std::launch::async, [inputs, setting = tracerAt ? *tracerAt : sceneLoc_] {
    return makeColorRenderer(inputs, setting);
  });
  sheetFrames_ = info_.contactSheet ? contactSheetFrames(info_.frames()) : std::set<uint64_t>{};
  const uint64_t owned = capture_ ? 0 : plan_.ownedEnd() - plan_.ownedBegin();
  for (uint64_t f = plan_.ownedBegin(); f < plan_.ownedEnd(); ++f) result_.resumedFrames += finished_.count(f);
  progress_ = std::make_unique<Progress>(owned - result_.resumedFrames, options_.progress);
  // At most the pool's queue plus its workers plus two read-back slots of
  // frames are alive at once; their buffers circulate.
  pool_ = std::make_unique<WritePool>(threads_, 2 * size_t(threads_));
}

// The renderer starts on a helper thread; with a pre-roll to hide behind,
// it also draws the stage as loaded once to compile its shader variants.
void DatasetRun::startRenderer(const RenderList& initialList) {
  std::optional<WarmUpFrame> warmUp;
  if (!scene_.events.empty())
    for (size_t c = 0; c < initialList.cameras.size(); ++c)
      if (initialList.cameras[c].path == cameraPaths_.front()) {
        warmUp = WarmUpFrame{initialList, c, passes_, std::nullopt};
        if (writers_.needs.coverage) {
          warmUp->coverageGroups.emplace();
          for (const SemanticEntity& e : computeSemantics(scene_.stage, initialList, writers_.semanticTypes).entities)
            warmUp->coverageGroups->push_back(e.items);
        }
        break;
      }
  Scene& scene = scene_;
  const RenderOverrides& overrides = options_.render;
  bringUp_ = std::make_unique<RendererBringUp>([&scene, &overrides] { return glContextFor(scene, overrides); },
                                               loaded_.assets, rasterSettings(settings_), std::move(warmUp));
}

void DatasetRun::runIteration(uint64_t iteration) {
  const uint64_t first = iteration * plan_.framesPerIteration;
  const uint64_t begin = std::max(first, plan_.ownedBegin());
  const uint64_t end = std::min(first + plan_.framesPerIteration, plan_.ownedEnd());
  bool work = false;
  for (uint64_t f = begin; f < end; ++f) work = work || !finished_.count(f);
  if (!work) return;  // not ours, or all done: no pre-roll either

  scene_.stage = original_;
  RunBehaviorSetup setup;
  BehaviorContext behaviorContext = behaviorContextFor(loaded_, options_.seed, setup);
  behaviorContext.iteration = iteration;
  behaviorContext.firstFrame = first;
  behaviorContext.hooks.simulationFrame = [this](const Stage& stage, const std::string&, uint64_t) {
    writeSimulationFrame(stage, bringUp_->renderer(), cameraPaths_, productNames_, options_.outDir,
                         result_.simulationFrames++);
  };
  BehaviorRuntime runtime(scene_.stage, loaded_.registry, behaviorContext);
  runtime.init();
  auto t0 = Clock::now();
  runPreroll(scene_.events, runtime);
  result_.stages.preroll += since(t0);
  ++result_.iterationsRun;
  for (nlohmann::ordered_json& report : setup.reports) {
    report["iteration"] = iteration;
    result_.settle.push_back(report);
  }
  if (!options_.saveStagePath.empty() && result_.iterationsRun == 1) saveStageAfterPreroll(loaded_, options_.saveStagePath);
  if (!options_.recordPath.empty() && !recorder_) recorder_ = std::make_unique<ChangeRecorder>(options_.recordPath, original_);
  if (recorder_) recorder_->recordPreroll(setup.reports, scene_.stage);

  runtime.play();
  Renderer& renderer = bringUp_->renderer();
  // Motion annotators need the poses of the frames around each one: every
  // stepped frame's render list is kept, and the frame after the shard's
  // last is stepped too when the iteration goes on.
  const bool motion = writers_.needs.motion;
  const uint64_t stepEnd = motion ? std::min(first + plan_.framesPerIteration, end + 1) : end;
  std::shared_ptr<const RenderList> previous;
  for (uint64_t frame = first; frame < stepEnd; ++frame) {
    t0 = Clock::now();
    runtime.update();
    result_.stages.behaviors += since(t0);
    std::shared_ptr<const RenderList> current;
    if (motion) {
      current = std::make_shared<const RenderList>(buildRenderList(scene_.stage));
      resolveNext(current);
    }
    if (frame < begin || frame >= end || finished_.count(frame)) {  // stepped, not rendered
      previous = current;
      continue;
    }
    if (recorder_) recorder_->recordFrame(frame, runtime.timeline().time(), scene_.stage);
    if (!saidNoLabels_) checkLabels();
    renderFrame(renderer, frame, iteration, first, previous, current);
    previous = current;
  }
  if (motion) resolveNext(nullptr);  // the iteration's last frame has no next
  runtime.stop();
  if (recorder_) recorder_->recordStop(scene_.stage);
  runtime.destroy();
}

void DatasetRun::renderFrame(Renderer& renderer, uint64_t frame, uint64_t iteration, uint64_t first,
                             std::shared_ptr<const RenderList> previous, std::shared_ptr<const RenderList> current) {
  // What every render product of this frame shares, read by the pool.
  auto scene = std::make_shared<FrameScene>();
  scene->list = current ? *current : buildRenderList(scene_.stage);
  scene->semantics = computeSemantics(scene_.stage, scene->list, writers_.semanticTypes);
  scene->itemBounds.reserve(scene->list.items.size());
  for (const RenderItem& item : scene->list.items) scene->itemBounds.push_back(renderer.meshBounds(item));
  scene->previous = std::move(previous);
  scene->nextKnown = !writers_.needs.motion;
  if (lidarCaster_) castLidars(*scene, frame);
  if (writers_.needs.motion) awaitingNext_ = scene;
  for (size_t product = 0; product < cameraPaths_.size(); ++product)
    renderProduct(renderer, scene, frame, iteration, first, product);
  log::debug("frame " + std::to_string(frame) + " rendered");
  ++result_.frames;
  progress_->update(result_.frames);
}

// Every captured sensor's sweep of this frame, at the frame's poses (the
// sweep is instantaneous: docs/scene-format.md, "Lidar"), cast on the run's
// threads while the pool encodes earlier frames.
void DatasetRun::castLidars(FrameScene& scene, uint64_t frame) {
  const auto start = Clock::now();
  lidarCaster_->setScene(scene.list);
  scene.lidars.resize(lidarPaths_.size());
  for (size_t i = 0; i < lidarPaths_.size(); ++i) {
    const Prim* prim = scene_.stage.find(lidarPaths_[i]);
    if (!prim || prim->type() != PrimType::Lidar) throw RunError("Lidar " + lidarPaths_[i] + " is gone");
    // A behavior may have changed the sensor since the scene was checked.
    if (const auto problems = lidarProblems(*prim); !problems.empty())
      throw RunError("frame " + std::to_string(frame) + ": " + prim->path() + "." + problems.front().attribute + ": " +
                     problems.front().message);
    LidarSweep& sweep = scene.lidars[i];
    sweep.path = lidarPaths_[i];
    sweep.preset = prim->getString("preset");
    lidarCaster_->cast(lidarPatternOf(*prim), scene_.stage.worldMatrix(*prim), scene.list.metersPerUnit,
                       lidarSeed(options_.seed, sweep.path, frame), sweep);
  }
  result_.stages.render += since(start);
}

// The frame waiting for its successor's poses gets them (null: it is the
// iteration's last), and its products collected meanwhile go to the pool.
void DatasetRun::resolveNext(std::shared_ptr<const RenderList> next) {
  if (!awaitingNext_) return;
  awaitingNext_->next = std::move(next);
  awaitingNext_->nextKnown = true;
  awaitingNext_.reset();
  for (auto& frame : held_) submit(std::move(frame));
  held_.clear();
}

void DatasetRun::renderProduct(Renderer& renderer, const std::shared_ptr<const FrameScene>& scene, uint64_t frame,
                               uint64_t iteration, uint64_t first, size_t product) {
  const RenderList& list = scene->list;
  size_t cameraIndex = list.cameras.size();
  for (size_t c = 0; c < list.cameras.size(); ++c)
    if (list.cameras[c].path == cameraPaths_[product]) cameraIndex = c;
  if (cameraIndex == list.cameras.size()) throw RunError("camera " + cameraPaths_[product] + " is gone");
  auto job = std::make_shared<ProductFrame>();
  job->frame = frame;
  job->iteration = iteration;
  job->frameInIteration = frame - first;
  job->product = product;
  job->cameraIndex = cameraIndex;
  job->scene = scene;
  job->camera = list.cameras[cameraIndex];
  job->metersPerUnit = list.metersPerUnit;
  job->passes = encoder_->spareFrames.take();
  auto renderStart = Clock::now();
  // Draw this product and start its read-back; while the GPU works,
  // collect the previous product (its read-back is done by now) and
  // hand it to the pool.
  const int slot = int(queued_++ & 1);
  // Sheet frames also read the ids back: their boxes come from them.
  job->toSheet = product == 0 && sheetFrames_.count(frame);
  PassSelection productPasses = passes_;
  productPasses.ids = passes_.ids || job->toSheet;
  renderer.queue(list, cameraIndex, productPasses, slot);
  if (writers_.needs.coverage) {
    job->hasMasks = true;
    job->masks = encoder_->spareMasks.take();
    std::vector<std::vector<size_t>> groups;
    for (const SemanticEntity& e : scene->semantics.entities) groups.push_back(e.items);
    renderer.queueCoverage(list, cameraIndex, groups, slot);
  }
  // The colour too (a path tracer's on the GPU works while the previous product is collected).
  colorRenderer().queue(list, cameraIndex, frameSampleSeed(options_.seed, frame, product), keepRadiance_, slot);
  collectPending();
  pending_ = Pending{job, slot};
  result_.stages.render += since(renderStart);
}

void DatasetRun::collectPending() {
  if (!pending_) return;
  // Taken out first: when collecting or submitting throws (a full disk
  // reported by the pool, say), the failure path must not collect it again.
  const Pending pending = std::move(*pending_);
  pending_.reset();
  Renderer& renderer = bringUp_->renderer();
  ProductFrame& frame = *pending.frame;
  renderer.collect(pending.slot, frame.passes);
  if (frame.hasMasks) renderer.collectCoverage(pending.slot, frame.masks);
  // Timed with the render stage around collectPending()'s callers.
  colorRenderer().collect(pending.slot, frame.passes);
  if (!saidBlack_) checkBlack(frame);
  if (frame.scene->nextKnown) submit(pending.frame);
  else held_.push_back(pending.frame);  // until the next frame's poses are known
}

void DatasetRun::warnOnce(bool& said, const std::string& message) {
  if (said) return;
  said = true;
  log::warn(message);
  result_.warnings.push_back(message);
}

// Boxes and segmentation come from semantic labels: a stage without any,
// after the pre-roll has spawned what it spawns, gives empty ones.
void DatasetRun::checkLabels() {
  if (!writers_.needs.labels) {
    saidNoLabels_ = true;
    return;
  }
  bool any = false;
  scene_.stage.traverse([&](const Prim& p) { any = any || !p.semantics().empty(); });
  if (any) saidNoLabels_ = true;
  else
    warnOnce(saidNoLabels_, "no prim on the stage has a semantic label, so boxes and segmentation are empty; label "
                            "prims with `semantics: {class: NAME}` (YAML) or Isaac's semantics attributes (USD)");
}

void DatasetRun::checkBlack(const ProductFrame& frame) {
  if (!frameIsBlack(frame.passes.rgba)) return;
  warnOnce(saidBlack_, "frame " + std::to_string(frame.frame) + " of camera " + frame.camera.path +
                           " is black (over 99.5 % of its pixels); the stage had " + lightsOf(frame.scene->list) +
                           ": check the lights' intensity and placement, and what the camera faces");
}

ColorRenderer& DatasetRun::colorRenderer() {
  if (!color_) color_ = colorMaking_.get();
  return *color_;
}

// Hands a collected product to the pool.
void DatasetRun::submit(std::shared_ptr<ProductFrame> frame) {
  FrameEncoder* encoder = encoder_.get();
  pool_->submit([encoder, frame, sequence = sequence_++] { encoder->encode(*frame, sequence); });
}

// A failure (a behavior's exception, on_stop, a lost camera, a signal)
// keeps the frames finished before it: the one still in read-back is
// collected and every queued frame is written with its manifest line, so
// --resume continues from them; the contact sheet shows what exists.
// Frames still waiting for the next one's poses (motion) are not finished:
// --resume makes them again.
void DatasetRun::keepFinishedFramesAfterFailure() {
  try {
    collectPending();
  } catch (const std::exception& e) {
    log::warn(std::string("the frame being read back when the run failed is lost: ") + e.what());
  }
  try {
    pool_->finish();
    manifest_->flush();
    if (info_.contactSheet && !plan_.shard.sharded()) writeContactSheetOfFinishedFrames(options_.outDir, info_);
  } catch (const std::exception& e) {
    log::warn(std::string("while keeping the finished frames: ") + e.what());
  }
}

void DatasetRun::finish() {
  // The last product is collected here, not by a successor's
  // renderProduct(): its read-back and colour (a whole path-traced frame)
  // are render time too, or a one-frame run would report none of it.
  const auto renderStart = Clock::now();
  collectPending();
  result_.stages.render += since(renderStart);
  progress_->finish();
  GlContext& context = bringUp_->context();
  result_.renderer = context.rendererName();
  result_.backend = context.backend();
  result_.device = context.device();
  if (color_) result_.colorDevice = color_->device().empty() ? "rasterizer (" + context.device() + ")" : color_->device();
  bringUp_->retireInBackground();
  if (!capture_) scene_.stage = original_;
  if (recorder_) recorder_->close();
  pool_->finish();
  manifest_->flush();
  uint64_t written = encoder_->datasetFiles + runFiles_ + result_.simulationFrames * cameraPaths_.size();
  if (!plan_.shard.sharded()) {
    written += finalizeDataset(options_.outDir, info_).files;
    result_.finalized = true;
  }
  result_.files = written;
  result_.stages.encodeWrite = double(encoder_->encodeMicros) / 1e6;
  result_.stages.annotate = double(encoder_->annotateMicros) / 1e6;
  result_.seconds = since(start_);
}

DatasetRunResult DatasetRun::run() {
  prepare();
  try {
    for (uint64_t iteration = 0; iteration < plan_.iterations; ++iteration) runIteration(iteration);
  } catch (...) {
    keepFinishedFramesAfterFailure();
    throw;
  }
  finish();
  return result_;
}

void DatasetRun::captureFrame() {
  const uint64_t frame = captured_++;
  if (!saidNoLabels_) checkLabels();
  std::shared_ptr<const RenderList> current;
  if (writers_.needs.motion) {
    current = std::make_shared<const RenderList>(buildRenderList(scene_.stage));
    resolveNext(current);
  }
  try {
    renderFrame(bringUp_->renderer(), frame, 0, 0, previousCapture_, current);
  } catch (...) {
    keepFinishedFramesAfterFailure();
    throw;
  }
  previousCapture_ = std::move(current);
}

DatasetRunResult DatasetRun::finishCapture() {
  if (writers_.needs.motion) resolveNext(nullptr);  // the last frame has no next
  info_.framesPerIteration = captured_;
  result_.info = info_;
  recordRunInfo(options_.outDir, info_);
  finish();
  return result_;
}

DatasetRunResult runDataset(LoadedScene& loaded, const DatasetRunOptions& options) {
  return DatasetRun(loaded, options).run();
}

DatasetCapture::DatasetCapture(LoadedScene& loaded, DatasetRunOptions options)
    : options_(std::make_unique<DatasetRunOptions>(std::move(options))),
      run_(std::make_unique<DatasetRun>(loaded, *options_, true)) {
  run_->prepareCapture();
}

DatasetCapture::~DatasetCapture() = default;

void DatasetCapture::capture() { run_->captureFrame(); }

uint64_t DatasetCapture::frames() const { return run_->captured(); }

DatasetRunResult DatasetCapture::finish() { return run_->finishCapture(); }

}  // namespace sdg
