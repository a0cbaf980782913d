#!/usr/bin/env bash
# The acceptance sweep of issue 42 (docs/design.md 5.2): each built-in sample analysed once, then
# `carbtf fidelity` over the five default pairs and over `--spread 16`, per fidelity seed. Prints per
# sample the mean structure score s (five / spread16, all seeds together), how many pair-seeds beat
# the Gaussian reference (s < 1), the worst pair and the material's size; keeps every CSV under OUT.
#
#   scripts/fidelity_sweep.sh OUT [ANALYZE OPTIONS...]
#   env: CARBTF_BIN (build/host/carbtf), SIZE (256), SEEDS ("1 2 3"),
#        SAMPLES ("leather fabric coast_sand_rocks"), SAMPLE_DIR (OUT/samples; reused when present)
#
# About 4-5 minutes at 256^2 with seeds 1-3 on a 2-core machine with lavapipe.
set -euo pipefail
[[ $# -ge 1 ]] || { sed -n 2,10p "$0" >&2; exit 2; }
out="$1"
shift
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
carbtf="${CARBTF_BIN:-$root/build/host/carbtf}"
[[ -x "$carbtf" ]] || { echo "fidelity_sweep.sh: no carbtf at $carbtf (run scripts/setup.sh)" >&2; exit 1; }
size="${SIZE:-256}"
seeds="${SEEDS:-1 2 3}"
samples="${SAMPLES:-leather fabric coast_sand_rocks}"
sample_dir="${SAMPLE_DIR:-$out/samples}"
mkdir -p "$out" "$sample_dir"

printf '%-18s %14s %16s %9s %9s  %s\n' sample "s five" "s spread16" "s<1" bytes "worst pair (s, seed)"
for sample in $samples; do
  data="$sample_dir/$sample-$size"
  [[ -d "$data/btf" ]] || "$carbtf" sample "$sample" --size "$size" --out "$data" > /dev/null
  run="$out/$sample"
  mkdir -p "$run"
  "$carbtf" analyze "$data/btf" "$@" --out "$run/material.cbtf" > "$run/analyze.log" 2>&1 ||
    { echo "fidelity_sweep.sh: analyze failed on $sample, see $run/analyze.log" >&2; exit 1; }
  for seed in $seeds; do
    "$carbtf" fidelity "$run/material.cbtf" "$data/btf" --seed "$seed" --out "$run/five_$seed" > /dev/null
    "$carbtf" fidelity "$run/material.cbtf" "$data/btf" --seed "$seed" --spread 16 \
      --out "$run/spread_$seed" > /dev/null
  done
  bytes=$(stat -c %s "$run/material.cbtf")
  # The CSV's columns: light_theta 3, light_phi 4, view_theta 5, view_phi 6, structure 8.
  awk -F, -v name="$sample" -v bytes="$bytes" '
    FNR == 1 { spread = (FILENAME ~ /spread_/); seed = FILENAME; sub(/.*_/, "", seed); sub(/\/.*/, "", seed); next }
    {
      s = $8
      if (spread) { ss += s; ns++; if (s < 1) beat++ } else { fs += s; nf++ }
      if (s > worst) { worst = s; pair = sprintf("(%s,%s)/(%s,%s) %.3f, seed %s", $3, $4, $5, $6, s, seed) }
    }
    END { printf "%-18s %14.3f %16.3f %4d of %2d %9d  %s\n", name, fs / nf, ss / ns, beat, ns, bytes, pair }
  ' "$run"/five_*/fidelity.csv "$run"/spread_*/fidelity.csv
done
