// volumeStackRandomizer — drops random assets onto surfaces and lets ODE
// rigid-body physics stack them.
//
// Exposed variables (exposedVar:volumeStackRandomizer:*):
//   includeChildren          bool     true    every geometry prim below is a surface too
//   event:input              string   isaacsim.replicator.behavior.volumeStackRandomizer.in   locked
//   event:output             string   isaacsim.replicator.behavior.volumeStackRandomizer.out  reply event
//   assets:assets            asset[]  []      mesh files; "file#label" sets the semantic class
//   assets:csv               string   (Isaac's two carton props)  comma-separated mesh files, after assets:assets
//   assets:numRange          int2     (4, 8)  assets per surface, both ends included
//   dropHeight               float    2.0     drop height above the surface top, and the wall height
//   renderSimulation         bool     true    render every physics step into <out>/simulation/
//   removeRigidBodyDynamics  bool     true    assets end static (always so here: see below)
//   preserveSimulationState  bool     true    keep the stacked poses after the timeline stops
//   seed                     int      -1
//
// Event driven, not timeline driven: {action: setup|run|reset, prim_path?}
// on event:input; replies {prim_path, state, state_name} on event:output
// with INIT(0) after init, SETUP(1), RUNNING(2), FINISHED(3), RESET(4).
//
// setup: per surface (in stage order) n = integers(lo, hi + 1) assets drawn
// with replacement become Mesh prims /Behaviors/volumeStackRandomizer/
// Assets/<surface>/Asset_i at the surface's world pose, labelled class=<label>
// (the "#label" of the entry, else the file name without extension), sorted
// largest world bounding box first; six invisible wall Cubes per surface go
// under .../CollisionWalls/<surface>/CollisionWalls. run: the schedule of
// physics/stack_simulation.h, poses written back, walls removed, settle
// quality reported. reset: everything it made is removed.
//
// Deliberate differences from Isaac Sim (README, "Behaviors"): each asset
// is pulled by its own centre force (Isaac sums them through a shared
// vector); the drop square turns with the surface; assets start below the
// ceiling, not half inside it; after the fixed schedule, extra steps run
// with the final friction until the stack is still. A run completes within
// the update that delivers it, so a reset can never arrive mid-run.
#include <algorithm>
#include <filesystem>
#include <optional>

#include "assets/asset_resolver.h"
#include "assets/file_check.h"
#include "behavior/behavior.h"
#include "behavior/behavior_prims.h"
#include "builtin_behaviors/builtin_behaviors.h"
#include "builtin_behaviors/spec_helpers.h"
#include "core/diagnostics.h"
#include "core/log.h"
#include "core/text.h"
#include "physics/physics_settings.h"
#include "physics/stack_simulation.h"
#include "stage/path.h"
#include "stage/xform.h"

namespace sdg {
namespace {

constexpr const char* kName = "volumeStackRandomizer";
constexpr const char* kEventIn = "isaacsim.replicator.behavior.volumeStackRandomizer.in";
constexpr const char* kEventOut = "isaacsim.replicator.behavior.volumeStackRandomizer.out";
constexpr const char* kScope = "/Behaviors/volumeStackRandomizer";
// Documented limit: more would take hours to simulate and GBs of prims.
constexpr int kMaxAssetsPerSurface = 10000;

enum class State { Init = 0, Setup = 1, Running = 2, Finished = 3, Reset = 4 };
const char* stateName(State s) {
  static const char* names[] = {"INIT", "SETUP", "RUNNING", "FINISHED", "RESET"};
  return names[int(s)];
}

struct AssetEntry {
  std::string url;    // as written; the renderer resolves it again
  std::string label;
};

// "props/box.glb#carton" -> {props/box.glb, carton}; no '#': the file stem.
AssetEntry parseEntry(const std::string& entry) {
  size_t hash = entry.rfind('#');
  if (hash != std::string::npos) return {entry.substr(0, hash), entry.substr(hash + 1)};
  return {entry, std::filesystem::path(entry).stem().string()};
}

// assets:assets, then the CSV entries, each a readable mesh file.
std::vector<AssetEntry> assetEntriesOf(const Prim& prim, const BehaviorSpec& spec, const AssetResolver& resolver) {
  std::vector<AssetEntry> entries;
  for (std::string_view name : {"assets:assets", "assets:csv"}) {
    const Attribute* attr = prim.findAttribute(exposedAttributeName(spec.name, name));
    if (!attr) continue;
    const SourceLoc loc = attr->loc.known() ? attr->loc : prim.loc();
    for (const std::string& file : fileEntriesOf(*attr, *spec.findVariable(name), resolver, prim.path())) {
      if (std::optional<std::string> problem = fileProblem(file, FileKind::Mesh, resolver))
        throw SceneError(loc, prim.path() + ": volumeStackRandomizer: " + *problem);
      AssetEntry e = parseEntry(file);
      if (e.label.empty())
        throw SceneError(loc, prim.path() + ": volumeStackRandomizer: asset " + text::quote(file) +
                                  " has an empty label after '#'");
      entries.push_back(std::move(e));
    }
  }
  return entries;
}

void setPose(Prim& prim, const BodyPose& pose) {
  prim.xformOps() = {XformOp{XformOpKind::Translate, "", Value::makeDouble3(pose.position)},
                     XformOp{XformOpKind::Orient, "", Value::makeQuatd(pose.orientation)}};
}

class VolumeStackRandomizer final : public Behavior {
 public:
  void onInit() override {
    subscription_ = events().subscribe(kEventIn, [this](const Payload& p) { onEvent(p); });
    output_ = kEventOut;
    publish(State::Init);
  }

