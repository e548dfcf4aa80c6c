#!/usr/bin/env bash
# bench/cycles/run.sh BIN OUTDIR [--res WxH] [--spp "64 256 1024"] [--seeds "1 2"] [--ref-spp N]
#     [--scenes "box cornell many-lights engine-sky closed-room corner-lamp"] [--threads N]
#     [--max-bounces N] [--config NAME="--set key=value ..."]... [--only-configs "default ..."]
#
# restir's `pt` against Blender Cycles on the same scenes, computing the same integral
# (docs/BENCHMARKS.md), at the sample counts users render: for each scene, sample count (--spp,
# default 64 256 1024) and renderer, one render per seed (--seeds, default 1 2: independent runs).
# report.py then takes the variance of one run from the spread between the seeds (no image is
# compared against a reference) and gives, per sample count, the time to equal noise, ours /
# Cycles, with a 95% interval. Installs Debian's blender with apt-get when it is missing (only
# here; never `make test`).
#
# Per scene the scene's triangles, Lambert materials, camera and constant environment go to
# Blender through `restir scene export --mesh` and build_scene.py; both renderers run at --threads
# threads (default 2), --res (default 320x240) and --max-bounces (our pt.max_bounces, default 8;
# Cycles gets max_bounces - 1). Ours runs in every configuration: "default" (the binary's
# defaults), "solid-angle" (--set lights.sample=solid-angle) and each --config NAME="SETTINGS";
# --only-configs "NAME ..." keeps those alone. Each renderer and configuration also renders 1
# sample per seed: its CPU time is the start-up (Blender's launch and scene build; our scene load
# and BVH), subtracted by report.py. Ours also renders one long reference per scene (--ref-spp,
# default 2048, 0 for none; the binary's defaults, seed 1000003), used only as the m of relVar's
# var / (m^2 + eps), which must share no noise with the runs measured. Scenes: box, closed-room
# and corner-lamp (bench/cycles/scenes; closed rooms with large ceiling lamps a few cm from the
# walls), cornell and many-lights (built-in, made Lambertian by lambertize.py), engine-sky (a glTF
# engine under a constant sky, flat shaded), or any scene file whose materials are all Lambertian.
#
# Order: every scene's start-up runs and reference, then each sample count in turn over all
# scenes (so the low counts are complete before the long ones start). Every run's CPU time (user
# + sys of its process), wall time, inner time (ours: the sampling pass, ms_pt of metrics.csv;
# Cycles: the wall time of the render call) and the build (restir's --version commit, Blender's
# version) go to OUTDIR/runs.csv; a run listed there with its image present is not repeated, so
# an interrupted run resumes, and a later call with more sample counts or scenes adds to it. Our
# runs' summary.json (every setting in effect) is kept in OUTDIR/logs. Writes OUTDIR/cycles.md,
# OUTDIR/cycles.csv and PNGs in OUTDIR/png (report.py OUTDIR redoes them from what is there).
set -euo pipefail

usage() { sed -n '2,4p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
[ $# -ge 2 ] || usage
bin=$(realpath "$1")
out=$2
shift 2
res=320x240
spps="64 256 1024"
seeds="1 2"
ref_spp=2048
ref_seed=1000003
threads=2
scenes="box cornell many-lights engine-sky closed-room corner-lamp"
max_bounces=8 # our pt.max_bounces default (restir render --help); Cycles gets max_bounces - 1
configs=("default|" "solid-angle|--set lights.sample=solid-angle")
only=""
while [ $# -gt 0 ]; do
  [ $# -ge 2 ] || usage
  case "$1" in
    --res) res=$2 ;;
    --spp) spps=$2 ;;
    --seeds) seeds=$2 ;;
    --ref-spp) ref_spp=$2 ;;
    --threads) threads=$2 ;;
    --scenes) scenes=$2 ;;
    --max-bounces) max_bounces=$2 ;;
    --config) [[ $2 == *=* ]] || usage; configs+=("${2%%=*}|${2#*=}") ;;
    --only-configs) only=$2 ;;
    *) usage ;;
  esac
  shift 2
