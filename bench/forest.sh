#!/usr/bin/env bash
# bench/forest.sh [BIN] [RES] [FRAMES] [REF_SPP] [OUT]: measurements on the built-in
# forest (75,000 alpha-masked leaf cards under a sky with a sun), static camera:
#  1. cost per frame and per pass of pt (1 spp), restir-di and restir-pt with the alpha masks on
#     and off (`--set scene.alpha=off`: the same geometry with opaque cards; another scene, so
#     only its times mean anything), two alternating repetitions, means over frames 1 .. FRAMES-1
#     of metrics.csv;
#  2. equal-time error of pt against restir-di (direct light, pt at 1 bounce) and restir-pt
#     (`restir compare --equal-time`, last frame against a REF_SPP reference of the same camera).
# The references are resumable (`restir reference`, written once into OUT and reused).
set -euo pipefail
bin=${1:-build/restir}
res=${2:-640x360}
frames=${3:-16}
ref_spp=${4:-1024}
out=${5:-out/bench/forest}
threads=${THREADS:-2}
mkdir -p "$out"
for m in restir-pt restir-di; do
  ref="$out/ref-$m-$res-$ref_spp.exr"
  [ -f "$ref" ] || "$bin" reference --scene forest --method "$m" --res "$res" --spp "$ref_spp" --threads "$threads" \
    --checkpoint-every 60 --out "$ref" > "$out/ref-$m.log"
done
# 1. costs: columns of metrics.csv averaged over frames 1.. (frame 0 has no history)
mean_cols() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
    $1 > 0 { n++; t += $col["ms_total"]; g += $col["ms_gbuffer"]; ini += $col["ms_initial"];
             tem += $col["ms_temporal"]; spa += $col["ms_spatial"] + $col["ms_select"]; sh += $col["ms_shade"];
             pt += $col["ms_pt"]; r += $col["rays"]; mr += $col["mrays_per_s"] }
    END { printf "%8.1f %8.1f %8.1f %8.1f %8.1f %8.1f %8.1f %6.2f %6.2f\n", t / n, g / n, ini / n, tem / n,
          spa / n, sh / n, pt / n, r / n / (W * H), mr / n }' W="${res%x*}" H="${res#*x}" "$1"
}
printf '%-10s %-5s %-4s %8s %8s %8s %8s %8s %8s %8s %6s %6s\n' method alpha rep ms/frame gbuffer initial temporal \
  spatial shade pt rays/px Mrays/s
for rep in 1 2; do
  for m in pt restir-di restir-pt; do
    for a in on off; do
      d="$out/cost-$m-alpha-$a-$rep"
      "$bin" render --scene forest --method "$m" --res "$res" --frames "$frames" --threads "$threads" \
        --set scene.alpha=$a --out "$d" --force > /dev/null
      printf '%-10s %-5s %-4s %s\n' "$m" "$a" "$rep" "$(mean_cols "$d/metrics.csv")"
    done
  done
done
# 2. equal time, static camera, the last frame against the reference
for m in restir-di restir-pt; do
  "$bin" compare --scene forest --methods "$m,pt" --equal-time --frames "$frames" --res "$res" \
    --ref "$out/ref-$m-$res-$ref_spp.exr" --threads "$threads" --out "$out/equal-time-$m" --force \
    > "$out/equal-time-$m.log"
  awk -F, -v m="$m" 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
    { rel[$1] = $col["relmse"]; printf "%-10s ms/frame %8.1f spp %3s instances %3s relMSE %.5f MAPE %.4f\n", $1,
        $col["ms_per_frame"], $col["spp"], $col["instances"], $col["relmse"], $col["mape"] }
    END { printf "equal-time relMSE(pt) / relMSE(%s) = %.2f\n", m, rel["pt"] / rel[m] }' "$out/equal-time-$m/compare.csv"
done
