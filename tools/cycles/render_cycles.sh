#!/usr/bin/env bash
# Renders a saved stage with Blender's Cycles at several sample counts.
#
#   tools/cycles/render_cycles.sh STAGE.yaml OUT_DIR [--samples "1024 32"] [--resolution WxH]
#                                 [--camera PATH] [--denoise-samples "32"] [--seed 0] [--threads N]
#
# Writes into OUT_DIR: stage_blender.py (the scene as a Blender script), and per
# sample count cycles_N.npy (linear radiance, float32 H x W x 3, rows top first),
# cycles_N.exr and cycles_N.json (its timing), and timings.json with them all.
# Each count renders in its own Blender process, without denoising, CPU, seed
# fixed. The JSON has two times: seconds_render, taken inside Blender around
# the render call alone (scene sync, BVH build, path tracing), and
# seconds_process, the whole Blender process (start-up, building the scene,
# rendering, writing). Counts in --denoise-samples are rendered once more with
# OpenImageDenoise (cycles_N_oidn) when this Blender has it; Debian's 3.4.1 is
# built without it, which timings.json records.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
python=/usr/bin/python3

usage() { sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
[[ $# -ge 2 ]] || usage
stage="$1" out="$2"
shift 2
samples="1024 32" resolution="" camera="" denoise_samples="32" seed=0 threads=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --samples) samples="$2"; shift 2 ;;
    --resolution) resolution="$2"; shift 2 ;;
    --camera) camera="$2"; shift 2 ;;
    --denoise-samples) denoise_samples="$2"; shift 2 ;;
    --seed) seed="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    *) usage ;;
  esac
done
command -v blender >/dev/null || { echo "render_cycles: no blender; run tools/install-deps.sh tools/cycles/debian-packages.txt" >&2; exit 1; }
mkdir -p "$out"

export_args=("$stage" -o "$out/stage_blender.py")
[[ -n "$resolution" ]] && export_args+=(--resolution "$resolution")
[[ -n "$camera" ]] && export_args+=(--camera "$camera")
"$python" "$here/stage_to_blender.py" "${export_args[@]}"

oidn=$(blender -b --factory-startup --python-expr \
  'import _cycles; print("OIDN", int(bool(getattr(_cycles, "with_openimagedenoise", False))))' 2>/dev/null |
  sed -n 's/^OIDN //p')

# One render in a fresh Blender; adds the whole process's wall time to its JSON.
render() {
  local n="$1"; shift
  local start end
  start=$(date +%s.%N)
  blender -b --factory-startup --python-exit-code 1 --python "$out/stage_blender.py" --python "$here/cycles_render.py" -- \
    --samples "$n" --out "$out" --seed "$seed" --threads "$threads" "$@" > "$out/blender_$n$*.log" 2>&1 ||
    { echo "render_cycles: Blender failed; see $out/blender_$n$*.log" >&2; tail -20 "$out/blender_$n$*.log" >&2; exit 1; }
  end=$(date +%s.%N)
  local name="cycles_$n"
  [[ "$*" == *--denoise* ]] && name+="_oidn"
  "$python" - "$out/$name.json" "$start" "$end" <<'EOF'
import json, sys
path, start, end = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
record = json.load(open(path))
record["seconds_process"] = end - start
json.dump(record, open(path, "w"), indent=2)
print(f"render_cycles: {record['name']}: {record['seconds_render']:.2f} s render, {end - start:.2f} s process")
EOF
}

for n in $samples; do
  render "$n"
done
for n in $denoise_samples; do
  if [[ "$oidn" == 1 ]]; then
    render "$n" --denoise
  else
    echo "render_cycles: this Blender has no OpenImageDenoise; no denoised Cycles render" >&2
  fi
done

"$python" - "$out" "$oidn" <<'EOF'
import glob, json, os, sys
out, oidn = sys.argv[1], sys.argv[2] == "1"
records = [json.load(open(p)) for p in sorted(glob.glob(os.path.join(out, "cycles_*.json")))]
json.dump({"oidn_available": oidn, "renders": records}, open(os.path.join(out, "timings.json"), "w"), indent=2)
EOF
