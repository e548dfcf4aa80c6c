#!/usr/bin/env bash
# bench/cycles/run.sh BIN OUTDIR [--res WxH] [--spp "1 4 16 64"] [--ref-spp N] [--cycles-ref-spp N]
#                     [--threads N] [--scenes "box cornell many-lights engine-sky"] [--max-bounces N] [--seed N]
#                     [--config NAME="--set key=value ..."]...
#
# restir's `pt` against Blender Cycles on the same scenes, computing the same integral
# (docs/BENCHMARKS.md). Installs Debian's blender with apt-get when it is missing (only here; never
# `make test`). Per scene: the scene's triangles, Lambert materials, camera and constant
# environment go to Blender through `restir scene export --mesh` and build_scene.py; then, all at
# --threads threads, our pt (configuration "default": the binary's defaults; "sobol-sa": sampler=sobol
# with lights.sample=solid-angle; each --config adds one) and Cycles render every --spp count with
# seed --seed, a 1-sample render (start-up cost) and a long reference each (ours --ref-spp with the
# default settings, Cycles --cycles-ref-spp) with another seed. Our runs' summary.json (every
# setting in effect) is kept in OUTDIR/logs. report.py then measures relMSE (by restir_bench error
# when BIN's folder has it, else by exrtool.py) against both references, CPU time per sample and
# the time to equal relMSE, and writes OUTDIR/cycles.csv, OUTDIR/cycles.md and PNGs in OUTDIR/png.
# Every run's CPU time (user + sys of its process), wall time and inner time (ours: the sampling
# pass, ms_pt of metrics.csv; Cycles: the wall time of the render call) go to OUTDIR/runs.csv; runs
# already listed there with their image present are not repeated, so an interrupted run resumes.
set -euo pipefail

usage() { sed -n '2,4p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
[ $# -ge 2 ] || usage
bin=$(realpath "$1")
out=$2
shift 2
res=320x180
spps="1 4 16 64"
ref_spp=4096
cycles_ref_spp=2048
threads=2
scenes="box cornell many-lights engine-sky"
max_bounces=8 # our pt.max_bounces default (restir render --help); Cycles gets max_bounces - 1
seed=1
ref_seed=1000003
configs=("default|" "sobol-sa|--set sampler=sobol --set lights.sample=solid-angle")
while [ $# -gt 0 ]; do
  [ $# -ge 2 ] || usage
  case "$1" in
    --res) res=$2 ;;
    --spp) spps=$2 ;;
    --ref-spp) ref_spp=$2 ;;
    --cycles-ref-spp) cycles_ref_spp=$2 ;;
    --threads) threads=$2 ;;
    --scenes) scenes=$2 ;;
    --max-bounces) max_bounces=$2 ;;
    --seed) seed=$2 ;;
    --config) [[ $2 == *=* ]] || usage; configs+=("${2%%=*}|${2#*=}") ;;
    *) usage ;;
  esac
  shift 2
done
[ -x "$bin" ] || { echo "run.sh: $bin is not an executable" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)

if ! command -v blender > /dev/null; then
  if [ "$(id -u)" != 0 ]; then
    echo "run.sh: blender is missing and installing it needs root (apt-get install -y blender)" >&2
    exit 1
  fi
  echo "installing blender (Debian package) ..." >&2
  DEBIAN_FRONTEND=noninteractive apt-get install -y blender > /dev/null || {
    apt-get update > /dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y blender > /dev/null; }
fi
blender_version=$(blender -b --factory-startup --version 2> /dev/null | sed -n 's/^Blender \([0-9.]*\).*/\1/p' | head -1)

mkdir -p "$out"/{scenes,mesh,renders,logs}
runs=$out/runs.csv
[ -f "$runs" ] || echo "scene,renderer,config,kind,spp,seed,user_s,sys_s,wall_s,inner_s,exr" > "$runs"
cat > "$out/settings.txt" << EOF
res=$res spp=$spps ref_spp=$ref_spp cycles_ref_spp=$cycles_ref_spp threads=$threads max_bounces=$max_bounces
seed=$seed ref_seed=$ref_seed blender=$blender_version bin=$bin (tree of this script: $(git -C "$here" describe --always --dirty 2> /dev/null || echo unknown))
ours configurations: $(printf '%s; ' "${configs[@]}")
cpu=$(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1) cores=$(nproc)
EOF

# Whether runs.csv already has this run and its image exists.
done_before() { grep -q "^$1,$2,$3,$4,$5,$6," "$runs" && [ -f "$7" ]; }

# timed LOG CMD...: runs CMD with stdout and stderr into LOG; sets user_s sys_s wall_s.
timed() {
  local log=$1 tf
  shift
  tf=$(mktemp)
  local TIMEFORMAT='%U %S %R'
  if ! { time "$@" > "$log" 2>&1; } 2> "$tf"; then
    echo "run.sh: failed: $* (log: $log)" >&2
    tail -5 "$log" >&2
    rm -f "$tf"
    exit 1
  fi
  read -r user_s sys_s wall_s < "$tf"
  rm -f "$tf"
}

