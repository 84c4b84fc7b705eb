#!/usr/bin/env bash
# `make bench`: runs the benchmarks, prints a table and writes
# bench/results.json (each figure: median, min, max of 5 runs).
set -euo pipefail
build=${1:?usage: bench.sh BUILD_DIR}
mkdir -p bench
lines=$(mktemp)
trap 'rm -f "$lines"' EXIT
for threads in 1 2; do
  LP_NUM_THREADS=$threads "$build/tools/sdg_bench_render" >> "$lines"
done
/usr/bin/python3 - "$lines" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
targets = {"4 pallets + 60 boxes + target + 3 lights, LP_NUM_THREADS=2": ">= 30 frames/s"}
print(f"{'benchmark':<92} {'median':>10} {'frames/s':>9}  target")
for r in rows:
    t = next((v for k, v in targets.items() if r["name"].endswith(k)), "")
    print(f"{r['name']:<92} {r['median']:>7.2f} ms {r['fps']:>9.1f}  {t}")
json.dump(rows, open("bench/results.json", "w"), indent=2)
print("wrote bench/results.json")
PY