  void onStop() override {
    // Isaac Sim resets the physics scene on stop unless told to preserve
    // it: the assets go back to where setup put them.
    if (ran_ && !preserve_)
      for (const Surface& s : surfaces_)
        for (const Placed& a : s.assets)
          if (Prim* p = stage().find(a.plan.path)) setPose(*p, a.setupPose);
  }

  void onDestroy() override {
    if (subscription_) events().unsubscribe(subscription_);
    subscription_ = 0;
    reset(false);
  }

 private:
  struct Placed {
    StackAsset plan;
    BodyPose setupPose;
    double boundsVolume = 0;
  };
  struct Surface {
    StackSurface geometry;
    std::string assetRoot;
    std::string wallRoot;
    std::vector<Placed> assets;
  };

  void onEvent(const Payload& payload) {
    if (!addressedToMe(payload)) return;
    std::string_view action = payload.getString("action");
    if (action == "setup") setup();
    else if (action == "run") run();
    else if (action == "reset") reset(true);
  }

  void publish(State s) {
    events().publish(output_, Payload{{"prim_path", primPath()},
                                      {"state", double(int(s))},
                                      {"state_name", std::string(stateName(s))}});
  }

  void setup() {
    output_ = var<std::string>("event:output");
    preserve_ = var<bool>("preserveSimulationState");
    if (!rng_) rng_ = makeRng(var<int32_t>("seed"));
    if (stage().metadata().upAxis != "Z")
      throw SceneError(prim().loc(), primPath() + ": volumeStackRandomizer: stacking needs stage.upAxis Z, found " +
                                         stage().metadata().upAxis);
    std::vector<AssetEntry> entries = assetEntries();
    if (entries.empty()) {
      log::warn(primPath() + ": volumeStackRandomizer: no assets given; nothing to stack");
      publish(State::Setup);
      return;
    }
    const Vec2i range = var<Vec2i>("assets:numRange");
    const double dropHeight = var<float>("dropHeight");
    for (Prim* surfacePrim : selectPrims(var<bool>("includeChildren"), [](const Prim& p) { return p.typeInfo().gprim; })) {
      Surface s;
      s.geometry = surfaceGeometry(*surfacePrim, dropHeight);
      const std::string name(path::name(surfacePrim->path()));
      s.assetRoot = nextFreePath(stage(), std::string(kScope) + "/Assets/" + name);
      ensureScope(stage(), s.assetRoot);
      const int64_t n = rng_->integers(range.x(), int64_t(range.y()) + 1);
      std::vector<size_t> picks;
      for (int64_t i = 0; i < n; ++i) picks.push_back(rng_->index(entries.size()));
      BodyPose atSurface{s.geometry.origin, Eigen::Quaterniond(s.geometry.rotation)};
      for (int64_t i = 0; i < n; ++i) {
        const AssetEntry& entry = entries[picks[size_t(i)]];
        Placed a;
        a.plan.path = s.assetRoot + "/Asset_" + std::to_string(i);
        a.plan.url = entry.url;
        Prim& assetPrim = stage().definePrim(a.plan.path, PrimType::Mesh);
        assetPrim.setAttribute("asset", Value::makeAsset(entry.url));
        assetPrim.semantics()["class"] = {entry.label};
        setPose(assetPrim, atSurface);
        a.setupPose = atSurface;
        a.plan.collider = ColliderCache::shared().get(meshKeyOf(assetPrim, stage().metadata().subdivisionLevel), *context().assets, a.plan.path);
        a.boundsVolume = worldBoundsVolume(*a.plan.collider, s.geometry.rotation);
        s.assets.push_back(std::move(a));
      }
      std::stable_sort(s.assets.begin(), s.assets.end(),
                       [](const Placed& a, const Placed& b) { return a.boundsVolume > b.boundsVolume; });
      surfaces_.push_back(std::move(s));
    }
    for (Surface& s : surfaces_) s.wallRoot = makeWalls(s);
    publish(State::Setup);
  }

