#!/usr/bin/env bash
# bench/pt_options_compare.sh [BIN] [RES] [REF_SPP] [SEEDS] [OUT]: two sets of pt's settings, A and B
# (environment: A="sampler=independent", B="sampler=sobol" by default; space-separated key=value),
# at equal samples and equal time. Per scene (SCENES: built-in names or scene files): a reference of
# REF_SPP paths per pixel with pt's defaults, then for each spp in SPPS (1 4 16 64), SEEDS seeded
# one-frame renders with A and with B against it. Prints per (scene, spp) the mean relMSE and MAPE
# over the seeds, the mean frame time, and the B / A ratios of MAPE and of relMSE x time (below 1:
# B reaches the error sooner). Machines are noisy: A and B run alternately, seed by seed.
# METHOD (default pt) renders with another method that reads A's and B's settings (restir-pt reads
# the walk's lights.*), FRAMES frames (default 1) from a static camera, the last frame's error
# measured; spp is then pt's only and SPPS is ignored.
set -euo pipefail
bin=${1:-build/restir}
res=${2:-160x120}
ref_spp=${3:-2048}
seeds=${4:-4}
out=${5:-out/pt-options-compare}
threads=${THREADS:-2}
scenes=${SCENES:-cornell ajar many-lights}
spps=${SPPS:-1 4 16 64}
method=${METHOD:-pt}
frames=${FRAMES:-1}
[ "$method" = pt ] || spps=1
a_sets=${A:-sampler=independent}
b_sets=${B:-sampler=sobol}
sets_args() { for kv in $1; do printf -- '--set %s ' "$kv"; done; }
mkdir -p "$out"
echo "$method, $frames frame(s); A: $a_sets; B: $b_sets"
echo "| scene | spp | relMSE A | relMSE B | MAPE A | MAPE B | ms A | ms B | MAPE ratio | relMSE x time ratio |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for scene in $scenes; do
  name=$(basename "$scene" .json)
  ref="$out/ref_${name}_${res}_${ref_spp}.exr"
  [ -f "$ref" ] || "$bin" reference --scene "$scene" --method pt --res "$res" --spp "$ref_spp" --threads "$threads" \
    --out "$ref" > /dev/null
  for spp in $spps; do
    rm -f "$out/runs.txt"
    for seed in $(seq 1 "$seeds"); do
      for side in A B; do
        sets=$a_sets
        [ "$side" = B ] && sets=$b_sets
        # shellcheck disable=SC2046
        spp_set=""
        [ "$method" = pt ] && spp_set="spp=$spp"
        line=$("$bin" render --scene "$scene" --method "$method" --res "$res" --frames "$frames" --seed "$seed" \
          --threads "$threads" $(sets_args "$spp_set $sets") --ref "$ref" --save last --out "$out/render" --force |
          grep "ms/frame")
        ms=$(sed -n 's/.*: \([0-9.]*\) ms\/frame.*/\1/p' <<< "$line")
        relmse=$(sed -n 's/.*relMSE \([0-9.e+-]*\).*/\1/p' <<< "$line")
        mape=$(sed -n 's/.* MAPE \([0-9.e+-]*\) SMAPE.*/\1/p' <<< "$line")
        echo "$side $ms $relmse $mape" >> "$out/runs.txt"
      done
    done
    awk -v scene="$name" -v spp="$spp" '
      { n[$1]++; ms[$1] += $2; rel[$1] += $3; mape[$1] += $4 }
      END {
        for (s in n) { ms[s] /= n[s]; rel[s] /= n[s]; mape[s] /= n[s] }
        printf "| %s | %d | %.4g | %.4g | %.4g | %.4g | %.1f | %.1f | %.3f | %.3f |\n", scene, spp,
               rel["A"], rel["B"], mape["A"], mape["B"], ms["A"], ms["B"],
               mape["B"] / mape["A"], (rel["B"] * ms["B"]) / (rel["A"] * ms["A"])
      }' "$out/runs.txt"
  done
done
