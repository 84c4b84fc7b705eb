#!/bin/sh
# Runs the [samples] tests of sdg_usd_tests (real files in ../shared/usd-samples),
# or exits 77 (skipped) with the reason when that folder is absent.
# Usage: run_samples.sh TEST_EXE SAMPLES_DIR
if [ ! -d "$2/test_assets" ] || [ ! -d "$2/full_assets" ]; then
  echo "SKIP: the USD sample files are not at $2 (expected beside the repository, in ../shared/usd-samples)"
  exit 77
fi
exec "$1" "[samples]"
