#!/usr/bin/env bash
# render_hashes.sh BIN OUT: renders every built-in scene with every method along its camera path
# (3 small frames each, every frame saved), each method's variants (non-default settings of its own
# code paths, listed in its registry row) on foliage, file scenes and a reference, then prints one
# "sha256  path" line per EXR and PNG written, sorted. A restructuring that changes no behaviour
# leaves this list unchanged: run it before and after and diff the two.
set -euo pipefail
bin=${1:?usage: render_hashes.sh BIN OUT}
out=${2:?usage: render_hashes.sh BIN OUT}
here=$(cd "$(dirname "$0")/.." && pwd)
# Scenes, methods, variants and the methods picked below come from the registry (`restir list --json`,
# read by scripts/registry.py), so a new method or variant is rendered without editing this script.
registry() { python3 "$here/scripts/registry.py" "$bin" "$@"; }
scenes=$(registry scenes)
methods=$(registry methods)
variants=$(registry variants)  # "METHOD key=value[:key=value...]" per line: each method row's .variants
reference=$(registry role reference)
reservoirs=$(registry first path-reservoirs) # the first path-reservoir method renders the file scenes
rm -rf "$out"
mkdir -p "$out"
common=(--res 48x32 --frames 3 --camera path --save all --threads 2)
for s in $scenes; do
  for m in $methods; do
    "$bin" render --scene "$s" --method "$m" "${common[@]}" --out "$out/$s-$m" > /dev/null
  done
done
while read -r m v; do
  [ -n "$m" ] || continue # no variants at all: one empty line
  sets=()
  IFS=: read -r -a assignments <<< "$v"
  for a in "${assignments[@]}"; do sets+=(--set "$a"); done
  "$bin" render --scene foliage --method "$m" "${sets[@]}" "${common[@]}" --out "$out/variant-$m-$v" \
    > /dev/null < /dev/null
done <<< "$variants"
for f in "$here"/tests/data/scenes/*.json; do
  "$bin" render --scene "$f" --method "$reservoirs" "${common[@]}" --out "$out/file-$(basename "$f" .json)" > /dev/null
done
gltf=/usr/share/assimp/models/glTF2/ClearCoat-glTF/ClearCoatTest.gltf
if [ -f "$gltf" ]; then
  "$bin" render --scene "$gltf" --method "$reference" "${common[@]}" --out "$out/file-gltf" > /dev/null
fi
"$bin" reference --scene cornell --method "$reference" --res 48x32 --spp 32 --threads 2 \
  --out "$out/reference.exr" > /dev/null
cd "$out" && find . -name '*.exr' -o -name '*.png' | sort | xargs sha256sum
