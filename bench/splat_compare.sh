#!/usr/bin/env bash
# bench/splat_compare.sh [BIN] [RES] [FRAMES] [REF_SPP] [OUT]: issue 22's comparison of temporal
# reuse techniques for restir-pt on the camera paths of foliage, pillars, ajar and cornell:
# backproject, splat and both, equal frame count, last frame against a pt reference; then each
# technique's per-frame temporal candidate shares from metrics.csv (render). Prints one table.
set -euo pipefail
bin=${1:-build/restir}
res=${2:-640x360}
frames=${3:-32}
ref_spp=${4:-256}
out=${5:-out/splat-compare}
mkdir -p "$out"
specs="restir-pt:temporal.reuse=backproject,restir-pt:temporal.reuse=splat,restir-pt:temporal.reuse=both"
for s in foliage pillars ajar cornell; do
  "$bin" compare --scene "$s" --camera path --res "$res" --frames "$frames" --ref-spp "$ref_spp" \
    --methods "$specs" --threads 2 --out "$out/$s" > "$out/$s.log"
  for m in backproject splat both; do
    "$bin" render --scene "$s" --method restir-pt --camera path --res "$res" --frames "$frames" --threads 2 \
      --set temporal.reuse=$m --out "$out/$s-render-$m" > /dev/null
  done
done
printf '%-8s %-12s %9s %9s %9s %9s | %7s %7s %7s %7s %7s\n' scene reuse ms/frame relmse mape smape \
  accept bp_acc spl_rec spl_acc ms_temp
for s in foliage pillars ajar cornell; do
  for m in backproject splat both; do
    row=$(awk -F, -v m="temporal.reuse=$m" 'index($1, m) { print $2, $5, $6, $7 }' "$out/$s/compare.csv")
    stats=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
      NR > 2 { a += $c["temporal_accept"]; b += $c["bp_accepted"]; r += $c["splat_received"];
               p += $c["splat_accepted"]; t += $c["ms_temporal"]; n++ }
      END { printf "%.3f %.3f %.3f %.3f %.1f", a / n, b / n, r / n, p / n, t / n }' "$out/$s-render-$m/metrics.csv")
    printf '%-8s %-12s %9s %9s %9s %9s | %7s %7s %7s %7s %7s\n' "$s" "$m" $row $stats
  done
done
