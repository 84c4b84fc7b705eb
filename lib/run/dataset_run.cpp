#include "run/dataset_run.h"

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <memory>
#include <set>
#include <thread>

#include "behavior/runtime.h"
#include "core/diagnostics.h"
#include "core/file_io.h"
#include "core/log.h"
#include "core/recycler.h"
#include "render/raster/renderer.h"
#include "run/dataset_finalize.h"
#include "run/color_renderer_choice.h"
#include "run/preroll.h"
#include "run/progress.h"
#include "run/record.h"
#include "run/renderer_bringup.h"
#include "run/run_inputs.h"
#include "run/scene_setup.h"
#include "stage/path.h"
#include "writers/basic_writer.h"
#include "writers/coco_writer.h"
#include "writers/contact_sheet.h"
#include "writers/png_encoder.h"
#include "writers/manifest.h"
#include "writers/write_pool.h"

namespace sdg {
namespace fs = std::filesystem;

namespace {

struct FrameShared {
  RenderList list;
  FrameSemantics semantics;
  std::vector<Eigen::AlignedBox3f> itemBounds;
};

// A product drawn and queued for read-back, waiting to be collected.
struct PendingProduct {
  std::shared_ptr<ProductFrame> job;
  std::shared_ptr<FrameShared> shared;
  std::shared_ptr<Renderer::CoverageMasks> masks;  // null: the writer needs no coverage
  size_t cameraIndex = 0;
  bool toSheet = false;
  int slot = 0;
};

// A frame's thumbnail with the tight box (visible pixels) and class of
// every visible entity.
std::vector<uint8_t> sheetTile(uint64_t frame, const FramePasses& passes, const FrameSemantics& semantics,
                               const std::vector<Box2D>& tight) {
  std::vector<SheetBox> boxes;
  for (const Box2D& b : tight) {
    const LabelSet& labels = semantics.entities[b.entity].labels;
    auto cls = labels.find("class");
    std::string label = cls != labels.end() ? cls->second : labels.empty() ? "" : labels.begin()->second;
    boxes.push_back({b.xMin, b.yMin, b.xMax, b.yMax, b.semanticId, label});
  }
  return contactSheetTile(frame, passes.rgba, passes.width, passes.height, boxes);
}

// Frames whose every render product the folder's manifests list with files
// that still match their SHA-256 (what --resume may keep).
std::set<uint64_t> finishedFrames(const std::string& dir, size_t products) {
  std::map<uint64_t, size_t> complete;
  for (const ManifestEntry& e : readManifests(dir)) {
    bool ok = true;
    for (const ManifestFile& f : e.files)
      ok = ok && sha256OfFile((fs::path(dir) / f.path).string()) == f.sha256;
    if (ok) ++complete[e.frame];
  }
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

}  // namespace

DatasetRunResult runDataset(LoadedScene& loaded, const DatasetRunOptions& options) {
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  const auto start = Clock::now();
  Scene& scene = loaded.scene;
  const SourceLoc sceneLoc{scene.sourcePath, 0, 0};
  const WriterConfig* writerConfig = nullptr;
  const WriterConfig* cocoConfig = nullptr;
  for (const WriterConfig& w : scene.writers) (w.type == "BasicWriter" ? writerConfig : cocoConfig) = &w;
  if (!writerConfig && !cocoConfig)
    throw SceneError(sceneLoc, "the scene has no writer; add e.g. `writer: {type: BasicWriter, rgb: true}`");
  // COCO alone still needs its images: they are written as BasicWriter's rgb.
  WriterConfig imagesOnly{"BasicWriter", OptionSet(findWriterType("BasicWriter")->options), sceneLoc};
  imagesOnly.options.set("rgb", Value::makeBool(true));
  if (!writerConfig) writerConfig = &imagesOnly;

  // Render products: capture.cameras, or every camera of the stage.
  RenderList initialList = buildRenderList(scene.stage);
  std::vector<std::string> cameraPaths = scene.capture.get("cameras").get<std::vector<std::string>>();
  if (cameraPaths.empty())
    for (const RenderCamera& c : initialList.cameras) cameraPaths.push_back(c.path);
  if (cameraPaths.empty()) throw SceneError(sceneLoc, "the scene has no Camera prim to render from");
  std::vector<std::string> productNames;
  std::set<std::string> seen;
  for (const std::string& p : cameraPaths) {
    std::string name(path::name(p));
    if (!seen.insert(name).second)
      throw SceneError(sceneLoc, "two cameras are named " + name + "; render products are named after the camera");
    productNames.push_back(name);
  }

  const FramePlan& plan = options.plan;
  const RenderSettings settings = renderSettingsFor(scene, options.render);
  RunInfo info;
  info.sceneHash = fileHash(scene.sourcePath);
  info.seed = options.seed;
  info.iterations = plan.iterations;
  info.framesPerIteration = plan.framesPerIteration;
  info.width = settings.width;
  info.height = settings.height;
  info.products = productNames;
  if (cocoConfig) {
    const auto& types = cocoConfig->options.get("semantic_types").get<std::vector<std::string>>();
    info.cocoFile = cocoConfig->options.getString("file_name");
    info.cocoTaxonomy = types.empty() ? std::string("class") : types.front();
  }
  info.contactSheet = scene.capture.get("contact_sheet").get<bool>();
  info.inputs = collectRunInputs(loaded);
  prepareOutputFolder(options.outDir, info,
                      FolderPolicy{options.overwrite, options.resume, plan.shard.sharded(), plan.shard.tag()});
  DatasetRunResult result;
  result.info = info;
  std::set<uint64_t> finished;
  if (options.resume) {
    removeStaleTemporaries(options.outDir);
    finished = finishedFrames(options.outDir, productNames.size());
  }
  BasicWriter writer(writerConfig->options, productNames, options.seed);
  const bool keepRadiance = writerConfig->options.getBool("hdr_color");
  if (keepRadiance && settings.mode != RenderMode::PathTraced) {
    const SourceLoc* at = writerConfig->options.locOf("hdr_color");
    throw SceneError(at ? *at : sceneLoc,
                     "writer.hdr_color: linear radiance comes from the path tracer; set render.mode: pathtraced "
                     "(or --render-mode pathtraced)");
  }
  writeFiles(options.outDir, writer.metadataFiles());
  ManifestWriter manifest(
      (fs::path(options.outDir) / (plan.shard.sharded() ? "manifest." + plan.shard.tag() + ".jsonl" : "manifest.jsonl"))
          .string());

  const unsigned threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
  const auto& semanticTypes = (cocoConfig && writerConfig == &imagesOnly ? cocoConfig : writerConfig)
                                  ->options.get("semantic_types")
                                  .get<std::vector<std::string>>();
  const bool annotations = writer.needsAnnotations() || cocoConfig != nullptr;
  PassSelection passes = writer.passesNeeded();
  passes.ids = passes.ids || cocoConfig != nullptr;  // COCO masks come from the ids
  const bool coverage = writer.needsCoverage() || cocoConfig != nullptr;
  // The renderer starts on a helper thread; with a pre-roll to hide behind,
  // it also draws the stage as loaded once to compile its shader variants.
  std::optional<WarmUpFrame> warmUp;
  if (!scene.events.empty())
    for (size_t c = 0; c < initialList.cameras.size(); ++c)
      if (initialList.cameras[c].path == cameraPaths.front()) {
        warmUp = WarmUpFrame{initialList, c, passes, std::nullopt};
        if (coverage) {
          warmUp->coverageGroups.emplace();
          for (const SemanticEntity& e : computeSemantics(scene.stage, initialList, semanticTypes).entities)
            warmUp->coverageGroups->push_back(e.items);
        }
        break;
      }
  RendererBringUp bringUp([&scene, &options] { return glContextFor(scene, options.render); }, loaded.assets, settings,
                          std::move(warmUp));
  // The colour of every product: the rasterizer's, or traced on `threads`
  // cores while the pool encodes the frames before it.
  const SourceLoc* tracerAt = scene.render.locOf("pathtracer");
  std::unique_ptr<ColorRenderer> color =
      makeColorRenderer({loaded.assets, settings, int(threads), [&bringUp]() -> GlContext& { return bringUp.context(); }},
                        tracerAt ? *tracerAt : sceneLoc);
  const std::set<uint64_t> sheetFrames = info.contactSheet ? contactSheetFrames(info.frames()) : std::set<uint64_t>{};
  std::atomic<uint64_t> files{0};
  std::atomic<uint64_t> encodeMicros{0};
  std::atomic<uint64_t> annotateMicros{0};
  uint64_t owned = plan.ownedEnd() - plan.ownedBegin(), sequence = 0;
  for (uint64_t f = plan.ownedBegin(); f < plan.ownedEnd(); ++f) result.resumedFrames += finished.count(f);
  Progress progress(owned - result.resumedFrames, options.progress);
  std::unique_ptr<ChangeRecorder> recorder;
  const Stage original = scene.stage;
  // At most the pool's queue plus its workers plus two read-back slots of
  // frames are alive at once; their buffers circulate.
  Recycler<FramePasses> spareFrames;
  Recycler<Renderer::CoverageMasks> spareMasks;
  // Declared after everything its jobs refer to: when a write fails and the
  // run unwinds, the pool's destructor joins the workers before those go.
  WritePool pool(threads, 2 * size_t(threads));
  // Hands a collected product to the pool: annotators, COCO fragment,
  // thumbnail, encoding, durable writes, then its manifest line.
  auto submit = [&](const PendingProduct& p) {
    auto job = p.job;
    auto shared = p.shared;
    auto masks = p.masks;
    const size_t cameraIndex = p.cameraIndex;
    const bool toSheet = p.toSheet;
    const std::string outDir = options.outDir;
    pool.submit([job, shared, masks, cameraIndex, toSheet, annotations, cocoConfig, &writer, &manifest, &info,
                 outDir, &files, &encodeMicros, &annotateMicros, &spareFrames, &spareMasks, seq = sequence++] {
      auto jobStart = Clock::now();
      const FrameSemantics& semantics = shared->semantics;
      std::vector<EntityCoverage> entityCoverage;
      if (masks) {
        std::vector<Renderer::Coverage> coverage;
        Renderer::coverageOf(*masks, coverage);
        spareMasks.give(std::move(*masks));
        for (const auto& c : coverage) entityCoverage.push_back({c.pixels, c.xMin, c.yMin, c.xMax, c.yMax});
      }
      // Sheet frames need the tight boxes even when the writer does not.
      if (annotations || toSheet)
        annotate(AnnotatorInputs{job->passes, shared->list, cameraIndex, semantics, entityCoverage, shared->itemBounds},
                 job->annotations);
      for (const SemanticEntity& e : semantics.entities) {
        job->entityPaths.push_back(e.primPath);
        job->entityLabels.push_back(e.labels);
      }
      job->semanticLabels = semantics.semanticLabels;
      job->renderIdPaths.assign(semantics.entityOfRenderId.size(), "");
      for (const RenderItem& item : shared->list.items)
        if (item.instanceId < job->renderIdPaths.size()) job->renderIdPaths[item.instanceId] = item.primPath;
      // Parts of the frame beside the dataset's own files, tracked by the manifest with them.
      std::vector<OutputFile> parts;
      if (cocoConfig) {
        std::string text = cocoFragment(writer.rgbPath(job->frame, job->product), job->passes.width,
                                        job->passes.height, job->annotations, semantics, info.cocoTaxonomy);
        parts.push_back({cocoFragmentPath(job->frame, job->product), std::vector<uint8_t>(text.begin(), text.end())});
      }
      if (toSheet)
        parts.push_back(
            {contactSheetTilePath(job->frame), sheetTile(job->frame, job->passes, semantics, job->annotations.tight)});
      auto encodeStart = Clock::now();
      annotateMicros += uint64_t(std::chrono::duration_cast<std::chrono::microseconds>(encodeStart - jobStart).count());
      std::vector<OutputFile> encoded = writer.encode(*job);
      const size_t datasetFiles = encoded.size();  // the hidden parts are not counted
      for (OutputFile& part : parts) encoded.push_back(std::move(part));
      writeFilesDurably(outDir, encoded);
      ManifestEntry entry{job->frame, uint32_t(job->product), {}};
      for (const OutputFile& f : encoded) entry.files.push_back({f.path, f.bytes.size(), sha256Hex(f.bytes)});
      manifest.commit(seq, std::move(entry));
      files += datasetFiles;
      spareFrames.give(std::move(job->passes));
      encodeMicros +=
          uint64_t(std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - encodeStart).count());
    });
  };
  std::optional<PendingProduct> pending;
  uint64_t queued = 0;
  auto collectPending = [&] {
    if (!pending) return;
    Renderer& renderer = bringUp.renderer();
    renderer.collect(pending->slot, pending->job->passes);
    if (pending->masks) renderer.collectCoverage(pending->slot, *pending->masks);
    // Timed with the render stage around collectPending()'s callers.
    const ProductFrame& job = *pending->job;
    color->render(pending->shared->list, pending->cameraIndex, frameSampleSeed(options.seed, job.frame, job.product),
                  pending->job->passes, keepRadiance);
    submit(*pending);
    pending.reset();
  };


