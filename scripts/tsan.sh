#!/bin/sh
# scripts/tsan.sh BUILD: every method of the restir command in BUILD (a RESTIR_TSAN=ON build, `make
# tsan`) renders a short camera path at tiny sizes on 2 OpenMP threads under ThreadSanitizer, with
# Archer (LLVM's OpenMP tool) telling it about OpenMP's barriers; then every method's variants, the
# denoisers, more reuse settings and a compare (its reference and runs). Methods and variants come
# from the registry (`restir list --json`, read by scripts/registry.py): none is named here. Exits 66
# at the first race reported (halt_on_error), 1 when a command fails otherwise.
set -eu
build=$1
bin=$build/restir
here=$(cd "$(dirname "$0")/.." && pwd)
[ -x "$bin" ] || { echo "tsan.sh: $bin is missing (make tsan builds it)" >&2; exit 2; }
archer=$(sed -n 's/^RESTIR_ARCHER:FILEPATH=//p' "$build/CMakeCache.txt")
[ -f "$archer" ] || { echo "tsan.sh: $build was not configured with RESTIR_TSAN=ON" >&2; exit 2; }
export OMP_NUM_THREADS=2 OMP_TOOL_LIBRARIES="$archer"
export TSAN_OPTIONS="halt_on_error=1 exitcode=66 ignore_noninstrumented_modules=1 suppressions=$here/scripts/tsan.supp"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

run() {
    echo "== restir $*"
    "$bin" "$@" --threads 2 >"$out/log" 2>&1 </dev/null || { st=$?; cat "$out/log"; exit "$st"; }
}
registry() { python3 "$here/scripts/registry.py" "$bin" "$@"; }

common="--res 24x16 --frames 3 --camera path"
methods=$(registry methods)
variants=$(registry variants) # "METHOD key=value[:key=value...]" per line: each method row's .variants
reference=$(registry role reference)
di=$(registry first direct-only selection-study)         # screen-space ReSTIR of direct light
paths=$(registry first path-reservoirs selection-study) # ReSTIR of path reservoirs
for m in $methods; do
    run render --scene cornell --method "$m" $common --out "$out/$m"
done
while read -r m v; do
    [ -n "$m" ] || continue # no variants at all: one empty line
    sets=$(echo "$v" | sed 's/^/--set /; s/:/ --set /g') # split below on purpose, as $common: no spaces inside
    run render --scene pillars --method "$m" $common $sets --out "$out/variant-$m-$v"
done <<VARIANTS
$variants
VARIANTS
run render --scene many-lights --method "$di" --res 32x18 --frames 3 --set denoise=svgf --out "$out/svgf"
run render --scene cornell --method "$paths" $common --set denoise=atrous --out "$out/atrous"
run render --scene pillars --method "$paths" $common --set spatial.reuse=spmis \
    --set spmis.search_score=compat --out "$out/spmis_pt"
run render --scene ajar --method "$paths" $common --set spatial.select=compat --out "$out/compat"
run render --scene foliage --method "$paths" $common --set temporal.reuse=both --out "$out/splat"
run render --scene cornell --method "$paths" $common --set temporal.subpixel=search --out "$out/search"
run compare --scene cornell --methods "$reference,$di" --res 24x16 --frames 2 --runs 2 --ref-spp 16 --out "$out/compare"
echo "tsan.sh: no race reported"
