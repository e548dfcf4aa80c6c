#!/usr/bin/env bash
# bench/sampler_compare.sh [BIN] [RES] [REF_SPP] [SEEDS] [OUT]: pt's samplers at equal samples
# and equal time. Per scene: a reference of REF_SPP paths per pixel (sampler=independent), then for
# spp in 1 4 16 64, SEEDS seeded one-frame renders with sampler=independent and sampler=sobol
# against it. Prints per (scene, spp) the mean relMSE and MAPE over the seeds, the mean frame time,
# and the sobol / independent ratios of MAPE and of relMSE x time (below 1: sobol reaches the
# error sooner). Machines are noisy: the two samplers run alternately, seed by seed.
set -euo pipefail
bin=${1:-build/restir}
res=${2:-160x120}
ref_spp=${3:-2048}
seeds=${4:-4}
out=${5:-out/sampler-compare}
threads=${THREADS:-2}
scenes=${SCENES:-cornell ajar many-lights}
mkdir -p "$out"
echo "| scene | spp | relMSE independent | relMSE sobol | MAPE independent | MAPE sobol | ms independent | ms sobol | MAPE ratio | relMSE x time ratio |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for scene in $scenes; do
  ref="$out/ref_${scene}_${res}_${ref_spp}.exr"
  [ -f "$ref" ] || "$bin" reference --scene "$scene" --method pt --res "$res" --spp "$ref_spp" --threads "$threads" \
    --out "$ref" > /dev/null
  for spp in 1 4 16 64; do
    rm -f "$out/runs.txt"
    for seed in $(seq 1 "$seeds"); do
      for sampler in independent sobol; do
        line=$("$bin" render --scene "$scene" --method pt --res "$res" --frames 1 --seed "$seed" --threads "$threads" \
          --set spp="$spp" --set sampler="$sampler" --ref "$ref" --save last --out "$out/render" | grep "ms/frame")
        ms=$(sed -n 's/.*: \([0-9.]*\) ms\/frame.*/\1/p' <<< "$line")
        relmse=$(sed -n 's/.*relMSE \([0-9.e+-]*\).*/\1/p' <<< "$line")
        mape=$(sed -n 's/.* MAPE \([0-9.e+-]*\) SMAPE.*/\1/p' <<< "$line")
        echo "$sampler $ms $relmse $mape" >> "$out/runs.txt"
      done
    done
    awk -v scene="$scene" -v spp="$spp" '
      { n[$1]++; ms[$1] += $2; rel[$1] += $3; mape[$1] += $4 }
      END {
        for (s in n) { ms[s] /= n[s]; rel[s] /= n[s]; mape[s] /= n[s] }
        printf "| %s | %d | %.4g | %.4g | %.4g | %.4g | %.1f | %.1f | %.3f | %.3f |\n", scene, spp,
               rel["independent"], rel["sobol"], mape["independent"], mape["sobol"], ms["independent"], ms["sobol"],
               mape["sobol"] / mape["independent"], (rel["sobol"] * ms["sobol"]) / (rel["independent"] * ms["independent"])
      }' "$out/runs.txt"
  done
done
