// `verify` and `merge`: commands on a dataset folder rather than a scene.
#include <iostream>
#include <memory>

#include "commands.h"
#include "core/log.h"
#include "run/merge.h"
#include "run/output_folder.h"
#include "writers/manifest.h"

namespace sdg::cli {

void addVerify(CLI::App& app, int& exitCode) {
  auto dir = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("verify", "Re-check every file of a dataset folder against its manifest (sha256)");
  cmd->add_option("dir", *dir, "Dataset folder (the --out of a run)")->required()->type_name("DIR");
  cmd->footer("Exit status: 0 every listed file matches and the run is complete, 1 otherwise.\n"
              "Example:\n  sdgbehave verify out/warehouse");
  cmd->callback([dir, &exitCode] {
    std::vector<ManifestEntry> entries = readManifests(*dir);
    if (entries.empty()) {
      log::error(*dir + ": no manifest*.jsonl with any frame; nothing to verify");
      exitCode = kExitRunFailure;
      return;
    }
    VerifyReport report = verifyManifest(*dir, entries);
    for (const std::string& p : report.problems) std::cout << *dir << "/" << p << "\n";
    size_t expected = 0;
    try {
      RunInfo info = readRunInfo(*dir);
      expected = info.frames() * info.products.size();
      // Frames of shards that ran with other inputs do not make one dataset.
      for (const std::string& p : shardInputProblems(*dir, info)) {
        std::cout << *dir << ": " << p << "\n";
        report.problems.push_back(p);
      }
      std::cout << *dir << ": inputs " << info.inputs.identity().substr(0, 16) << " (" << info.inputs.files.size()
                << " files, sdgbehave " << info.inputs.version << ")\n";
    } catch (const RunError&) {
    }
    const bool complete = expected == 0 || entries.size() == expected;
    // "N files" counts what `run` counted (files_written); the manifest
    // lists the frames' files and hidden parts, not the files made at the end.
    std::cout << *dir << ": " << report.folderFiles << " files, " << entries.size() << " frame outputs; the manifest's "
              << report.files - report.hiddenParts << " files and " << report.hiddenParts
              << " hidden parts checked, " << report.problems.size() << " problems" << (complete ? "" : "; the run is incomplete (" +
                                                                             std::to_string(entries.size()) + " of " +
                                                                             std::to_string(expected) + ")")
              << "\n";
    exitCode = report.problems.empty() && complete ? kExitOk : kExitRunFailure;
  });
}

void addMerge(CLI::App& app, int& exitCode) {
  auto dir = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "merge", "Finish a dataset written by shards: manifest, COCO file, contact sheet and run_summary.json");
  cmd->add_option("dir", *dir, "The shared --out of every shard")->required()->type_name("DIR");
  cmd->footer("Run it once, after every shard has exited 0. A missing frame exits 1 and names it;\n"
              "rerun that shard with --resume, then merge again.\n"
              "Example:\n  sdgbehave merge /shared/datasets/warehouse");
  cmd->callback([dir, &exitCode] {
    MergeResult r = mergeShards(*dir);
    log::info(*dir + ": merged " + std::to_string(r.frames) + " frames from " + std::to_string(r.shards) +
              " shard summaries");
    exitCode = kExitOk;
  });
}

}  // namespace sdg::cli
