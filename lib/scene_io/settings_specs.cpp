// The run-level option tables: names, types, defaults and docs. BasicWriter
// options keep Replicator's names and defaults so its users recognise them.
#include <stdexcept>

#include "scene_io/scene.h"

namespace sdg {
namespace {

AttributeSpec option(std::string name, Value fallback, std::string doc) {
  return makeAttributeSpec(std::move(name), std::move(fallback), std::move(doc));
}

AttributeSpec atLeast(double minimum, AttributeSpec spec) {
  spec.minimum = minimum;
  return spec;
}

AttributeSpec tokens(AttributeSpec spec, std::vector<std::string> allowed) {
  spec.allowedTokens = std::move(allowed);
  return spec;
}

const std::vector<AttributeSpec>& stageSpecs() {
  static const std::vector<AttributeSpec> specs = {
      atLeast(1, option("timeCodesPerSecond", Value::makeDouble(60.0),
                        "Timeline rate; one update advances 1/timeCodesPerSecond seconds and physics steps at that rate.")),
      atLeast(1e-9, option("metersPerUnit", Value::makeDouble(1.0),
                           "Size of one scene unit in metres (distance outputs are written in metres).")),
      tokens(option("upAxis", Value::makeToken("Z"), "The world's up axis."), {"Y", "Z"}),
  };
  return specs;
}

const std::vector<AttributeSpec>& renderSpecs() {
  static const std::vector<AttributeSpec> specs = {
      atLeast(1, option("resolution", Value::makeInt2(512, 512), "Image size in pixels (width, height).")),
      atLeast(1, option("subframes", Value::makeUInt(1),
                        "Jittered sub-samples accumulated per frame for anti-aliased colour (labels stay exact).")),
      tokens(option("mode", Value::makeToken("raster"),
                    "Colour from the rasterizer (raster: fast, shadow maps, no bounced light) or the CPU path tracer "
                    "(pathtraced: physically based; labels still come from the rasterizer)."),
             {"raster", "pathtraced"}),
      tokens(option("pathtracer", Value::makeToken("auto"),
                    "Which path tracer draws render.mode pathtraced: cpu (Embree), gpu (a GPU path tracer; an error "
                    "where this build or machine has none) or auto (the GPU's where one is built in and runs here, "
                    "else the CPU's)."),
             {"auto", "cpu", "gpu"}),
      atLeast(1, option("samples", Value::makeUInt(64), "Path-traced samples per pixel.")),
      atLeast(1, option("max_bounces", Value::makeUInt(8), "Path-traced scattering events whose light is counted.")),
      option("denoise", Value::makeBool(false),
             "Filter path-traced colour with the edge-aware denoiser (guided by albedo, normals, depth, instances)."),
      tokens(option("subdivision_level", Value::makeToken("2"),
                    "Uniform refinements of subdivision surfaces (a Mesh whose subdivisionScheme is catmullClark, "
                    "loop or bilinear), each splitting every face in four, with OpenSubdiv; none draws the "
                    "authored polygons."),
             {"none", "1", "2", "3", "4", "5", "6"}),
      tokens(option("backend", Value::makeToken("auto"),
                    "GL back end: osmesa (CPU), egl (GPU, headless) or auto (EGL GPU when present, else OSMesa)."),
             {"auto", "osmesa", "egl"}),
  };
  return specs;
}

const std::vector<AttributeSpec>& captureSpecs() {
  static const std::vector<AttributeSpec> specs = {
      option("cameras", Value::makeStringArray({}),
             "Camera prims to render, one render product each; empty means every Camera prim of the stage."),
      option("lidars", Value::makeStringArray({}),
             "Lidar prims to scan, one sweep each per frame, written by a writer with `lidar: true`; empty means "
             "every Lidar prim of the stage."),
      option("frames", Value::makeUInt(1), "Number of frames to capture (per iteration; --frames overrides)."),
      atLeast(1, option("iterations", Value::makeUInt(1),
                        "Independent repetitions: each re-runs the pre-roll (fresh stacks) with random streams derived "
                        "from (seed, iteration), then captures its frames; frame numbers continue (--iterations)."))
      ,
      option("frames_per_iteration", Value::makeUInt(0), "Frames per iteration; 0 means `frames`."),
      option("seed", Value::makeInt(0), "Run seed; every random stream is derived from it (--seed overrides)."),
      option("contact_sheet", Value::makeBool(true),
             "Write <out>/contact_sheet.png: up to 36 frames of the first camera with boxes and class names."),
  };
  return specs;
}

const std::vector<AttributeSpec>& physicsSpecs() {
  static const std::vector<AttributeSpec> specs = {
      atLeast(0, option("gravity", Value::makeDouble(9.81), "Gravity along -up (m/s^2).")),
      atLeast(1e-6, option("density", Value::makeDouble(1000.0),
                           "Density of dropped assets (kg/m^3); mass is density times collider volume.")),
      atLeast(1, option("solver_iterations", Value::makeUInt(20), "ODE QuickStep iterations per step.")),
      atLeast(0, option("settle_linear_speed", Value::makeDouble(0.01),
                        "A stack is settled when no asset's net speed over the last 30 steps exceeds this (m/s)...")),
      atLeast(0, option("settle_angular_speed", Value::makeDouble(0.1), "...and no asset turns faster than this (rad/s).")),
      option("max_settle_steps", Value::makeUInt(600),
             "Extra steps allowed after the fixed stacking schedule to reach the settle speeds."),
      option("require_settled", Value::makeBool(false),
             "Fail the run (exit 1) when a stack is still moving after max_settle_steps; otherwise warn."),
  };
  return specs;
}

const std::vector<AttributeSpec>& runSpecs() {
  static const std::vector<AttributeSpec> specs = {
      atLeast(0, option("hook_timeout", Value::makeDouble(60.0),
                        "Seconds one call into a behavior script (a hook or an event callback) may take before the run "
                        "stops with an error naming it; 0 means no limit (--hook-timeout overrides).")),
      tokens(option("isaac_scripts", Value::makeToken("auto"),
                    "Isaac's six behavior scripts listed in omni:scripting:scripts: auto runs the file when it "
                    "exists, else the built-in of its name; builtin always the built-in; script always the file "
                    "(--isaac-scripts overrides; docs/isaac-scripts.md)."),
             {"auto", "builtin", "script"}),
  };
  return specs;
}

const std::vector<AttributeSpec>& basicWriterSpecs() {
  auto flag = [](std::string name, bool fallback, std::string doc) {
    return option(std::move(name), Value::makeBool(fallback), std::move(doc));
  };
  static const std::vector<AttributeSpec> specs = {
      flag("rgb", false, "rgb_X.png: the colour image (8-bit RGBA)."),
      flag("hdr_color", false,
           "hdr_color_X.npy: linear radiance before tone mapping (float32, height x width x 3); render.mode pathtraced only."),
      flag("bounding_box_2d_tight", false, "Boxes around the visible pixels of each labelled entity."),
      flag("bounding_box_2d_loose", false, "Boxes around the full projected extent, ignoring occluders."),
      flag("semantic_segmentation", false, "Per-pixel semantic ids and their labels."),
      flag("instance_id_segmentation", false, "Per-pixel instance ids mapped to prim paths."),
      flag("instance_segmentation", false, "Per-pixel instance ids mapped to prim paths and labels."),
      flag("distance_to_camera", false, "float32 metres from the camera centre (.npy)."),
      flag("distance_to_image_plane", false, "float32 metres along the optical axis (.npy)."),
      flag("bounding_box_3d", false, "Local extents and local-to-world transforms of labelled entities."),
      flag("motion_vectors", false,
           "motion_vectors_X.npy: float32 (H, W, 4) pixels each surface point moved since the previous frame "
           "(x left-positive, y up-positive, z and w 0), Isaac's layout."),
      flag("occlusion", false, "Fraction of each entity hidden by others."),
      flag("normals", false, "World-space normals encoded as an RGBA PNG."),
      flag("camera_params", false, "Intrinsics, view and projection matrices (camera_params_X.json)."),
      flag("pointcloud", false, "World positions, colours, normals and ids of labelled pixels (.npy)."),
      flag("pointcloud_include_unlabelled", false, "Include unlabelled geometry in the point cloud."),
      flag("forward_flow", false,
           "forward_flow_X.npy: float32 (H, W, 2) optical flow to the next frame, (row, column) pixels (Kubric's)."),
      flag("backward_flow", false,
           "backward_flow_X.npy: float32 (H, W, 2) optical flow to the previous frame, (row, column) pixels."),
      flag("lidar", false,
           "lidar_<sensor>_X.npy: each capture.lidars sensor's sweep (a structured array of points in the sensor "
           "frame with range, intensity, ring, azimuth, time, semantic and instance ids) and lidar_<sensor>_X.json "
           "(pose and labels)."),
      flag("lidar_kitti", false, "Also lidar_<sensor>_X.bin: KITTI's N x 4 float32 (x, y, z, intensity)."),
      flag("lidar_keep_misses", false,
           "Keep rays that return nothing (no hit in range, or dropped) as points with range 0 and x, y, z 0."),
      tokens(option("image_output_format", Value::makeToken("png"), "File format of the rgb output."), {"png"}),
      flag("colorize_semantic_segmentation", true, "Write colours (RGBA PNG) instead of raw ids."),
      flag("colorize_instance_id_segmentation", true, "Write colours (RGBA PNG) instead of raw ids."),
      flag("colorize_instance_segmentation", true, "Write colours (RGBA PNG) instead of raw ids."),
      flag("colorize_depth", false, "Also write a greyscale PNG for each distance output."),
      option("semantic_types", Value::makeStringArray({"class"}), "Label taxonomies to write."),
      option("frame_padding", Value::makeUInt(4), "Zero-padding width of frame numbers in file names."),
      flag("use_common_output_dir", false,
           "With several cameras: <annotator>/<camera>_<kind>_X files instead of <camera>/<annotator>/ folders."),
  };
  return specs;
}

const std::vector<AttributeSpec>& cocoWriterSpecs() {
  static const std::vector<AttributeSpec> specs = {
      option("semantic_types", Value::makeStringArray({"class"}),
             "Label taxonomies whose labels become COCO categories."),
      option("file_name", Value::makeString("coco_instances.json"), "Name of the instances file in the output folder."),
  };
  return specs;
}

const std::vector<AttributeSpec>& bopWriterSpecs() {
  static const std::vector<AttributeSpec> specs = {
      option("objects", Value::makeStringArray({}),
             "Labels (of the first semantic taxonomy) of the BOP objects; obj_id is the position in this list plus one."),
      option("split", Value::makeString("train_pbr"), "Folder of the images: <split>/<scene_id>/ (one scene per iteration)."),
      atLeast(1e-6, option("depth_scale", Value::makeDouble(1.0),
                           "Millimetres per unit of the 16-bit depth images (1.0: 1 mm steps, at most 65.535 m).")),
      option("symmetries", Value::makeStringArray({}),
             "Symmetries of the objects for models_info.json: '<label>: continuous <x|y|z>' or "
             "'<label>: discrete <x|y|z> <degrees>' (axes of the model frame, through its origin)."),
  };
  return specs;
}

}  // namespace

OptionSet::OptionSet(std::span<const AttributeSpec> specs) {
  for (const AttributeSpec& s : specs) values_.emplace(s.name, s.defaultValue);
}

const Value& OptionSet::get(std::string_view name) const {
  auto it = values_.find(name);
  if (it == values_.end()) throw std::logic_error("no option " + std::string(name));
  return it->second;
}

void OptionSet::set(const std::string& name, Value value, const SourceLoc& loc) {
  values_[name] = std::move(value);
  locs_[name] = loc;
}

const SourceLoc* OptionSet::locOf(std::string_view name) const {
  auto it = locs_.find(name);
  return it == locs_.end() ? nullptr : &it->second;
}

Scene::Scene()
    : render(renderOptionSpecs()), capture(captureOptionSpecs()), physics(physicsOptionSpecs()), run(runOptionSpecs()) {}

void applyRenderSettingsToStage(Scene& scene) {
  const std::string& level = scene.render.getString("subdivision_level");
  scene.stage.metadata().subdivisionLevel = level == "none" ? 0 : std::stoi(level);
}

std::span<const AttributeSpec> stageOptionSpecs() { return stageSpecs(); }
std::span<const AttributeSpec> renderOptionSpecs() { return renderSpecs(); }
std::span<const AttributeSpec> physicsOptionSpecs() { return physicsSpecs(); }
std::span<const AttributeSpec> captureOptionSpecs() { return captureSpecs(); }
std::span<const AttributeSpec> runOptionSpecs() { return runSpecs(); }

std::span<const WriterTypeInfo> writerTypes() {
  static const std::vector<WriterTypeInfo> types = {
      {"BasicWriter", "Replicator BasicWriter folder layout and file formats.", basicWriterSpecs()},
      {"CocoWriter", "One COCO instances JSON for the run (tight boxes, RLE masks).", cocoWriterSpecs()},
      {"BopWriter", "The BOP 6D pose format: rgb, depth, masks, scene_gt/scene_camera/scene_gt_info, models.",
       bopWriterSpecs()},
  };
  return types;
}

const WriterTypeInfo* findWriterType(std::string_view name) {
  for (const WriterTypeInfo& t : writerTypes())
    if (t.name == name) return &t;
  return nullptr;
}

}  // namespace sdg
