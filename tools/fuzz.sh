#!/usr/bin/env bash
# `make fuzz`: builds the libFuzzer harnesses (the `fuzz` preset: clang,
# ASan + UBSan) and runs each for FUZZ_SECONDS (default 60), seeded with
# every scene in scenes/ and tests/data. A crash leaves its input in
# build/fuzz/artifacts/ and fails; add it to tests/data/fuzz_regressions/, whose
# inputs the unit tests replay and the next fuzz run starts from.
set -euo pipefail
seconds=${FUZZ_SECONDS:-60}
build=build/fuzz
cmake --preset fuzz >/dev/null
cmake --build "$build" -j "$(nproc)" --target fuzz_scene_loader fuzz_overrides fuzz_usda fuzz_crate fuzz_usdz fuzz_image_header \
  fuzz_usd_mesh
mkdir -p "$build/corpus/scene" "$build/corpus/set" "$build/corpus/usda" "$build/corpus/crate" "$build/corpus/usdz" \
  "$build/corpus/image" "$build/corpus/mesh" "$build/artifacts"
# usda seeds: the USD sample files beside the repository, when present.
if [[ -d ../shared/usd-samples ]]; then
  find ../shared/usd-samples -name '*.usd*' -size -300k -exec grep -l '^#usda' {} + | while read -r f; do
    cp "$f" "$build/corpus/usda/$(echo "${f#../}" | tr / _)"
  done
fi
printf 'def Xform "A" (variants = {string v = "x"}\n prepend variantSets = "v")\n{\n variantSet "v" = { "x" { double a = 1 } }\n}\n' \
  > "$build/corpus/usda/seed1"
find scenes tests/data -name '*.yaml' -exec cp {} "$build/corpus/scene/" \;
# Image headers: the project's own small PNG and JPEG files.
find scenes tests/data \( -name '*.png' -o -name '*.jpg' -o -name '*.jpeg' \) -size -200k -exec cp {} "$build/corpus/image/" \;
cp tests/data/fuzz_regressions/* "$build/corpus/scene/"
printf '%s\n' 'render.resolution=[640,480]' '/World/Box.size=3' '/World/Box.xformOp:translate=[1,2,3]' \
  '/World/Box.exposedVar:locationRandomizer:interval=4' 'capture.frames=12' 'physics.require_settled=true' \
  '/World/Cam.orient=[0.7,0.7,0,0]' > "$build/corpus/set/seed1"
# The USD readers start from the sample packages (where ../shared/usd-samples
# exists) and the crate layers inside them.
samples=../shared/usd-samples
if [[ -d $samples ]]; then
  find "$samples" -name '*.usdz' -size -300k -exec cp {} "$build/corpus/usdz/" \;
  /usr/bin/python3 - "$samples" "$build/corpus/crate" <<'PY'
import pathlib, sys, zipfile
for package in pathlib.Path(sys.argv[1]).rglob('*.usdz'):
    with zipfile.ZipFile(package) as z:
        for name in z.namelist():
            if name.endswith('.usdc'):
                (pathlib.Path(sys.argv[2]) / (package.stem + '.usdc')).write_bytes(z.read(name))
PY
fi
# ASan's allocator keeps every size class at its peak and a 256 MB
# quarantine, so inputs that each stay under ~250 MB (the alias limits) add
# up past -rss_limit_mb in a few minutes; returning freed memory keeps the
# limit a test of each input rather than of the run's history.
export ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}allocator_release_to_os_interval_ms=100:quarantine_size_mb=32
status=0
for harness in fuzz_scene_loader fuzz_overrides fuzz_usda fuzz_crate fuzz_usdz fuzz_image_header fuzz_usd_mesh; do
  corpus=$build/corpus/scene
  [[ $harness == fuzz_overrides ]] && corpus=$build/corpus/set
  [[ $harness == fuzz_usda ]] && corpus=$build/corpus/usda
  max_len=65536
  [[ $harness == fuzz_crate ]] && corpus=$build/corpus/crate max_len=300000
  [[ $harness == fuzz_usdz ]] && corpus=$build/corpus/usdz max_len=300000
  [[ $harness == fuzz_image_header ]] && corpus=$build/corpus/image max_len=200000
  # The mesh harness builds its usda from the bytes: it starts from nothing.
  [[ $harness == fuzz_usd_mesh ]] && corpus=$build/corpus/mesh max_len=4096
  echo "fuzz: $harness for ${seconds}s"
  log=$build/artifacts/$harness.log
  if "$build/tests/fuzz/$harness" -seed="${FUZZ_SEED:-1}" -max_total_time="$seconds" -max_len=$max_len \
      -rss_limit_mb=2048 -timeout=10 -artifact_prefix="$build/artifacts/$harness-" -print_final_stats=1 \
      "$corpus" >"$log" 2>&1; then
    tail -6 "$log"
  else
    status=1
    # The report, not libFuzzer's closing statistics, is what a reader needs.
    sed -n '/^==[0-9]*==ERROR\|runtime error\|^ALARM\|out-of-memory/,/^SUMMARY/p' "$log" | head -60
    grep -h 'Test unit written to' "$log" || tail -12 "$log"
  fi
done
exit $status
