#!/usr/bin/env bash
# bench/spmis_cost.sh [SCENE] [METHOD] [RES] [FRAMES] [OUT]: what stochastic pairwise MIS (004)
# costs against standard selection + spatial reuse (target: at most 1.2x at 640x360), per pass:
# spmis with the paper's cell search (`spmis.search=always`), with our low-confidence search, and
# standard reuse, camera path, three alternating repetitions (the machine is noisy: compare within
# one repetition), medians over frames 2 .. FRAMES-1 of metrics.csv. BASE=path/to/old/restir adds
# the paper's search and standard reuse on an older binary to each repetition (before / after in one run).
set -euo pipefail
scene=${1:-pillars}
method=${2:-restir-pt}
res=${3:-640x360}
frames=${4:-12}
out=${5:-out/bench/spmis_cost}
bin=${BIN:-build/restir}
threads=${THREADS:-2}
mkdir -p "$out"
median_cols() {
  python3 - "$1" <<'EOF'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))[2:]
med = lambda c: statistics.median(float(r[c]) for r in rows)
std = med('ms_select') + med('ms_spatial')
spmis = med('ms_cells') + med('ms_cell_search') + med('ms_spmis_canonical') + med('ms_spmis_reuse')
print('%8.1f %8.1f %8.1f %8.1f %8.1f %8.1f %8.1f %8.1f' % (med('ms_total'), med('ms_select'), med('ms_spatial'),
      med('ms_cells'), med('ms_cell_search'), med('ms_spmis_canonical'), med('ms_spmis_reuse'), std + spmis))
EOF
}
printf '%-22s %-3s %8s %8s %8s %8s %8s %8s %8s %8s\n' config rep ms/frame select spatial cells search \
  canonical reuse reuse-sum
for rep in 1 2 3; do
  configs=("spmis-always|$bin|--set spatial.reuse=spmis"
           "spmis-low-confidence|$bin|--set spatial.reuse=spmis --set spmis.search=low-confidence"
           "standard|$bin|")
  [ -n "${BASE:-}" ] &&
    configs=("spmis-always-BASE|$BASE|--set spatial.reuse=spmis" "${configs[@]}" "standard-BASE|$BASE|")
  for c in "${configs[@]}"; do
    IFS='|' read -r name b sets <<< "$c"
    d="$out/$scene-$method-$name-$rep"
    rm -rf "$d" # a run's own folder (BASE may be a restir from before --force)
    # shellcheck disable=SC2086
    "$b" render --scene "$scene" --method "$method" --res "$res" --frames "$frames" --camera path \
      --threads "$threads" $sets --out "$d" --save last > /dev/null
    printf '%-22s %-3s %s\n' "$name" "$rep" "$(median_cols "$d/metrics.csv")"
  done
done
