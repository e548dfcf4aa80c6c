#!/usr/bin/env bash
# render_hashes.sh BIN OUT: renders every built-in scene with every method along its camera path
# (3 small frames each, every frame saved), a few non-default reuse settings, file scenes and a
# reference, then prints one "sha256  path" line per EXR and PNG written, sorted. A restructuring
# that changes no behaviour leaves this list unchanged: run it before and after and diff the two.
set -euo pipefail
bin=${1:?usage: render_hashes.sh BIN OUT}
out=${2:?usage: render_hashes.sh BIN OUT}
rm -rf "$out"
mkdir -p "$out"
common=(--res 48x32 --frames 3 --camera path --save all --threads 2)
scenes=$("$bin" list | awk '$1 == "scene" { print $2 }')
methods=$("$bin" list | awk '$1 == "method" { print $2 }')
for s in $scenes; do
  for m in $methods; do
    "$bin" render --scene "$s" --method "$m" "${common[@]}" --out "$out/$s-$m" > /dev/null
  done
done
variants=(
  "restir-di spatial.reuse=spmis"
  "restir-pt spatial.reuse=spmis"
  "restir-di spatial.preset=fast"
  "restir-pt spatial.select=compat-binary"
  "restir-pt shift=reconnection"
  "restir-di mis=balance"
  "grestir-pt recon=both"
  "grestir-pt grad.base=shared"
)
for v in "${variants[@]}"; do
  read -r m set <<< "$v"
  "$bin" render --scene foliage --method "$m" --set "$set" "${common[@]}" --out "$out/variant-$m-$set" > /dev/null
done
here=$(cd "$(dirname "$0")/.." && pwd)
for f in "$here"/tests/data/scenes/*.json; do
  "$bin" render --scene "$f" --method restir-pt "${common[@]}" --out "$out/file-$(basename "$f" .json)" > /dev/null
done
gltf=/usr/share/assimp/models/glTF2/ClearCoat-glTF/ClearCoatTest.gltf
if [ -f "$gltf" ]; then
  "$bin" render --scene "$gltf" --method pt "${common[@]}" --out "$out/file-gltf" > /dev/null
fi
"$bin" reference --scene cornell --method pt --res 48x32 --spp 32 --threads 2 --out "$out/reference.exr" > /dev/null
cd "$out" && find . -name '*.exr' -o -name '*.png' | sort | xargs sha256sum