  void run() {
    publish(State::Running);
    if (!rng_) rng_ = makeRng(var<int32_t>("seed"));  // run before setup: nothing to stack, as in Isaac Sim
    StackPlan plan;
    drawDrops();
    for (const Surface& s : surfaces_) {
      plan.surfaces.push_back(s.geometry);
      plan.assets.emplace_back();
      for (const Placed& a : s.assets) plan.assets.back().push_back(a.plan);
    }
    StackOptions options = stackOptions();
    if (var<bool>("renderSimulation") && context().hooks.simulationFrame) {
      options.onStep = [this](uint64_t step, const std::vector<std::vector<BodyPose>>& poses) {
        writePoses(poses);
        context().hooks.simulationFrame(stage(), primPath(), step);
      };
    }
    StackResult result = simulateStack(plan, options);
    writePoses(result.poses);
    for (const SurfaceSettleReport& r : result.reports)
      for (const std::string& left : r.leftArea) {
        log::warn(primPath() + ": volumeStackRandomizer: " + left + " ended outside the walls of " + r.surface +
                  "; removed");
        stage().removePrim(left);
      }
    for (Surface& s : surfaces_) stage().removePrim(s.wallRoot), s.wallRoot.clear();
    removeEmptyScopes(stage(), kScope);
    ran_ = true;
    reportSettling(result);
    publish(State::Finished);
  }

  void reset(bool announce) {
    for (Surface& s : surfaces_) {
      if (!s.wallRoot.empty()) stage().removePrim(s.wallRoot);
      stage().removePrim(s.assetRoot);
    }
    if (!surfaces_.empty()) removeEmptyScopes(stage(), kBehaviorsScope);
    surfaces_.clear();
    rng_.reset();
    ran_ = false;
    if (announce) publish(State::Reset);
  }

  // The drop pose of every asset, drawn in the order Isaac Sim draws them:
  // batch by batch (the k-th asset of every surface), x and y offsets, then
  // the X, Y and Z quarter turns.
  void drawDrops() {
    static constexpr double kAngles[] = {180, 90, 0, -90, -180};
    size_t batches = 0;
    for (const Surface& s : surfaces_) batches = std::max(batches, s.assets.size());
    for (size_t k = 0; k < batches; ++k)
      for (Surface& s : surfaces_) {
        if (k >= s.assets.size()) continue;
        Placed& a = s.assets[k];
        const StackSurface& g = s.geometry;
        const Eigen::AlignedBox3d& bounds = a.plan.collider->bounds;
        const double margin = bounds.sizes().maxCoeff() / 2;
        const double half = std::min(g.size.x(), g.size.y()) / 2 - margin;
        const double dx = rng_->uniform(-half, half), dy = rng_->uniform(-half, half);
        const double ax = kAngles[rng_->index(5)], ay = kAngles[rng_->index(5)], az = kAngles[rng_->index(5)];
        const Matrix3d turn = axisRotation(2, az) * axisRotation(1, ay) * axisRotation(0, ax);
        // Highest the turned asset can start: its top 1 mm under the ceiling.
        double top = -1e300, bottom = 1e300;
        for (int corner = 0; corner < 8; ++corner) {
          double z = (turn * bounds.corner(Eigen::AlignedBox3d::CornerType(corner))).z();
          top = std::max(top, z), bottom = std::min(bottom, z);
        }
        double z = std::max(g.dropHeight - top - 0.001, -bottom);
        Vec3d local = g.topCentre() + Vec3d(dx, dy, z);
        a.plan.drop.position = g.toWorld(local);
        a.plan.drop.orientation = Eigen::Quaterniond(g.rotation * turn).normalized();
      }
  }

  // The run's physics section, or its defaults when run without one.
  const PhysicsSettings& physicsSettings() const {
    static const PhysicsSettings defaults;
    return context().physics ? *context().physics : defaults;
  }

