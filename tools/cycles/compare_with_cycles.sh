#!/usr/bin/env bash
# Renders a scene with sdgbehave and with Blender Cycles and compares them.
#
#   tools/cycles/compare_with_cycles.sh SCENE.yaml [--out DIR] [--resolution WxH]
#       [--ref-samples 1024] [--samples "32"] [--raster-frames 10]
#       [--pathtraced DIR] [--pathtraced-samples "16 64 256"] [--sdgbehave BIN]
#
# 1. sdgbehave runs the scene (rasterizer): DIR/raster/rgb_0000.png, its
#    run_summary.json (time per frame: seconds.render / frames, over
#    --raster-frames identical frames) and the stage after the pre-roll,
#    DIR/stage.yaml (--save-stage). Use a static scene: behaviors that move
#    things on frame 0 are not in the saved stage.
# 2. render_cycles.sh renders DIR/stage.yaml with Cycles at --ref-samples (the
#    reference) and at each of --samples, into DIR/cycles/.
# 3. compare.py compares the rasterizer, Cycles at --samples and any
#    path-traced renders against the reference: table on stdout,
#    DIR/report.json, DIR/side_by_side.png (ours | Cycles | rasterizer).
#
# Path-traced renders (the hook for `--render-mode pathtraced`):
# - --pathtraced DIR compares every DIR/*/hdr_color_0000.npy (linear radiance,
#   H x W x 3 float, rows top first) it finds, named after its folder, e.g.
#   DIR/pt_16/, DIR/pt_16_denoised/, ...; the time per frame comes from the
#   run_summary.json beside it, the sample count from run_summary.json's
#   render.samples if present, else from the folder name.
# - --pathtraced-samples "16 64 256" first renders those folders itself with
#   run_pathtraced() below, into DIR/pathtraced/; its flags are a guess at the
#   coming interface (marked TODO) and must be checked when it lands.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
python=/usr/bin/python3

usage() { sed -n '2,28p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
[[ $# -ge 1 ]] || usage
scene="$1"
shift
out="" resolution="" ref_samples=1024 samples="32" raster_frames=10 pathtraced="" pt_samples=""
sdgbehave="$root/build/release/app/sdgbehave"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --out) out="$2"; shift 2 ;;
    --resolution) resolution="$2"; shift 2 ;;
    --ref-samples) ref_samples="$2"; shift 2 ;;
    --samples) samples="$2"; shift 2 ;;
    --raster-frames) raster_frames="$2"; shift 2 ;;
    --pathtraced) pathtraced="$2"; shift 2 ;;
    --pathtraced-samples) pt_samples="$2"; shift 2 ;;
    --sdgbehave) sdgbehave="$2"; shift 2 ;;
    *) usage ;;
  esac
done
out="${out:-out/cycles_compare/$(basename "${scene%.*}")}"
mkdir -p "$out"
res_args=()
[[ -n "$resolution" ]] && res_args=(--resolution "$resolution")

echo "== sdgbehave (rasterizer): $scene" >&2
"$sdgbehave" run "$scene" --frames "$raster_frames" --out "$out/raster" --overwrite \
  --save-stage "$out/stage.yaml" "${res_args[@]}" --quiet

# TODO(path tracer): the flags below are a guess at the coming interface
# (a render mode, a sample count, a denoiser switch and a writer option that
# writes linear radiance as hdr_color_XXXX.npy). Adjust them when it lands;
# compare.py needs only the .npy and the run_summary.json beside it.
run_pathtraced() {
  local n="$1" denoise="$2" dir="$3"
  "$sdgbehave" run "$scene" --frames 1 --out "$dir" --overwrite "${res_args[@]}" --quiet \
    --render-mode pathtraced --set "render.samples=$n" --set "render.denoise=$denoise" \
    --set writer.hdr_color=true
}
if [[ -n "$pt_samples" ]]; then
  pathtraced="${pathtraced:-$out/pathtraced}"
  for n in $pt_samples; do
    echo "== sdgbehave (path traced): $n samples" >&2
    run_pathtraced "$n" false "$pathtraced/pt_$n"
    run_pathtraced "$n" true "$pathtraced/pt_${n}_denoised"
  done
fi

echo "== Cycles: $ref_samples (reference) and $samples samples" >&2
"$here/render_cycles.sh" "$out/stage.yaml" "$out/cycles" --samples "$ref_samples $samples" "${res_args[@]}"

candidates=("rasterizer=$out/raster/rgb_0000.png")
for n in $samples; do
  candidates+=("cycles_$n=$out/cycles/cycles_$n.npy")
  [[ -f "$out/cycles/cycles_${n}_oidn.npy" ]] && candidates+=("cycles_${n}_oidn=$out/cycles/cycles_${n}_oidn.npy")
done
if [[ -n "$pathtraced" ]]; then
  while IFS= read -r f; do
    candidates+=("$(basename "$(dirname "$f")")=$f")
  done < <(find "$pathtraced" -name 'hdr_color_0000.npy' | sort -V)
fi

echo "== compare" >&2
"$python" "$here/compare.py" --reference "$out/cycles/cycles_$ref_samples.npy" "${candidates[@]}" \
  --json "$out/report.json" --side-by-side "$out/side_by_side.png"
"$python" - "$out/cycles/timings.json" <<'EOF'
import json, sys
for r in json.load(open(sys.argv[1]))["renders"]:
    print(f"{r['name']}: {r['seconds_render']:.2f} s render inside Blender, {r['seconds_process']:.2f} s whole process")
EOF
echo "report: $out/report.json, $out/side_by_side.png" >&2