# ours SCENE SRC CONFIG KIND SPP SEED [--set ...]: our pt, one frame.
ours() {
  local scene=$1 src=$2 config=$3 kind=$4 spp=$5 s=$6
  shift 6
  local exr=$out/renders/${scene}_ours_${config}_${kind}_${spp}.exr dir=$out/renders/tmp_ours
  done_before "$scene" ours "$config" "$kind" "$spp" "$s" "$exr" && return 0
  rm -rf "$dir"
  timed "$out/logs/${scene}_ours_${config}_${kind}_${spp}.log" "$bin" render --scene "$src" --method pt --res "$res" \
    --frames 1 --seed "$s" --threads "$threads" --set spp="$spp" --set pt.max_bounces="$max_bounces" "$@" \
    --save last --out "$dir"
  local inner
  inner=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "ms_pt") c = i } NR == 2 { printf "%.4f", $c / 1000 }' \
    "$dir/metrics.csv")
  mv "$dir/frame_0000.exr" "$exr"
  cp "$dir/summary.json" "$out/logs/${scene}_ours_${config}_${kind}_${spp}.summary.json"
  rm -rf "$dir"
  echo "$scene,ours,$config,$kind,$spp,$s,$user_s,$sys_s,$wall_s,$inner,$exr" >> "$runs"
}

# cycles SCENE MESH KIND SPP SEED: Blender Cycles through build_scene.py.
cycles() {
  local scene=$1 mesh=$2 kind=$3 spp=$4 s=$5
  local exr=$out/renders/${scene}_cycles_default_${kind}_${spp}.exr log=$out/logs/${scene}_cycles_${kind}_${spp}.log
  done_before "$scene" cycles default "$kind" "$spp" "$s" "$exr" && return 0
  timed "$log" blender -b --factory-startup -t "$threads" -P "$here/build_scene.py" -- "$mesh" "$exr" "$spp" "$s" \
    --res "$res" --max-bounces "$max_bounces"
  local inner
  inner=$(sed -n 's/^cycles_render:.* wall_s \([0-9.]*\).*/\1/p' "$log")
  echo "$scene,cycles,default,$kind,$spp,$s,$user_s,$sys_s,$wall_s,$inner,$exr" >> "$runs"
}

for scene in $scenes; do
  sets=()
  case "$scene" in
    box) src=$here/scenes/box.json ;;
    cornell | many-lights)
      # the built-in scene with every material made Lambertian (lambertize.py says what changes)
      "$bin" scene export "$scene" --out "$out/scenes/builtin" --force > /dev/null
      python3 "$here/lambertize.py" "$out/scenes/builtin/$scene.json" "$out/scenes/$scene.json" > /dev/null
      src=$out/scenes/$scene.json ;;
    engine-sky)
      # flat shading: shading normals are refused by the export (Cycles bends them otherwise)
      src=$here/scenes/engine_sky.json
      sets=(--set scene.shading_normals=off) ;;
    *) src=$scene ;; # any scene file whose materials are all Lambertian
  esac
  mesh=$("$bin" scene export "$src" --mesh --force --out "$out/mesh" "${sets[@]}" \
    2> "$out/logs/${scene}_export.log") || {
    cat "$out/logs/${scene}_export.log" >&2
    exit 1
  }
  name=$(basename "$mesh" .mesh.json)
  [ "$name" = "$scene" ] || { mv "$mesh" "$out/mesh/$scene.mesh.json"; mesh=$out/mesh/$scene.mesh.json; }
  echo "== $scene: $(grep -m1 '"triangles"' "$mesh" | tr -d ' ,\n') ($(date +%T))" >&2
  # the series; 1 sample always (the start-up cost), the references last
  for spp in $(echo 1 $spps | tr ' ' '\n' | sort -n -u); do
    for cfg in "${configs[@]}"; do
      read -r -a extra <<< "${cfg#*|}"
      ours "$scene" "$src" "${cfg%%|*}" test "$spp" "$seed" "${sets[@]}" "${extra[@]}"
    done
    cycles "$scene" "$mesh" test "$spp" "$seed"
  done
  ours "$scene" "$src" default ref "$ref_spp" "$ref_seed" "${sets[@]}"
  cycles "$scene" "$mesh" ref "$cycles_ref_spp" "$ref_seed"
done

# relMSE by our own restir_bench (beside BIN) when it is there, else by exrtool.py
bench_bin=$(dirname "$bin")/restir_bench
bench_usage=$([ -x "$bench_bin" ] && "$bench_bin" error 2>&1 || true)
if [[ $bench_usage == *"usage: restir_bench error"* ]]; then
  python3 "$here/report.py" "$out" --bench "$bench_bin"
else
  python3 "$here/report.py" "$out"
fi
