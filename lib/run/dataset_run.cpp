#include "run/dataset_run.h"

#include <chrono>
#include <filesystem>
#include <memory>
#include <set>
#include <thread>

#include "behavior/runtime.h"
#include "core/diagnostics.h"
#include "core/file_io.h"
#include "core/log.h"
#include "render/renderer.h"
#include "run/preroll.h"
#include "run/progress.h"
#include "run/record.h"
#include "run/scene_setup.h"
#include "stage/path.h"
#include "writers/basic_writer.h"
#include "writers/coco_writer.h"
#include "writers/contact_sheet.h"
#include "writers/png_encoder.h"
#include "writers/write_pool.h"

namespace sdg {
namespace fs = std::filesystem;

namespace {

void prepareOutputFolder(const std::string& dir, bool overwrite) {
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec)) throw SceneError(SourceLoc{"--out", 0, 0}, dir + " exists and is not a folder");
    if (!overwrite && !fs::is_empty(dir, ec))
      throw SceneError(SourceLoc{"--out", 0, 0},
                       dir + " is not empty; choose another folder or pass --overwrite to replace its files");
  }
  fs::create_directories(dir, ec);
  if (ec) throw RunError("cannot create the output folder " + dir + ": " + ec.message());
}

void writeFiles(const std::string& dir, const std::vector<OutputFile>& files) {
  for (const OutputFile& file : files) {
    fs::path path = fs::path(dir) / file.path;
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw RunError("cannot create " + path.parent_path().string() + ": " + ec.message());
    writeFileAtomic(path.string(), file.bytes);
  }
}

// A frame's thumbnail with the tight box and class of every visible entity.
void addToSheet(ContactSheet& sheet, uint64_t frame, const FramePasses& passes, const FrameSemantics& semantics,
                const std::vector<Renderer::Coverage>& coverage) {
  std::vector<SheetBox> boxes;
  for (size_t e = 0; e < semantics.entities.size() && e < coverage.size(); ++e) {
    const Renderer::Coverage& c = coverage[e];
    if (c.pixels == 0) continue;
    const LabelSet& labels = semantics.entities[e].labels;
    auto cls = labels.find("class");
    std::string label = cls != labels.end() ? cls->second : labels.empty() ? "" : labels.begin()->second;
    boxes.push_back({c.xMin, c.yMin, c.xMax, c.yMax, semantics.entities[e].semanticId, label});
  }
  sheet.add(frame, passes.rgba, passes.width, passes.height, boxes);
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
      renderer.render(list, c, passes);
      std::vector<uint8_t> png = encodePng(passes.rgba, uint32_t(passes.width), uint32_t(passes.height), PngPixels::Rgba8);
      writeFiles(outDir, {{"simulation/" + productNames[product] + "/" + name, std::move(png)}});
    }
}

}  // namespace

