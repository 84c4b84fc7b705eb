#include "run/run_summary.h"

#include <sys/resource.h>

#include <cstdio>
#include <fstream>
#include <iterator>

#include "core/file_io.h"

namespace sdg {

double peakRssMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // Linux reports KiB
}

nlohmann::ordered_json makeRunSummary(const RunSummaryInputs& in) {
  using Json = nlohmann::ordered_json;
  const DatasetRunResult& r = *in.result;
  const DatasetRunOptions& o = *in.options;
  Json j;
  j["tool"] = "sdgbehave";
  j["version"] = in.version;
  j["scene"] = in.scenePath;
  j["scene_hash"] = fileHash(in.scenePath);
  j["inputs_identity"] = r.info.inputs.identity();
  j["seed"] = o.seed;
  j["frames"] = r.frames;
  j["frames_resumed"] = r.resumedFrames;
  j["frames_in_run"] = o.plan.total();
  j["iterations"] = o.plan.iterations;
  j["frames_per_iteration"] = o.plan.framesPerIteration;
  j["shard"] = {{"index", o.plan.shard.index}, {"count", o.plan.shard.count},
                {"first_frame", o.plan.ownedBegin()}, {"end_frame", o.plan.ownedEnd()}};
  j["pre_rolls"] = r.iterationsRun;
  j["output"] = o.outDir;
  j["files_written"] = datasetFilesWritten(r, o.plan.shard.sharded());
  j["renderer"] = {{"backend", r.backend}, {"device", r.device}, {"gl_renderer", r.renderer}, {"color", r.colorDevice}};
  const double total = in.loadSeconds + r.seconds;
  j["seconds"] = {{"load", in.loadSeconds},          {"preroll", r.stages.preroll},
                  {"behaviors", r.stages.behaviors}, {"render", r.stages.render},
                  {"annotate", r.stages.annotate},   {"encode_write_all_threads", r.stages.encodeWrite},
                  {"total", total}};
  j["frames_per_second"] = r.seconds > 0 ? double(r.frames) / r.seconds : 0.0;
  j["peak_rss_mb"] = peakRssMb();
  j["settle"] = r.settle;
  // What the scene's USD files had that the stage did not carry over, and
  // what the run found wrong with its frames (docs/cli.md).
  nlohmann::ordered_json dropped = nlohmann::ordered_json::array();
  if (in.dropped)
    for (const DroppedWarning& d : *in.dropped)
      dropped.push_back({{"kind", d.info.kind}, {"what", d.info.what}, {"count", d.info.count},
                         {"first", d.diagnostic.loc.str()}, {"message", d.diagnostic.message}});
  j["dropped"] = std::move(dropped);
  j["warnings"] = r.warnings;
  return j;
}

uint64_t datasetFilesWritten(const DatasetRunResult& result, bool sharded) {
  return result.files + (sharded ? 0 : 1);
}

}  // namespace sdg