  // A failure (a behavior's exception, on_stop, a lost camera, a signal)
  // keeps the frames finished before it: the one still in read-back is
  // collected and every queued frame is written with its manifest line, so
  // --resume continues from them; the contact sheet shows what exists.
  try {
    for (uint64_t iteration = 0; iteration < plan.iterations; ++iteration) {
      const uint64_t first = iteration * plan.framesPerIteration;
      const uint64_t begin = std::max(first, plan.ownedBegin());
      const uint64_t end = std::min(first + plan.framesPerIteration, plan.ownedEnd());
      bool work = false;
      for (uint64_t f = begin; f < end; ++f) work = work || !finished.count(f);
      if (!work) continue;  // not ours, or all done: no pre-roll either

      scene.stage = original;
      RunBehaviorSetup setup;
      BehaviorContext behaviorContext = behaviorContextFor(loaded, options.seed, setup);
      behaviorContext.iteration = iteration;
      behaviorContext.firstFrame = first;
      behaviorContext.hooks.simulationFrame = [&](const Stage& stage, const std::string&, uint64_t) {
        writeSimulationFrame(stage, bringUp.renderer(), cameraPaths, productNames, options.outDir, result.simulationFrames++);
      };
      BehaviorRuntime runtime(scene.stage, loaded.registry, behaviorContext);
      runtime.init();
      auto t0 = Clock::now();
      runPreroll(scene.events, runtime);
      result.stages.preroll += since(t0);
      ++result.iterationsRun;
      for (nlohmann::ordered_json& report : setup.reports) {
        report["iteration"] = iteration;
        result.settle.push_back(report);
      }
      if (!options.saveStagePath.empty() && result.iterationsRun == 1) saveStageAfterPreroll(loaded, options.saveStagePath);
      if (!options.recordPath.empty() && !recorder) recorder = std::make_unique<ChangeRecorder>(options.recordPath, original);
      if (recorder) recorder->recordPreroll(setup.reports, scene.stage);

      runtime.play();
      Renderer& renderer = bringUp.renderer();
      for (uint64_t frame = first; frame < end; ++frame) {
        t0 = Clock::now();
        runtime.update();
        result.stages.behaviors += since(t0);
        if (frame < begin || finished.count(frame)) continue;  // stepped, not rendered
        if (recorder) recorder->recordFrame(frame, runtime.timeline().time(), scene.stage);
        // What every render product of this frame shares, read by the pool.
        auto shared = std::make_shared<FrameShared>();
        shared->list = buildRenderList(scene.stage);
        const RenderList& list = shared->list;
        shared->semantics = computeSemantics(scene.stage, list, semanticTypes);
        shared->itemBounds.reserve(list.items.size());
        for (const RenderItem& item : list.items) shared->itemBounds.push_back(renderer.meshBounds(item));
        std::vector<std::vector<size_t>> groups;
        for (const SemanticEntity& e : shared->semantics.entities) groups.push_back(e.items);

        for (size_t product = 0; product < cameraPaths.size(); ++product) {
          size_t cameraIndex = list.cameras.size();
          for (size_t c = 0; c < list.cameras.size(); ++c)
            if (list.cameras[c].path == cameraPaths[product]) cameraIndex = c;
          if (cameraIndex == list.cameras.size()) throw RunError("camera " + cameraPaths[product] + " is gone");
          auto job = std::make_shared<ProductFrame>();
          job->frame = frame;
          job->product = product;
          job->camera = list.cameras[cameraIndex];
          job->metersPerUnit = list.metersPerUnit;
          job->passes = spareFrames.take();
          auto renderStart = Clock::now();
          // Draw this product and start its read-back; while the GPU works,
          // collect the previous product (its read-back is done by now) and
          // hand it to the pool.
          const int slot = int(queued++ & 1);
          // Sheet frames also read the ids back: their boxes come from them.
          const bool toSheet = product == 0 && sheetFrames.count(frame);
          PassSelection productPasses = passes;
          productPasses.ids = passes.ids || toSheet;
          renderer.queue(list, cameraIndex, productPasses, slot);
          std::shared_ptr<Renderer::CoverageMasks> masks;
          if (coverage) {
            masks = std::make_shared<Renderer::CoverageMasks>(spareMasks.take());
            renderer.queueCoverage(list, cameraIndex, groups, slot);
          }
          collectPending();
          pending = PendingProduct{job, shared, masks, cameraIndex, toSheet, slot};
          result.stages.render += since(renderStart);
        }
        log::debug("frame " + std::to_string(frame) + " rendered");
        ++result.frames;
        progress.update(result.frames);
      }
      runtime.stop();
      if (recorder) recorder->recordStop(scene.stage);
      runtime.destroy();
    }
  } catch (...) {
    try {
      collectPending();
    } catch (const std::exception& e) {
      log::warn(std::string("the frame being read back when the run failed is lost: ") + e.what());
    }
    try {
      pool.finish();
      if (info.contactSheet && !plan.shard.sharded()) writeContactSheetOfFinishedFrames(options.outDir, info);
    } catch (const std::exception& e) {
      log::warn(std::string("while keeping the finished frames: ") + e.what());
    }
    throw;
  }
  collectPending();
  progress.finish();
  GlContext& context = bringUp.context();
  result.renderer = context.rendererName();
  result.backend = context.backend();
  result.device = context.device();
  bringUp.retireInBackground();
  scene.stage = original;
  if (recorder) recorder->close();
  pool.finish();
  uint64_t written = files + 1 + result.simulationFrames * cameraPaths.size();  // + metadata.txt, simulation
  if (!plan.shard.sharded()) {
    written += finalizeDataset(options.outDir, info).files;
    result.finalized = true;
  }
  result.files = written;
  result.stages.encodeWrite = double(encodeMicros) / 1e6;
  result.stages.annotate = double(annotateMicros) / 1e6;
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace sdg
