#!/bin/bash
# bench/assimp_models.sh [BIN] [--set ...]: how a new user fares with `restir scene info FILE` on the
# first 400 model files of assimp-testmodels. Writes $OUT/models400.out (default /tmp).
bin=${1:-build/restir}
find /usr/share/assimp/models /usr/share/assimp/models-nonbsd -type f 2>/dev/null | \
  grep -viE '\.(png|jpg|jpeg|bmp|tga|dds|gif|tif|tiff|bin|mtl|txt|md|license|pdf|ktx2|webp|hdr|exr|psd|ini|xcf|zip)$' | \
  grep -viE '/(license|readme)' | sort | head -400 > ${OUT:-/tmp}/models400.txt
: > ${OUT:-/tmp}/models400.out
while read -r f; do
  out=$(OMP_NUM_THREADS=1 timeout 60 "$bin" scene info "$f" "${@:2}" 2>&1 >/dev/null); rc=$?
  if [ $rc -eq 0 ]; then
    if echo "$out" | grep -q "default sky"; then echo "load-sky $f"; else echo "load $f"; fi
  elif echo "$out" | grep -q "no emissive\|no emitter"; then echo "no-emitter $f"
  elif echo "$out" | grep -qi "texture"; then echo "texture $f"
  else echo "refused($rc) $f :: ${out:0:160}"; fi
done < ${OUT:-/tmp}/models400.txt > ${OUT:-/tmp}/models400.out
awk '{print $1}' ${OUT:-/tmp}/models400.out | sed 's/(.*//' | sort | uniq -c
