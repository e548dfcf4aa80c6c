#!/bin/sh
# scripts/tsan.sh BUILD: every method of the restir command in BUILD (a RESTIR_TSAN=ON build, `make
# tsan`) renders a short camera path at tiny sizes on 2 OpenMP threads under ThreadSanitizer, with
# Archer (LLVM's OpenMP tool) telling it about OpenMP's barriers, and with each reuse variant, the
# denoisers and the gradient methods; then a compare (its reference and runs). Exits 66 at
# the first race reported (halt_on_error), 1 when a command fails otherwise.
set -eu
build=$1
bin=$build/restir
[ -x "$bin" ] || { echo "tsan.sh: $bin is missing (make tsan builds it)" >&2; exit 2; }
archer=$(sed -n 's/^RESTIR_ARCHER:FILEPATH=//p' "$build/CMakeCache.txt")
[ -f "$archer" ] || { echo "tsan.sh: $build was not configured with RESTIR_TSAN=ON" >&2; exit 2; }
export OMP_NUM_THREADS=2 OMP_TOOL_LIBRARIES="$archer"
export TSAN_OPTIONS="halt_on_error=1 exitcode=66 ignore_noninstrumented_modules=1 suppressions=$(pwd)/scripts/tsan.supp"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

run() {
    echo "== restir $*"
    "$bin" "$@" --threads 2 >"$out/log" 2>&1 || { st=$?; cat "$out/log"; exit "$st"; }
}

common="--res 24x16 --frames 3 --camera path"
methods=$("$bin" list | awk -F'\t' '$1 ~ /^method / {sub(/^method /, "", $1); print $1}')
[ -n "$methods" ] || { echo "tsan.sh: restir list gave no methods" >&2; exit 1; }
for m in $methods; do # every registered method (restir list), none kept by hand
    run render --scene cornell --method $m $common --out "$out/$m"
done
run render --scene many-lights --method restir-di --res 32x18 --frames 3 --set denoise=svgf --out "$out/svgf"
run render --scene cornell --method restir-pt $common --set denoise=atrous --out "$out/atrous"
run render --scene pillars --method restir-di $common --set spatial.reuse=spmis --out "$out/spmis_di"
run render --scene pillars --method restir-pt $common --set spatial.reuse=spmis \
    --set spmis.search_score=compat --out "$out/spmis_pt"
run render --scene ajar --method restir-pt $common --set spatial.select=compat --out "$out/compat"
run render --scene foliage --method restir-pt $common --set temporal.reuse=both --out "$out/splat"
run render --scene cornell --method restir-pt $common --set temporal.subpixel=search --out "$out/search"
run render --scene pillars --method grestir-pt $common --set recon=both --out "$out/l1"
run compare --scene cornell --methods pt,restir-di --res 24x16 --frames 2 --runs 2 --ref-spp 16 --out "$out/compare"
echo "tsan.sh: no race reported"
