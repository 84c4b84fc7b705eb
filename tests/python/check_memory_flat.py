"""Memory stays flat over a long run (issue 42): the same 16 x 16 raster
scene with its behaviors and five annotators, run for 200 and for 1,600
frames; the longer run's peak resident memory (run_summary.json's
peak_rss_mb, the process's high-water mark, finishing included) may exceed
the shorter one's by at most 2 %. Eight times the frames within 2 % is what
this test can afford on 2 cores; it does not extrapolate to 100,000 frames
(docs/performance.md gives that run, measured by hand)."""
import json
import subprocess
import sys
import tempfile

from checklib import check, finish

binary, scene = sys.argv[1], sys.argv[2]
SHORT, LONG = 200, 1600


def peak_rss_mb(frames, out):
    subprocess.run([binary, "run", scene, "--frames", str(frames), "--seed", "3", "--set", "render.resolution=[16,16]",
                    "--out", out, "--overwrite"], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(f"{out}/run_summary.json") as f:
        summary = json.load(f)
    check(summary["frames"] == frames, f"{out}: {summary['frames']} frames, expected {frames}")
    return summary["peak_rss_mb"]


with tempfile.TemporaryDirectory() as tmp:
    short = peak_rss_mb(SHORT, f"{tmp}/short")
    long = peak_rss_mb(LONG, f"{tmp}/long")
growth = (long - short) / short
check(growth <= 0.02, f"peak memory grew {100 * growth:.2f} % from {SHORT} to {LONG} frames "
                      f"({short:.1f} MB -> {long:.1f} MB); at most 2 % allowed")
sys.exit(finish(f"peak memory {short:.1f} MB after {SHORT} frames, {long:.1f} MB after {LONG} "
                f"({100 * growth:+.2f} %)"))
