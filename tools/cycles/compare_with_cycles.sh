#!/usr/bin/env bash
# Renders a scene with sdgbehave and with Blender Cycles and compares them.
#
#   tools/cycles/compare_with_cycles.sh SCENE.yaml [--out DIR] [--resolution WxH]
#       [--ref-samples 1024] [--samples "32"] [--raster-frames 10]
#       [--pathtraced DIR] [--pathtraced-samples "256 1024"] [--denoised-samples "4"]
#       [--gpu-samples "16"] [--reuse-cycles] [--sdgbehave BIN]
#
# 1. sdgbehave runs the scene (rasterizer): DIR/raster/rgb_0000.png, its
#    run_summary.json (time per frame: seconds.render / frames, over
#    --raster-frames identical frames) and the stage after the pre-roll,
#    DIR/stage.yaml (--save-stage). Use a static scene: behaviors that move
#    things on frame 0 are not in the saved stage.
# 2. render_cycles.sh renders DIR/stage.yaml with Cycles at --ref-samples (the
#    reference) and at each of --samples, into DIR/cycles/; --reuse-cycles
#    keeps the renders already there (to add rows without the 1,024-sample
#    render again) and renders only the missing counts.
# 3. compare.py compares the rasterizer, Cycles at --samples and the
#    path-traced renders against the reference: table on stdout,
#    DIR/report.json, DIR/side_by_side.png (ours | Cycles | rasterizer).
#
# Path-traced renders, one frame each (render.mode pathtraced, linear
# radiance from writer.hdr_color), into DIR/pathtraced/ (or --pathtraced):
# - --pathtraced-samples N...: the CPU tracer without the denoiser, pt_N/;
# - --denoised-samples N...: the CPU tracer with it, pt_N_denoised/;
# - --gpu-samples N...: the GPU tracer (render.pathtracer gpu: EGL's first
#   GPU, else llvmpipe), without the denoiser, gpu_N/.
# - --pathtraced DIR alone (no counts) compares every DIR/*/hdr_color_0000.npy
#   already there, named after its folder; the time per frame comes from the
#   run_summary.json beside it, the sample count from the folder name.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
python=/usr/bin/python3

usage() { sed -n '2,30p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
[[ $# -ge 1 ]] || usage
scene="$1"
shift
out="" resolution="" ref_samples=1024 samples="32" raster_frames=10 pathtraced="" pt_samples=""
denoised_samples="" gpu_samples="" reuse_cycles=0
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
    --denoised-samples) denoised_samples="$2"; shift 2 ;;
    --gpu-samples) gpu_samples="$2"; shift 2 ;;
    --reuse-cycles) reuse_cycles=1; shift ;;
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

# One path-traced frame: N samples, the denoiser on or off, a tracer (cpu or
# gpu), its linear radiance as hdr_color_0000.npy. 32 bounces, as Cycles'
# (blender_scene.py): the default 8 leaves out light a white room still has
# after them (0.4 % of the Cornell box's).
run_pathtraced() {
  local n="$1" denoise="$2" tracer="$3" dir="$4"
  echo "== sdgbehave (path traced, $tracer): $n samples, denoiser $denoise" >&2
  "$sdgbehave" run "$scene" --frames 1 --out "$dir" --overwrite "${res_args[@]}" --quiet \
    --render-mode pathtraced --set "render.pathtracer=$tracer" --set "render.samples=$n" \
    --set render.max_bounces=32 --set "render.denoise=$denoise" --set writer.hdr_color=true
}
if [[ -n "$pt_samples$denoised_samples$gpu_samples" ]]; then
  pathtraced="${pathtraced:-$out/pathtraced}"
  for n in $pt_samples; do run_pathtraced "$n" false cpu "$pathtraced/pt_$n"; done
  for n in $denoised_samples; do run_pathtraced "$n" true cpu "$pathtraced/pt_${n}_denoised"; done
  for n in $gpu_samples; do run_pathtraced "$n" false gpu "$pathtraced/gpu_$n"; done
fi

cycles_samples=""
for n in $ref_samples $samples; do
  [[ $reuse_cycles -eq 1 && -f "$out/cycles/cycles_$n.npy" ]] || cycles_samples+="$n "
done
if [[ -n "$cycles_samples" ]]; then
  echo "== Cycles: $cycles_samples samples (the reference: $ref_samples)" >&2
  "$here/render_cycles.sh" "$out/stage.yaml" "$out/cycles" --samples "$cycles_samples" "${res_args[@]}"
fi

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
