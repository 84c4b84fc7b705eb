#!/usr/bin/env bash
# The GPU path tracer's figures (docs/performance.md) on a machine with an
# NVIDIA GPU and no build tools, in two steps:
#
#   tools/gpu-bench.sh bundle BUILD_DIR OUT_DIR   # here: the binaries, their
#       # shared libraries (not glibc's, not the GL loaders) and the scenes into OUT_DIR
#   OUT_DIR/gpu-bench.sh run OUT_DIR               # there: prints one JSON row per figure
#
# The GL loader libraries (libegl1, libglvnd0, libopengl0, libgl1, libglx0)
# must be installed there; with the device tool, unpack the carried .debs
# first (/work/shared/gpu/README.md).
set -euo pipefail
mode=${1:?usage: gpu-bench.sh bundle BUILD_DIR OUT_DIR | run BUNDLE_DIR}
if [ "$mode" = bundle ]; then
  build=${2:?BUILD_DIR}
  out=${3:?OUT_DIR}
  mkdir -p "$out/bin" "$out/lib"
  cp "$build/app/sdgbehave" "$build/tools/sdg_bench_pathtrace" "$build/tools/sdg_tracer_agreement" "$out/bin/"
  cp "$0" "$out/gpu-bench.sh"
  cp -r scenes "$out/"
  for exe in "$out"/bin/*; do
    ldd "$exe" | awk '/=> \// {print $3}' | while read -r lib; do
      case "$(basename "$lib")" in
        libc.so*|libm.so*|libdl.so*|libpthread.so*|librt.so*|ld-linux*|libgcc_s.so*|libstdc++.so*) ;;
        libEGL*|libGL*|libOpenGL*|libGLX*|libGLdispatch*) ;;
        *) cp -Ln "$lib" "$out/lib/" ;;
      esac
    done
  done
  # libstdc++ too: Debian 12's is newer than some hosts'.
  cp -L "$(ldd "$out/bin/sdgbehave" | awk '/libstdc\+\+/ {print $3}')" "$out/lib/"
  du -sh "$out"
  exit 0
fi
bundle=$(cd "${2:?BUNDLE_DIR}" && pwd)
export LD_LIBRARY_PATH="$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
bin="$bundle/bin"
cores=$(nproc)
work=$(mktemp -d)
cd "$bundle"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader || true
# The demo's stage after its pre-roll, as tools/bench.sh makes it.
"$bin/sdgbehave" run scenes/warehouse.yaml --frames 1 --seed 10 --out "$work/st" --backend egl \
  --save-stage "$work/demo_stage.yaml" > /dev/null 2>&1
# A fresh machine's GPU idles at a fraction of its clock and ramps up only
# under load: one unmeasured invocation first (docs/performance.md).
"$bin/sdg_bench_pathtrace" "$work/demo_stage.yaml" 512 512 4 "$cores" denoise gpu > /dev/null
nvidia-smi --query-gpu=clocks.sm,pstate --format=csv,noheader || true
set -x
"$bin/sdg_bench_pathtrace" "$work/demo_stage.yaml" 512 512 4 "$cores" denoise gpu
# Each frame's stages (setup, tracing, denoising, read-back) on stderr.
SDG_GPU_TIMING=1 "$bin/sdg_bench_pathtrace" "$work/demo_stage.yaml" 512 512 4 "$cores" denoise gpu
"$bin/sdg_bench_pathtrace" "$work/demo_stage.yaml" 512 512 4 "$cores" gpu
"$bin/sdg_bench_pathtrace" "$work/demo_stage.yaml" 512 512 4 "$cores" denoise
"$bin/sdg_bench_pathtrace" scenes/examples/cornell_box.yaml 256 256 1024 "$cores" gpu
"$bin/sdg_bench_pathtrace" scenes/examples/cornell_box.yaml 256 256 64 "$cores"
"$bin/sdg_tracer_agreement" scenes/examples/cornell_box.yaml 256 256 1024 "$cores"
"$bin/sdg_tracer_agreement" "$work/demo_stage.yaml" 256 256 1024 "$cores"
for run in 1 2; do  # the second is the figure: the first compiles the kernels into the driver's cache
  "$bin/sdgbehave" run scenes/warehouse.yaml --render-mode pathtraced --samples 4 --set render.denoise=true \
    --set render.pathtracer=gpu --backend egl --threads "$cores" --seed 10 --frames 300 --overwrite \
    --out "$work/run$run" > /dev/null
done
grep -o '"frames_per_second": [0-9.]*' "$work/run2/run_summary.json"
set +x
rm -rf "$work"
