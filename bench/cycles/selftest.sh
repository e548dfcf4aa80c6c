#!/usr/bin/env bash
# bench/cycles/selftest.sh BIN: checks report.py's statistics without Blender (ctest bench.cycles_report).
#
# Renders bench/cycles/scenes/box.json tiny with BIN's pt at four seeds and lists seeds 1 and 2 as
# "ours", seeds 3 and 4 as "cycles" in a runs.csv with made-up CPU times, with a longer render of
# seed 5 as our reference (relVar's denominator), then runs report.py on it.
# Both "renderers" are the same estimator, so report.py must find: a variance ratio near 1 and an
# interval around the exact CPU ratio the times give, the CPU ratio itself exactly, and images that
# agree (no 16 x 16 block beyond 4 standard errors, mean z^2 near 1, image means within 4 standard
# errors). Never starts Blender.
set -euo pipefail
[ $# -eq 1 ] || { echo "usage: bench/cycles/selftest.sh BIN" >&2; exit 2; }
bin=$(realpath "$1")
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/out/renders"
runs=$tmp/out/runs.csv
echo "scene,renderer,config,kind,spp,seed,user_s,sys_s,wall_s,inner_s,build,exr" > "$runs"
# made-up CPU times (user + sys): start-up 0.4 s ours, 1.5 s "cycles"; 16 samples 1.9 / 2.0 and 4.5 / 4.6 s
declare -A user=([1]=1.8 [2]=1.9 [3]=4.4 [4]=4.5)
for s in 1 2 3 4; do
  "$bin" render --scene "$here/scenes/box.json" --method pt --res 128x96 --frames 1 --seed "$s" --threads 2 \
    --set spp=16 --save last --out "$tmp/r$s" > /dev/null
  mv "$tmp/r$s/frame_0000.exr" "$tmp/out/renders/box_$s.exr"
  renderer=ours startup=0.3
  [ "$s" -le 2 ] || { renderer=cycles startup=1.4; }
  echo "box,$renderer,default,startup,1,$s,$startup,0.1,1,1,test," >> "$runs"
  echo "box,$renderer,default,test,16,$s,${user[$s]},0.1,1,1,test,$tmp/out/renders/box_$s.exr" >> "$runs"
done
"$bin" render --scene "$here/scenes/box.json" --method pt --res 128x96 --frames 1 --seed 5 --threads 2 \
  --set spp=64 --save last --out "$tmp/r5" > /dev/null
mv "$tmp/r5/frame_0000.exr" "$tmp/out/renders/box_ref.exr"
echo "box,ours,default,ref,64,5,2,0.1,1,1,test,$tmp/out/renders/box_ref.exr" >> "$runs"
python3 "$here/report.py" "$tmp/out" > "$tmp/report.txt"
python3 - "$tmp/out" << 'EOF'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1] + "/cycles.csv")))
assert len(rows) == 1, f"one ratio row expected, got {len(rows)}"
r = rows[0]
want_time = (1.55 * 16 / 15) / (3.05 * 16 / 15)  # mean net CPU: (T - T1) n / (n - 1)
checks = [
    (abs(float(r["time_ratio"]) - want_time) < 1e-4, f"CPU ratio {r['time_ratio']}, {want_time:.6g} expected"),
    (0.8 < float(r["var_ratio"]) < 1.25, f"variance ratio {r['var_ratio']} of one estimator against itself"),
    (float(r["lo"]) < want_time < float(r["hi"]), f"interval {r['lo']} - {r['hi']} misses {want_time:.4g}"),
    (float(r["hi"]) / float(r["lo"]) < 2.0, f"interval {r['lo']} - {r['hi']} implausibly wide"),
    (r["verdict"] == "below 0.8", f"verdict {r['verdict']!r} for an interval below 0.8"),
]
md = open(sys.argv[1] + "/cycles.md").read()
line = [l for l in md.splitlines() if l.startswith("| box | default | 2 / 2 |")]
checks.append((len(line) == 1, "no agreement row for box"))
checks.append(("box ours default, 64 spp, seed 5" in md, "the reference is not relVar's denominator"))
if line:
    cells = [c.strip() for c in line[0].strip("|").split("|")]
    flagged, mean_z2, z_image = int(cells[4].split()[0]), float(cells[5]), float(cells[8])
    checks += [(flagged == 0, f"{flagged} blocks beyond 4 standard errors between runs of one estimator"),
               (0.4 < mean_z2 < 2.5, f"mean z^2 {mean_z2}, about 1 expected"),
               (abs(z_image) < 4.0, f"image means differ by {z_image} standard errors")]
bad = [msg for ok, msg in checks if not ok]
for msg in bad:
    print("selftest: " + msg)
sys.exit(1 if bad else 0)
EOF
echo "bench/cycles/selftest.sh: report.py passes"