DatasetRunResult runDataset(LoadedScene& loaded, const DatasetRunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
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

  prepareOutputFolder(options.outDir, options.overwrite);
  BasicWriter writer(writerConfig->options, productNames, options.seed);
  writeFiles(options.outDir, writer.metadataFiles());

  const RenderSettings settings = renderSettingsFor(scene, options.width, options.height, options.subframes);
  std::unique_ptr<GlContext> context = createOsMesaContext();
  Renderer renderer(*context, loaded.assets, settings);

  RunBehaviorSetup setup;
  BehaviorContext behaviorContext = behaviorContextFor(loaded, options.seed, setup);
  DatasetRunResult result;
  behaviorContext.hooks.simulationFrame = [&](const Stage& stage, const std::string&, uint64_t) {
    writeSimulationFrame(stage, renderer, cameraPaths, productNames, options.outDir, result.simulationFrames++);
  };
  BehaviorRuntime runtime(scene.stage, loaded.registry, behaviorContext);
  runtime.init();
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  auto t0 = Clock::now();
  runPreroll(scene.events, runtime);
  result.stages.preroll = since(t0);
  result.settle = setup.reports;
  if (!options.saveStagePath.empty()) saveStageAfterPreroll(loaded, options.saveStagePath);
  std::unique_ptr<ChangeRecorder> recorder;
  if (!options.recordPath.empty()) {
    recorder = std::make_unique<ChangeRecorder>(options.recordPath, scene.stage);
    recorder->recordPreroll(setup.reports);
  }

  const unsigned threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
  WritePool pool(threads, 2 * size_t(threads));
  const auto& semanticTypes = (cocoConfig && writerConfig == &imagesOnly ? cocoConfig : writerConfig)
                                  ->options.get("semantic_types")
                                  .get<std::vector<std::string>>();
  std::unique_ptr<CocoWriter> coco;
  if (cocoConfig) {
    const auto& types = cocoConfig->options.get("semantic_types").get<std::vector<std::string>>();
    coco = std::make_unique<CocoWriter>(options.outDir, cocoConfig->options.getString("file_name"),
                                        types.empty() ? std::string("class") : types.front());
  }
  result.renderer = context->rendererName();
  result.backend = context->backend();
  std::atomic<uint64_t> files{0};
  std::atomic<uint64_t> encodeMicros{0};
  Progress progress(options.frames, options.progress);
  std::unique_ptr<ContactSheet> sheet;
  if (scene.capture.get("contact_sheet").get<bool>()) sheet = std::make_unique<ContactSheet>(options.frames);

  runtime.play();
  for (uint64_t frame = 0; frame < options.frames; ++frame) {
    t0 = Clock::now();
    runtime.update();
    result.stages.behaviors += since(t0);
    if (recorder) recorder->recordFrame(frame, runtime.timeline().time(), scene.stage);
    t0 = Clock::now();
    RenderList list = buildRenderList(scene.stage);
    FrameSemantics semantics = computeSemantics(scene.stage, list, semanticTypes);
    std::vector<Eigen::AlignedBox3f> itemBounds;
    itemBounds.reserve(list.items.size());
    for (const RenderItem& item : list.items) itemBounds.push_back(renderer.meshBounds(item));
    std::vector<std::vector<size_t>> groups;
    for (const SemanticEntity& e : semantics.entities) groups.push_back(e.items);

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
      auto renderStart = Clock::now();
      renderer.render(list, cameraIndex, job->passes);
      std::vector<Renderer::Coverage> coverage;
      const bool toSheet = sheet && product == 0 && sheet->wants(frame);
      if (writer.needsCoverage() || coco || toSheet) renderer.renderCoverage(list, cameraIndex, groups, coverage);
      result.stages.render += since(renderStart);
      auto annotateStart = Clock::now();
      std::vector<EntityCoverage> entityCoverage;
      for (const auto& c : coverage) entityCoverage.push_back({c.pixels, c.xMin, c.yMin, c.xMax, c.yMax});
      annotate(AnnotatorInputs{job->passes, list, cameraIndex, semantics, entityCoverage, itemBounds, scene.stage},
               job->annotations);
      for (const SemanticEntity& e : semantics.entities) {
        job->entityPaths.push_back(e.primPath);
        job->entityLabels.push_back(e.labels);
      }
      job->semanticLabels = semantics.semanticLabels;
      if (coco)
        coco->addFrame(writer.rgbPath(frame, product), job->passes.width, job->passes.height, job->annotations,
                       semantics);
      job->renderIdPaths.assign(semantics.entityOfRenderId.size(), "");
      for (const RenderItem& item : list.items)
        if (item.instanceId < job->renderIdPaths.size()) job->renderIdPaths[item.instanceId] = item.primPath;
      if (toSheet) addToSheet(*sheet, frame, job->passes, semantics, coverage);
      result.stages.annotate += since(annotateStart);
      const std::string outDir = options.outDir;
      pool.submit([job, &writer, outDir, &files, &encodeMicros] {
        auto start = Clock::now();
        std::vector<OutputFile> encoded = writer.encode(*job);
        writeFiles(outDir, encoded);
        files += encoded.size();
        encodeMicros += uint64_t(std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - start).count());
      });
    }
    log::debug("frame " + std::to_string(frame) + " rendered");
    ++result.frames;
    progress.update(result.frames);
  }
  progress.finish();
  if (sheet && !sheet->empty()) {
    writeFileAtomic((fs::path(options.outDir) / "contact_sheet.png").string(), sheet->encodePng());
    ++files;
  }
  runtime.stop();
  if (recorder) {
    recorder->recordStop(scene.stage);
    recorder->close();
  }
  runtime.destroy();
  pool.finish();
  if (coco) {
    coco->finish();
    ++files;
  }
  result.files = files + 1 + result.simulationFrames * cameraPaths.size();  // metadata.txt, simulation frames
  result.stages.encodeWrite = double(encodeMicros) / 1e6;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace sdg
