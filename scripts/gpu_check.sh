#!/usr/bin/env bash
# The checks a machine with a real GPU runs, in one go (meant to take under 5 minutes there; not yet
# run on one: no session has had a GPU since it was written), into one
# markdown report:
#   1. `carbtf devices`: which Vulkan devices there are and which one carbtf picks;
#   2. `carbtf conform` of a sample material with every built-in stiff and extreme case, on that device;
#   3. `carbtf bench synth` at 512^2 and 2048^2, with the serial and the wavefront CAR scheme each;
#   4. `carbtf bench frame` at 1920x1080 and 3840x2160, with GPU timestamps (at 1920x1080 with what each
#      part of the fragment stage costs, --parts), and at 1920x1080 again with the subspace images
#      filtered by hand (the CPU twin's arithmetic) instead of by the sampler.
# Usage: scripts/gpu_check.sh [--small] [--validation] [--carbtf PATH] [--out REPORT.md] [--work DIR]
#   --small    sizes lavapipe runs in about half a minute (a machine without a GPU, and the test of this script)
#   --validation  the Vulkan validation layer on in every device step (any message it reports fails it)
#   --carbtf   the carbtf binary (default: build/host/carbtf, built by scripts/setup.sh)
#   --out      the report (default: gpu_check.md)
#   --work     a folder for the sample, the material and the benches' own files (default: gpu_check_work);
#              it is created if missing, and only the files the steps write there are replaced
# CARBTF_DEVICE picks another device, as for every carbtf command. A failed step is reported in the
# markdown with its exit status and output, the other steps still run, and the script exits 1.
set -uo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
carbtf="$repo_root/build/host/carbtf"
report="gpu_check.md"
work="gpu_check_work"
small=0
validation=()
while (($#)); do
  case "$1" in
    --small) small=1 ;;
    --validation) validation=(--validation) ;;
    --carbtf) carbtf="${2:?--carbtf needs a path}"; shift ;;
    --out) report="${2:?--out needs a file}"; shift ;;
    --work) work="${2:?--work needs a folder}"; shift ;;
    -h | --help) sed -n '2,17p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "gpu_check.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
if [[ ! -x "$carbtf" ]]; then
  echo "gpu_check.sh: $carbtf is not an executable carbtf (run scripts/setup.sh, or pass --carbtf PATH)" >&2
  exit 2
fi

# The CPU float32 reference that bench synth times the device against runs on every core.
if ((small)); then
  sample_size=64 synth_sizes=(64 128) conform_args=(--size 64 --large-size 256 --growth-sizes 64 128)
  frames=(160x90 320x180) frame_count=3 repeats=1 texture_args=(--texture-size 64) threads=2
else
  sample_size=256 synth_sizes=(512 2048) conform_args=(--size 512)
  frames=(1920x1080 3840x2160) frame_count=30 repeats=3 texture_args=() threads=$(nproc 2>/dev/null || echo 2)
fi

mkdir -p "$work" "$(dirname "$report")" || exit 2
: >"$report" || exit 2
failures=0
started=$(date +%s)

section() { printf '\n## %s\n\n' "$1" >>"$report"; }

# Runs one step, prints its time, and puts its output into the report as a code block.
step() {
  local title="$1"
  shift
  local begin=$(date +%s) output status
  echo "gpu_check: $title" >&2
  output="$("$@" 2>&1)"
  status=$?
  section "$title"
  printf '`%s` (%s s)\n\n```\n%s\n```\n' "$*" "$(($(date +%s) - begin))" "$output" >>"$report"
  if ((status != 0)); then
    printf '\n**FAILED (exit %d)**\n' "$status" >>"$report"
    failures=$((failures + 1))
  fi
  return $status
}

printf '# carbtf GPU check\n\n%s, %s sizes, on %s\n' "$(date -u '+%Y-%m-%d %H:%M UTC')" \
  "$( ((small)) && echo lavapipe || echo full)" "$(uname -n)" >>"$report"
step "devices" "$carbtf" devices

material="$work/material.cbtf"
if step "sample material (leather, ${sample_size}^2)" "$carbtf" sample leather --size "$sample_size" --out "$work/sample" &&
  step "analysis" "$carbtf" analyze "$work/sample/btf" --out "$material"; then
  step "conform, every extreme case" "$carbtf" conform "$material" "${conform_args[@]}" "${validation[@]}"
  for scheme in serial wavefront; do
    out="$work/bench_synth_$scheme"
    step "bench synth, $scheme scheme" "$carbtf" bench synth --material "$material" --sizes "${synth_sizes[@]}" \
      --base-size "${synth_sizes[0]}" --subspace-counts 20 --size-sweep-subspaces 20 --repeats "$repeats" \
      --scheme "$scheme" --cpu-threads "$threads" --out "$out" "${validation[@]}"
  done
  for frame in "${frames[@]}"; do
    out="$work/bench_frame_$frame"
    # The first size also times each part of the fragment stage (--parts).
    parts=()
    [[ "$frame" == "${frames[0]}" ]] && parts=(--parts)
    step "bench frame, $frame" "$carbtf" bench frame --material "$material" --width "${frame%x*}" --height "${frame#*x}" \
      --frames "$frame_count" "${texture_args[@]}" "${parts[@]}" --out "$out" "${validation[@]}"
  done
  frame="${frames[0]}"
  step "bench frame, $frame, filtered by hand" "$carbtf" bench frame --material "$material" --width "${frame%x*}" \
    --height "${frame#*x}" --frames "$frame_count" "${texture_args[@]}" --hand-filtering \
    --out "$work/bench_frame_${frame}_by_hand" "${validation[@]}"
fi

section "summary"
printf '%d failed steps, %d s in all\n' "$failures" "$(($(date +%s) - started))" >>"$report"
echo "gpu_check: wrote $report ($failures failed steps)" >&2
((failures == 0))
