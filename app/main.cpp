// sdgbehave: synthetic data for computer vision from YAML scene files.
// This file only wires the command line to the library and maps errors to
// exit codes: 0 ok, 2 bad usage or an invalid scene, 1 a failure during a run.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "commands.h"
#include "stop_signals.h"
#include "core/diagnostics.h"
#include "core/log.h"
#include "scene_io/usd_mesh_asset.h"

namespace {

constexpr const char* kDescription =
    "sdgbehave generates synthetic training data for computer vision from a YAML scene:\n"
    "prims with behaviors (randomizers), a physics pre-roll, off-screen rendering and\n"
    "Replicator BasicWriter-compatible output.\n\n"
    "Examples:\n"
    "  sdgbehave validate scenes/warehouse.yaml\n"
    "  sdgbehave inspect scenes/warehouse.yaml --set render.resolution=[640,480]\n"
    "  sdgbehave describe locationRandomizer\n"
    "  sdgbehave run scenes/warehouse.yaml --frames 6 --seed 10 --out out/warehouse   # then open contact_sheet.png\n"
    "  sdgbehave run scenes/examples/location_randomizer.yaml --frames 6 --no-render --record changes.jsonl\n"
    "  sdgbehave run scenes/warehouse.yaml --frames 50 --shard 0/2 --out ds   # and --shard 1/2, then:\n"
    "  sdgbehave merge ds && sdgbehave verify ds\n"
    "  sdgbehave schema --out schemas/scene.schema.json\n"
    "  sdgbehave new-behavior randomScale   # a starter behavior script (Python) and a scene that uses it\n"
    "  sdgbehave flatten scenes/warehouse.yaml -o flat.yaml   # smart assets expanded into one file\n"
    "  sdgbehave studio scenes/warehouse.yaml   # tune it live in the browser\n";

}  // namespace

std::string sdg::cli::versionText() {
  std::string v = "sdgbehave " SDG_VERSION;
  if (std::string(SDG_GIT_DESCRIBE).size()) v += " (" SDG_GIT_DESCRIBE ")";
  return v;
}

int main(int argc, char** argv) {
  using namespace sdg;
  registerUsdMeshAssets();  // `asset: x.usd` meshes, for every command that draws or checks a scene
  CLI::App app(kDescription, "sdgbehave");
  app.require_subcommand(1);
  app.set_version_flag("--version", cli::versionText());
  app.footer(
      "Exit status: 0 success; 2 bad usage or an invalid scene; 1 a failure during a run.\n"
      "Run `sdgbehave COMMAND --help` for a command's options.");
  bool quiet = false, verbose = false;
  std::string logFormat = "text";
  app.add_flag("-q,--quiet", quiet, "Only errors on stderr");
  app.add_flag("-v,--verbose", verbose, "Debug messages on stderr");
  app.add_option("--log-format", logFormat, "Log lines as text or JSON (one object per line)")
      ->check(CLI::IsMember({"text", "json"}))
      ->capture_default_str();

  // Global options are accepted after the subcommand too (`sdgbehave run
  // scene.yaml --quiet`): subcommands created from here on inherit this and
  // pass options they do not know up to the app.
  app.fallthrough();

  int exitCode = cli::kExitOk;
  cli::addValidate(app, exitCode);
  cli::addInspect(app, exitCode);
  cli::addFlatten(app, exitCode);
  cli::addExportUsd(app, exitCode);
  cli::addExec(app, exitCode);
  cli::addSchema(app, exitCode);
  cli::addDescribe(app, exitCode);
  cli::addRun(app, exitCode);
  cli::addRender(app, exitCode);
  cli::addVerify(app, exitCode);
  cli::addMerge(app, exitCode);
  cli::addNewBehavior(app, exitCode);
  cli::addStudio(app, exitCode);

  // Logging must be configured before subcommand callbacks run; so must the
  // stop signals (the studio waits for them itself).
  app.parse_complete_callback([&] {
    log::configure(quiet ? log::Level::Error : verbose ? log::Level::Debug : log::Level::Info,
                   logFormat == "json" ? log::Format::Json : log::Format::Text);
    if (!app.got_subcommand("studio")) cli::installStopSignalHandlers();
  });

  cli::setCommandLine(std::vector<std::string>(argv + 1, argv + argc));
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return cli::kExitInvalid;
  } catch (const SceneError& e) {
    for (const Diagnostic& d : e.problems()) log::diagnostic(d);
    log::write(log::Level::Error, std::to_string(e.problems().size()) +
                                      (e.problems().size() == 1 ? " problem" : " problems") + "; nothing was run");
    return cli::kExitInvalid;
  } catch (const RunError& e) {
    log::error(e.what());
    return cli::kExitRunFailure;
  } catch (const std::exception& e) {
    log::error(std::string("internal error: ") + e.what());
    return cli::kExitRunFailure;
  }
  return exitCode;
}