  StackOptions stackOptions() const {
    const PhysicsSettings& settings = physicsSettings();
    const StageMetadata& meta = stage().metadata();
    const double mpu = meta.metersPerUnit;
    StackOptions o;
    o.world.dt = 1.0 / meta.timeCodesPerSecond;
    o.world.gravity = Vec3d(0, 0, -settings.gravity / mpu);
    o.world.density = settings.density * mpu * mpu * mpu;
    o.world.solverIterations = settings.solverIterations;
    o.world.contactLayer = 0.001 / mpu;
    o.world.maxCorrectingSpeed = 1.0 / mpu;
    o.settleLinearSpeed = settings.settleLinearSpeed / mpu;
    o.settleAngularSpeed = settings.settleAngularSpeed;
    o.maxSettleSteps = settings.maxSettleSteps;
    return o;
  }

  void writePoses(const std::vector<std::vector<BodyPose>>& poses) {
    for (size_t s = 0; s < surfaces_.size(); ++s)
      for (size_t i = 0; i < surfaces_[s].assets.size(); ++i)
        if (Prim* p = stage().find(surfaces_[s].assets[i].plan.path)) setPose(*p, poses[s][i]);
  }

  void reportSettling(const StackResult& result) {
    const PhysicsSettings& settings = physicsSettings();
    std::vector<std::string> unsettled;
    for (const SurfaceSettleReport& r : result.reports) {
      nlohmann::ordered_json j;
      j["behavior_prim"] = primPath();
      j["surface"] = r.surface;
      j["assets"] = r.assets;
      j["steps"] = r.steps;
      j["extra_settle_steps"] = r.extraSettleSteps;
      j["settled"] = r.settled;
      j["max_linear_speed"] = r.maxLinearSpeed;
      j["max_angular_speed"] = r.maxAngularSpeed;
      j["max_penetration_surface"] = r.maxPenetrationSurface;
      j["max_penetration_assets"] = r.maxPenetrationAssets;
      j["left_area"] = r.leftArea;
      if (context().hooks.report) context().hooks.report(kName, j);
      log::debug(primPath() + ": volumeStackRandomizer: " + j.dump());
      if (!r.settled) unsettled.push_back(r.surface);
    }
    if (unsettled.empty()) return;
    std::string message = primPath() + ": volumeStackRandomizer: the stack on " + text::join(unsettled, ", ") +
                          " still moves after " + std::to_string(result.steps) + " steps (max_settle_steps " +
                          std::to_string(settings.maxSettleSteps) + ")";
    if (settings.requireSettled) throw RunError(message + "; physics.require_settled is true");
    log::warn(message);
  }

  StackSurface surfaceGeometry(const Prim& surface, double dropHeight) const {
    Decomposed d = decompose(stage().worldMatrix(surface));
    auto collider = ColliderCache::shared().get(meshKeyOf(surface, stage().metadata().subdivisionLevel), *context().assets, surface.path());
    StackSurface g;
    g.path = surface.path();
    g.origin = d.translation;
    g.rotation = d.rotation;
    g.size = collider->bounds.sizes().cwiseProduct(d.scale);
    g.mid = collider->bounds.center().cwiseProduct(d.scale);
    g.dropHeight = dropHeight;
    return g;
  }

  static double worldBoundsVolume(const Collider& c, const Matrix3d& rotation) {
    Eigen::AlignedBox3d box;
    for (int corner = 0; corner < 8; ++corner)
      box.extend(rotation * c.bounds.corner(Eigen::AlignedBox3d::CornerType(corner)));
    return box.volume();
  }

  // Invisible Cubes, so the walls can be inspected between setup and run;
  // the physics world builds its own boxes from the same numbers.
  std::string makeWalls(const Surface& s) {
    const std::string name(path::name(s.geometry.path));
    std::string parent = std::string(kScope) + "/CollisionWalls/" + name;
    ensureScope(stage(), parent);
    std::string root = nextFreePath(stage(), parent + "/CollisionWalls");
    Prim& r = stage().definePrim(root, PrimType::Xform);
    Matrix4d m = Matrix4d::Identity();
    m.topLeftCorner<3, 3>() = s.geometry.rotation;
    m.topRightCorner<3, 1>() = s.geometry.origin;
    r.xformOps() = {XformOp{XformOpKind::Transform, "", Value::makeMatrix4d(m)}};
    for (const WallBox& w : wallBoxes(s.geometry)) {
      Prim& wall = stage().definePrim(root + "/" + w.name, PrimType::Cube);
      wall.xformOps() = {XformOp{XformOpKind::Translate, "", Value::makeDouble3(w.centre)},
                         XformOp{XformOpKind::Scale, "", Value::makeDouble3(w.halfExtents)}};
      wall.setAttribute("visibility", Value::makeToken("invisible"));
    }
    return root;
  }

