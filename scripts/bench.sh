#!/usr/bin/env bash
# bench.sh: runs the benchmarks (per-pass time, rays/s, Embree-only replay ratio, equal-time error,
# 001's temporal experiment) and prints Markdown for docs/BENCHMARKS.md. Not a test.
set -euo pipefail
build=${1:-build}
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
# BENCH_QUICK=1: only the tables of passes.csv and equal_time.csv (in BENCH_OUT, default out/bench/).
"$build/restir_bench" ${BENCH_ARGS:-}
# The passes with Embree streams on and off; the full run only.
if [ -z "${BENCH_QUICK:-}" ] || [ "${BENCH_QUICK}" = 0 ]; then
  [ -n "${BENCH_ARGS:-}" ] || "$build/restir_bench" streams
fi