done
[ -x "$bin" ] || { echo "run.sh: $bin is not an executable" >&2; exit 2; }
[ "$(echo $seeds | wc -w)" -ge 2 ] || { echo "run.sh: --seeds needs at least two seeds (the variance comes from their spread)" >&2; exit 2; }
[[ $ref_spp =~ ^[0-9]+$ ]] || { echo "run.sh: --ref-spp must be an integer (0: no reference)" >&2; exit 2; }
for spp in $spps; do
  [[ $spp =~ ^[0-9]+$ ]] && [ "$spp" -ge 2 ] || { echo "run.sh: --spp counts must be integers of at least 2" >&2; exit 2; }
done
if [ -n "$only" ]; then
  kept=()
  for cfg in "${configs[@]}"; do
    [[ " $only " == *" ${cfg%%|*} "* ]] && kept+=("$cfg")
  done
  [ ${#kept[@]} -gt 0 ] || { echo "run.sh: --only-configs \"$only\" names no configuration" >&2; exit 2; }
  configs=("${kept[@]}")
fi
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
ours_build=$("$bin" --version 2> /dev/null | sed -n 's/.*commit \([0-9a-f]*\).*/\1/p' | head -1)

mkdir -p "$out"/{scenes,mesh,renders,logs}
runs=$out/runs.csv
header="scene,renderer,config,kind,spp,seed,user_s,sys_s,wall_s,inner_s,build,exr"
[ -f "$runs" ] || echo "$header" > "$runs"
[ "$(head -1 "$runs")" = "$header" ] || {
  echo "run.sh: $runs was written by another version of run.sh (header differs): use a new OUTDIR" >&2
  exit 2
}
cat >> "$out/settings.txt" << EOF
$(date -u +%FT%TZ): res=$res spp=$spps seeds=$seeds ref_spp=$ref_spp ref_seed=$ref_seed threads=$threads max_bounces=$max_bounces scenes=$scenes
  blender=$blender_version bin=$bin (commit ${ours_build:-unknown}; tree of this script: $(git -C "$here" describe --always --dirty 2> /dev/null || echo unknown))
  ours configurations: $(printf '%s; ' "${configs[@]}")
  cpu=$(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1) cores=$(nproc) load=$(cut -d' ' -f1-3 /proc/loadavg)
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
  local name=${scene}_ours_${config}_${kind}_${spp}_s$s
  local exr=$out/renders/$name.exr dir=$out/renders/tmp_ours
  done_before "$scene" ours "$config" "$kind" "$spp" "$s" "$exr" && return 0
  rm -rf "$dir"
  timed "$out/logs/$name.log" "$bin" render --scene "$src" --method pt --res "$res" \
    --frames 1 --seed "$s" --threads "$threads" --set spp="$spp" --set pt.max_bounces="$max_bounces" "$@" \
    --save last --out "$dir"
  local inner
  inner=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "ms_pt") c = i } NR == 2 { printf "%.4f", $c / 1000 }' \
    "$dir/metrics.csv")
  mv "$dir/frame_0000.exr" "$exr"
  cp "$dir/summary.json" "$out/logs/$name.summary.json"
  rm -rf "$dir"
  echo "$scene,ours,$config,$kind,$spp,$s,$user_s,$sys_s,$wall_s,$inner,${ours_build:-unknown},$exr" >> "$runs"
}

