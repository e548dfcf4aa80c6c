#!/usr/bin/env bash
# bench/splat_compare.sh [BIN] [RES] [FRAMES] [REF_SPP] [RUNS] [OUT]: a comparison of
# temporal reuse techniques for restir-pt on the camera paths of foliage, pillars, ajar and cornell:
# backproject, splat and both at equal frame count. One `restir compare` per scene with --runs RUNS
# (errors are means over the runs; temporal autocovariance of 000 Eq. 17 at lag 3 over the second
# half of the frames, RUNS >= 2) and --ref-every 8 (frames 7, 15, 23, ... against their own
# references). Prints one table from compare.csv and frames.csv.
set -euo pipefail
bin=${1:-build/restir}
res=${2:-640x360}
frames=${3:-32}
ref_spp=${4:-256}
runs=${5:-4}
out=${6:-out/splat-compare}
threads=${THREADS:-2}
mkdir -p "$out"
specs="restir-pt:temporal.reuse=backproject,restir-pt:temporal.reuse=splat,restir-pt:temporal.reuse=both"
for s in foliage pillars ajar cornell; do
  "$bin" compare --scene "$s" --camera path --res "$res" --frames "$frames" --ref-spp "$ref_spp" \
    --runs "$runs" --ref-every 8 --methods "$specs" --threads "$threads" --out "$out/$s" --force > "$out/$s.log"
done
# Columns: frame time and temporal pass (means over frames 1..), last-frame relMSE / MAPE, MAPE of
# frames 7, 15, 23, ... (every 8th, before the last), mean shares over frames 1.. (accept: history
# shifted in; bp_acc: backprojected history shifted in; spl_rec / spl_acc: a splat landed / shifted
# in), temporal autocovariance.
printf '%-8s %-11s %8s %7s %7s %6s | %-27s | %6s %6s %7s %7s | %7s\n' scene reuse ms/frame ms_temp relmse mape \
  "mape at frames 7,15,23,.." accept bp_acc spl_rec spl_acc tcov
for s in foliage pillars ajar cornell; do
  for m in backproject splat both; do
    label="restir-pt:temporal.reuse=$m"
    last=$(awk -F, -v m="$label" '$1 == m { printf "%.3f %.3f %s", $5, $6, ($10 == "" ? "-" : sprintf("%.4f", $10)) }' \
      "$out/$s/compare.csv")
    read -r relmse mape tcov <<< "$last"
    stats=$(awk -F, -v m="$label" -v last=$((frames - 1)) '$1 == m && $2 > 0 {
        ms += $4; mt += $5; a += $6; b += $8; r += $9; p += $10; n++
        if ($12 != "" && $2 != last) every = every (every == "" ? "" : ",") sprintf("%.3f", $12) }
      END { printf "%.1f %.1f %s %.3f %.3f %.3f %.3f", ms / n, mt / n, every, a / n, b / n, r / n, p / n }' \
      "$out/$s/frames.csv")
    read -r ms mt every a b r p <<< "$stats"
    printf '%-8s %-11s %8s %7s %7s %6s | %-27s | %6s %6s %7s %7s | %7s\n' "$s" "$m" "$ms" "$mt" "$relmse" "$mape" \
      "$every" "$a" "$b" "$r" "$p" "$tcov"
  done
done
