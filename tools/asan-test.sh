#!/usr/bin/env bash
# The suite under ASan + UBSan + LeakSanitizer (make asan).
#
# intercept_tls_get_addr=0: this libasan (GCC 12) guesses where a dynamic
# TLS block starts from a header that some older glibc versions put in
# front of it. Debian 12's glibc allocates those blocks with malloc, so when
# one lands 16 bytes into a page the guess reads ASan's own chunk header, and
# at exit LeakSanitizer scans from a bogus address near zero and its tracer
# dies ("Tracer caught signal 11: addr=0x2340", seen in CI). Only Mesa's
# dlopen'ed libraries have dynamic TLS; sdgbehave's thread-locals are static
# TLS, which is still scanned.
#
# Should the tracer still crash (a fault of the sanitizer runtime, not a
# leak), the tests that failed only that way run once more; any real finding
# (a leak report, an ASan or UBSan error, a failed check) fails the run.
set -uo pipefail
build=${1:?usage: tools/asan-test.sh BUILD_DIR}
jobs=${JOBS:-$(nproc)}
root=$(cd "$(dirname "$0")/.." && pwd)

export ASAN_OPTIONS=detect_leaks=1:intercept_tls_get_addr=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$root/tests/lsan.supp

log=$(mktemp)
trap 'rm -f "$log"' EXIT
cd "$build" || exit 1
# Tests labelled release_only run in the release suite only (tests/CMakeLists.txt
# says which and why). -O1 -g1 (CMakePresets.json): ASan's recommended level,
# and line tables are all its reports need; -O2 -g took twice the build time.
ctest --output-on-failure -j "$jobs" -LE release_only 2>&1 | tee "$log"
[ "${PIPESTATUS[0]}" -eq 0 ] && exit 0

tracer_crashes=$(grep -c "LeakSanitizer has encountered a fatal error" "$log")
real_findings=$(grep -cE "ERROR: (AddressSanitizer|LeakSanitizer: detected)|runtime error:|\.cpp:[0-9]+: FAILED:" "$log")
if [ "$tracer_crashes" -eq 0 ] || [ "$real_findings" -ne 0 ]; then
  exit 1
fi
echo "asan: $tracer_crashes LeakSanitizer tracer crash(es) and no other finding; running the failed tests once more"
ctest --rerun-failed --output-on-failure -j "$jobs"