  std::vector<AssetEntry> assetEntries() const {
    static const AssetResolver kNoRoots;
    return assetEntriesOf(prim(), spec(), context().assets ? *context().assets : kNoRoots);
  }

  EventBus::Subscription subscription_ = 0;
  std::string output_;
  std::optional<Rng> rng_;
  std::vector<Surface> surfaces_;
  bool preserve_ = false;  // read in setup, as in Isaac Sim
  bool ran_ = false;
};

}  // namespace

BehaviorSpec volumeStackRandomizerSpec() {
  using namespace behaviors;
  BehaviorSpec spec;
  spec.name = kName;
  spec.summary = "Drops random assets onto surfaces and stacks them with rigid-body physics (event driven).";
  spec.eventDriven = true;
  AttributeSpec input = variable("event:input", Value::makeString(kEventIn), "Event it listens on (informational).");
  input.locked = true;
  AttributeSpec dropHeight = variable("dropHeight", Value::makeFloat(2.0f),
                                      "Drop height above the surface top (stage units); also the wall height.");
  dropHeight.minimum = 0.0;
  spec.variables = {
      includeChildrenVariable(),
      input,
      variable("event:output", Value::makeString(kEventOut), "Event it replies on."),
      fileVariable("assets:assets", Value::makeAssetArray({}), FileKind::Mesh,
               "Mesh files to drop; 'file#label' gives the semantic class (default: the file name)."),
      fileVariable("assets:csv",
               Value::makeString("/Isaac/Environments/Simple_Warehouse/Props/SM_CardBoxC_01.usd,"
                                 "/Isaac/Environments/Simple_Warehouse/Props/SM_CardBoxD_01.usd"),
               FileKind::Mesh,
               "Comma-separated mesh files, used after assets:assets."),
      variable("assets:numRange", Value::makeInt2(4, 8), "(min, max) assets per surface, both included."),
      dropHeight,
      variable("renderSimulation", Value::makeBool(true), "Render every physics step into <out>/simulation/."),
      variable("removeRigidBodyDynamics", Value::makeBool(true),
               "Make the assets static after the run (sdgbehave runs no physics on the timeline, so they always are)."),
      variable("preserveSimulationState", Value::makeBool(true),
               "Keep the stacked poses after the timeline stops; false puts them back where setup placed them."),
      seedVariable(),
  };
  spec.events = {std::string(kEventIn) + " (in): {action: setup|run|reset, prim_path?}",
                 std::string(kEventOut) + " (out): {prim_path, state, state_name: INIT|SETUP|RUNNING|FINISHED|RESET}"};
  spec.example = "volumeStackRandomizer: {assets:csv: \"props/crate.glb#crate\", assets:numRange: [2, 6]}";
  spec.validate = [](const Prim& prim, Diagnostics& diag) {
    const Attribute* r = prim.findAttribute("exposedVar:volumeStackRandomizer:assets:numRange");
    if (!r) return;
    Vec2i v = r->value.get<Vec2i>();
    if (v.x() < 0 || v.x() > v.y() || v.y() > kMaxAssetsPerSurface)
      diag.error(r->loc.known() ? r->loc : prim.loc(),
                 prim.path() + ".exposedVar:volumeStackRandomizer:assets:numRange: expected 0 <= min <= max <= " +
                     std::to_string(kMaxAssetsPerSurface) + " (assets per surface), found (" + std::to_string(v.x()) +
                     ", " + std::to_string(v.y()) + ")");
  };
  return spec;
}

std::unique_ptr<Behavior> makeVolumeStackRandomizer() { return std::make_unique<VolumeStackRandomizer>(); }

std::vector<LabelledMesh> meshesSpawnedByBuiltins(const Stage& stage, const AssetResolver& resolver) {
  const BehaviorSpec spec = volumeStackRandomizerSpec();
  std::vector<LabelledMesh> out;
  stage.traverse([&](const Prim& prim) {
    const auto& names = prim.behaviors();
    if (std::find(names.begin(), names.end(), spec.name) == names.end()) return;
    for (const AssetEntry& e : assetEntriesOf(prim, spec, resolver))
      out.push_back({"class", e.label, e.url, prim.path() + ": " + spec.name});
  });
  return out;
}

}  // namespace sdg
