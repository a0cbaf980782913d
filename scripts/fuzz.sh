#!/usr/bin/env bash
# Long fuzzing runs of every parser of outside input, under ASan + UBSan (libFuzzer, clang):
#   scripts/fuzz.sh [RUNS] [SECONDS_PER_TARGET]      (defaults: 1000000 runs, 3600 s cap per target)
# Builds the sanitized tree in build/tests/sanitize (as the `sanitize` and `fuzz` CTest labels do) and
# runs each target; a finding stops the script and its input is left in build/tests/sanitize/fuzz_artifacts.
set -euo pipefail
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cmake -DSOURCE_DIR="$repo_root" -DWORK_DIR="$repo_root/build/tests/sanitize" -DRUNS="${1:-1000000}" -DSECONDS="${2:-3600}" \
  -P "$repo_root/tests/fuzz/run_fuzz.cmake"
