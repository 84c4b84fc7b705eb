// The runtime's promises for long and interrupted runs: the timeline's time
// does not drift, the events of the last update are delivered at stop, and
// run_activity names the hook and frame in progress.
#include <catch2/catch.hpp>

#include "behavior/registry.h"
#include "behavior/run_activity.h"
#include "behavior/runtime.h"
#include "stage/stage.h"

using namespace sdg;

namespace {

// Publishes "tick" {frame} on every update and records what the run's
// activity said during its hooks.
struct Ticker : Behavior {
  std::vector<std::string>* seen;
  explicit Ticker(std::vector<std::string>* s) : seen(s) {}
  void onPlay() override { seen->push_back(activity::current().text()); }
  void onUpdate(double, double) override {
    seen->push_back(activity::current().text());
    events().publish("tick", {{"n", double(++updates)}});
  }
  void onStop() override { seen->push_back(activity::current().text()); }
  int updates = 0;
};

// Records the ticks it hears, and when.
struct Listener : Behavior {
  std::vector<std::string>* seen;
  explicit Listener(std::vector<std::string>* s) : seen(s) {}
  void onInit() override {
    events().subscribe("tick", [this](const Payload& p) {
      seen->push_back("heard " + std::to_string(int(std::get<double>(*p.find("n")))) + activity::current().phaseText());
    });
  }
  void onStop() override { seen->push_back("listener stops"); }
};

struct Run {
  Stage stage;
  BehaviorRegistry registry;
  std::vector<std::string> seen;
  explicit Run(const BehaviorContext& context = {}) {
    BehaviorSpec ticker;
    ticker.name = "ticker";
    registry.add(ticker, [this] { return std::make_unique<Ticker>(&seen); }, "test");
    BehaviorSpec listener;
    listener.name = "listener";
    registry.add(listener, [this] { return std::make_unique<Listener>(&seen); }, "test");
    stage.definePrim("/World", PrimType::Xform).behaviors() = {"ticker", "listener"};
    runtime = std::make_unique<BehaviorRuntime>(stage, registry, context);
  }
  std::unique_ptr<BehaviorRuntime> runtime;
};

}  // namespace

TEST_CASE("timeline: the time is steps / rate, never a drifting sum", "[behavior][timeline]") {
  Timeline timeline(60.0);
  timeline.play();
  double summed = 0.0;
  for (int i = 0; i < 10000; ++i) summed += timeline.advance();
  CHECK(timeline.steps() == 10000);
  CHECK(timeline.time() == 10000.0 / 60.0);  // 166.66666666666666
  CHECK(summed != 10000.0 / 60.0);           // what summing gave: 166.66666666669144
  timeline.pause();
  timeline.play();
  timeline.advance();
  CHECK(timeline.time() == 10001.0 / 60.0);  // resume continues counting
  timeline.stop();
  CHECK(timeline.time() == 0.0);
}

TEST_CASE("runtime: the events of the last update are delivered at stop, before onStop", "[behavior][events]") {
  Run run;
  run.runtime->init();
  run.runtime->play();
  for (int frame = 0; frame < 3; ++frame) run.runtime->update();
  run.runtime->stop();
  run.runtime->destroy();
  std::vector<std::string> heard;
  for (const std::string& s : run.seen)
    if (s.starts_with("heard") || s == "listener stops") heard.push_back(s);
  CHECK(heard == std::vector<std::string>{"heard 1 at frame 1", "heard 2 at frame 2", "heard 3 after frame 2",
                                          "listener stops"});
}

TEST_CASE("runtime: run_activity names the prim, behavior, hook and frame", "[behavior][activity]") {
  SECTION("frames of the first iteration") {
    Run run;
    run.runtime->init();
    run.runtime->update();  // a pre-roll update
    CHECK(activity::current().text() == "in pre-roll update 1");
    run.runtime->play();
    run.runtime->update();
    run.runtime->update();
    CHECK(activity::current().text() == "at frame 1");  // between hooks: only the frame
    run.runtime->stop();
    CHECK(run.seen[0] == "/World: ticker.on_play() at frame 0");
    CHECK(run.seen[1] == "/World: ticker.on_update() at frame 0");
    CHECK(run.seen[3] == "/World: ticker.on_update() at frame 1");
    CHECK(run.seen.back() == "/World: ticker.on_stop() after frame 1");
  }
  SECTION("iterations after the first") {
    // What the first update of iteration 2 says, with and without the
    // dataset number of the iteration's first frame.
    auto firstUpdate = [](std::optional<uint64_t> firstFrame) {
      BehaviorContext context;
      context.iteration = 2;
      context.firstFrame = firstFrame;
      Run run(context);
      run.runtime->init();
      run.runtime->play();
      run.runtime->update();
      return run.seen[1];
    };
    CHECK(firstUpdate(10) == "/World: ticker.on_update() at frame 10");
    CHECK(firstUpdate(std::nullopt) == "/World: ticker.on_update() at frame 0 of iteration 2");
  }
  SECTION("nested scopes restore the outer one") {
    activity::HookScope outer("/A", "b", "on_update");
    {
      activity::HookScope inner("/A", "b", "the callback for event 'e'", activity::HookScope::Kind::Callback);
      CHECK(activity::current().hook == "the callback for event 'e'");
    }
    CHECK(activity::current().hook == "on_update");
  }
}