# cycles SCENE MESH KIND SPP SEED: Blender Cycles through build_scene.py.
cycles() {
  local scene=$1 mesh=$2 kind=$3 spp=$4 s=$5
  local name=${scene}_cycles_default_${kind}_${spp}_s$s
  local exr=$out/renders/$name.exr log=$out/logs/$name.log
  done_before "$scene" cycles default "$kind" "$spp" "$s" "$exr" && return 0
  timed "$log" blender -b --factory-startup -t "$threads" -P "$here/build_scene.py" -- "$mesh" "$exr" "$spp" "$s" \
    --res "$res" --max-bounces "$max_bounces"
  local inner
  inner=$(sed -n 's/^cycles_render:.* wall_s \([0-9.]*\).*/\1/p' "$log")
  echo "$scene,cycles,default,$kind,$spp,$s,$user_s,$sys_s,$wall_s,$inner,blender-$blender_version,$exr" >> "$runs"
}

# every_run SCENE KIND SPP: each seed, each configuration of ours, then Cycles.
every_run() {
  local scene=$1 kind=$2 spp=$3 s cfg
  local -a extra sets
  read -r -a sets <<< "${scene_sets[$scene]}"
  for s in $seeds; do
    for cfg in "${configs[@]}"; do
      read -r -a extra <<< "${cfg#*|}"
      ours "$scene" "${scene_src[$scene]}" "${cfg%%|*}" "$kind" "$spp" "$s" "${sets[@]}" "${extra[@]}"
    done
    cycles "$scene" "${scene_mesh[$scene]}" "$kind" "$spp" "$s"
  done
}

declare -A scene_src scene_mesh scene_sets
keys=()
for scene in $scenes; do
  sets=()
  key=$scene
  case "$scene" in
    box) src=$here/scenes/box.json ;;
    closed-room) src=$here/scenes/closed_room.json ;;
    corner-lamp) src=$here/scenes/corner_lamp.json ;;
    cornell | many-lights)
      # the built-in scene with every material made Lambertian (lambertize.py says what changes)
      "$bin" scene export "$scene" --out "$out/scenes/builtin" --force > /dev/null
      python3 "$here/lambertize.py" "$out/scenes/builtin/$scene.json" "$out/scenes/$scene.json" > /dev/null
      src=$out/scenes/$scene.json ;;
    engine-sky)
      # flat shading: shading normals are refused by the export (Cycles bends them otherwise)
      src=$here/scenes/engine_sky.json
      sets=(--set scene.shading_normals=off) ;;
    *) # any scene file whose materials are all Lambertian, named by its file name
      src=$(realpath "$scene")
      key=$(basename "$scene" .json) ;;
  esac
  [[ $key =~ ^[A-Za-z0-9._-]+$ ]] || { echo "run.sh: scene name \"$key\": letters, digits, . _ - only" >&2; exit 2; }
  scene=$key
  keys+=("$key")
  mesh=$("$bin" scene export "$src" --mesh --force --out "$out/mesh" "${sets[@]}" \
    2> "$out/logs/${scene}_export.log") || {
    cat "$out/logs/${scene}_export.log" >&2
    exit 1
  }
  name=$(basename "$mesh" .mesh.json)
  [ "$name" = "$scene" ] || { mv "$mesh" "$out/mesh/$scene.mesh.json"; mesh=$out/mesh/$scene.mesh.json; }
  scene_src[$scene]=$src
  scene_mesh[$scene]=$mesh
  scene_sets[$scene]=${sets[*]}
  echo "== $scene: $(grep -m1 '"triangles"' "$mesh" | tr -d ' ,\n'), start-up runs ($(date +%T))" >&2
  every_run "$scene" startup 1
  if [ "$ref_spp" -gt 0 ]; then
    read -r -a sets <<< "${scene_sets[$scene]}"
    ours "$scene" "$src" default ref "$ref_spp" "$ref_seed" "${sets[@]}"
  fi
done
for spp in $(echo $spps | tr ' ' '\n' | sort -n -u); do
  for scene in "${keys[@]}"; do
    echo "== $scene: $spp spp ($(date +%T))" >&2
    every_run "$scene" test "$spp"
  done
done

python3 "$here/report.py" "$out"
