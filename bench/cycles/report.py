#!/usr/bin/env python3
"""report.py OUTDIR [--bench RESTIR_BENCH]: the tables of bench/cycles/run.sh from OUTDIR/runs.csv and the
images it lists. With --bench, relMSE comes from our own `restir_bench error IMAGE REF` (the first one is
checked against exrtool.py's, which reads the images for everything else).

Per scene, renderer (ours: `pt` in each configuration run.sh ran, "default" being the binary's
defaults; cycles: Blender Cycles) and sample count:
- relMSE (src/metrics/metrics.c) against the renderer's own long reference and against the other's;
- CPU seconds (user + sys of the process): one sample's cost is (T_L - T_1) / (L - 1) with L the
  configuration's longest run (its reference, or its largest sample count), and the start-up
  (Blender's launch and scene build; our scene load, BVH build and image writing) the 1-sample run's
  time less one sample's cost; each run's own CPU time less the start-up is in the CSV too (cpu_s),
  but at a few samples it is mostly the noise of the start-up, so times below are cost * spp;
- our own per-pass wall time (restir's ms_pt, the sampling loop alone) and Cycles' render call's;
- time to equal relMSE, ours / Cycles: at each Cycles point (relMSE e, time t), the time our
  configuration needs for the same e, interpolated linearly in log relMSE - log time between our
  points (outside them, relMSE * time held constant, as for any unbiased Monte Carlo estimator).
Also whether the two references agree within their noise: relMSE between them against what their
noise alone gives (each renderer's largest test run's relMSE scaled by spp / reference spp, summed),
the ratio of their channel means, and per 16 x 16-pixel block the z-score of the difference of the
block means (variances from the largest test runs' squared errors, scaled to the reference spp).
Writes OUTDIR/cycles.csv, OUTDIR/cycles.md and OUTDIR/png/*.png.
"""
import csv
import math
import os
import subprocess
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exrtool  # noqa: E402

BLOCK = 16
Z_FLAG = 4.0


def load_runs(out):
    with open(os.path.join(out, "runs.csv")) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        r["spp"] = int(r["spp"])
        r["cpu"] = float(r["user_s"]) + float(r["sys_s"])
        r["wall"] = float(r["wall_s"])
        r["inner"] = float(r["inner_s"]) if r["inner_s"] else float("nan")
    return rows


_cache = {}
_bench = {"path": None, "checked": False}


def relmse(a_path, b_path):
    """relMSE of image a against reference b: restir_bench error when given, else exrtool."""
    if not _bench["path"]:
        return exrtool.relmse(image(a_path), image(b_path))
    line = subprocess.run([_bench["path"], "error", a_path, b_path], check=True, capture_output=True,
                          text=True).stdout.split()
    e = float(line[line.index("relMSE") + 1])
    if not _bench["checked"]:
        mine = exrtool.relmse(image(a_path), image(b_path))
        if abs(mine - e) > 1e-5 * abs(e):
            sys.exit(f"report.py: restir_bench says relMSE {e}, exrtool.py {mine} ({a_path} against {b_path})")
        _bench["checked"] = True
    return e


def image(path):
    if path not in _cache:
        _cache[path] = exrtool.read_exr(path)
    return _cache[path]


def startup_and_cost(rows):
    """(start-up CPU s, CPU s per sample) from a configuration's 1-sample run and its longest run."""
    one = [r for r in rows if r["spp"] == 1 and r["kind"] == "test"]
    longest = max(rows, key=lambda r: r["spp"])
    if not one or longest["spp"] == 1:
        return 0.0, float("nan")
    cost = (longest["cpu"] - one[0]["cpu"]) / (longest["spp"] - 1)
    if not cost > 0:  # runs too short to tell a sample's cost from the start-up's jitter
        return one[0]["cpu"], float("nan")
    return one[0]["cpu"] - cost, cost


def time_at(points, e):
    """Time to reach relMSE e along points [(e_i, t_i)], log-log interpolation, e*t constant outside."""
    pts = sorted((p for p in points if p[0] > 0 and p[1] > 0), key=lambda p: -p[0])
    if not pts:
        return float("nan")
    if e >= pts[0][0]:
        return pts[0][0] * pts[0][1] / e
    if e <= pts[-1][0]:
        return pts[-1][0] * pts[-1][1] / e
    for (e0, t0), (e1, t1) in zip(pts, pts[1:]):
        if e1 <= e <= e0:
            a = (math.log(e) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + a * (math.log(t1) - math.log(t0)))
    return float("nan")


def block_z(ref_a, ref_b, var_a, var_b, w, h):
    """Per block: (bx, by, z) of the difference of the luminance block means of two references."""
    out = []
    for by in range(0, h, BLOCK):
        for bx in range(0, w, BLOCK):
            sa = sb = va = vb = 0.0
            n = 0
            for y in range(by, min(h, by + BLOCK)):
                for x in range(bx, min(w, bx + BLOCK)):
                    i = y * w + x
                    sa += ref_a[i]
                    sb += ref_b[i]
                    va += var_a[i]
                    vb += var_b[i]
                    n += 1
            se = math.sqrt(va + vb) / n
            out.append((bx, by, (sb - sa) / n / se if se > 0 else 0.0))
    return out


def luminance(img):
    p = img.rgb
    return [0.2126 * p[3 * i] + 0.7152 * p[3 * i + 1] + 0.0722 * p[3 * i + 2] for i in range(img.width * img.height)]


def scaled_sq_err(test, ref, factor):
    a, b = luminance(test), luminance(ref)
    return [(x - y) ** 2 * factor for x, y in zip(a, b)]


def exposure(img):
    lum = sorted(luminance(img))
    p = lum[int(0.97 * (len(lum) - 1))]
    return 0.85 / p if p > 0 else 1.0


def write_pngs(out, scene, ours_ref, cyc_ref, blocks, tests):
    pdir = os.path.join(out, "png")
    os.makedirs(pdir, exist_ok=True)
    w, h = ours_ref.width, ours_ref.height
    k = exposure(ours_ref)
    exrtool.write_png(os.path.join(pdir, f"{scene}_ref_ours.png"), w, h, ours_ref.rgb, k)
    exrtool.write_png(os.path.join(pdir, f"{scene}_ref_cycles.png"), w, h, cyc_ref.rgb, k)
    # relative difference (Cycles - ours) / (ours + 0.05 * mean): red where Cycles is brighter, blue darker; x5
    mean = sum(luminance(ours_ref)) / (w * h)
    la, lb = luminance(ours_ref), luminance(cyc_ref)
    diff = []
    for a, b in zip(la, lb):
        d = 5.0 * (b - a) / (a + 0.05 * mean)
        diff += [max(d, 0.0), 0.0, max(-d, 0.0)]
    exrtool.write_png(os.path.join(pdir, f"{scene}_diff_x5.png"), w, h, diff)
    # block z-scores: red Cycles brighter, blue darker, full at |z| = 2 Z_FLAG
    zimg = [0.0] * (3 * w * h)
    for bx, by, z in blocks:
        v = min(1.0, abs(z) / (2 * Z_FLAG))
        c = (v, 0.0, 0.0) if z > 0 else (0.0, 0.0, v)
        for y in range(by, min(h, by + BLOCK)):
            for x in range(bx, min(w, bx + BLOCK)):
                zimg[3 * (y * w + x):3 * (y * w + x) + 3] = c
    exrtool.write_png(os.path.join(pdir, f"{scene}_blockz.png"), w, h, zimg)
    for name, r in tests.items():
        exrtool.write_png(os.path.join(pdir, f"{scene}_{name}_{r['spp']}.png"), w, h, image(r["exr"]).rgb, k)


def fmt(x, digits=4):
    if x != x:
        return "-"
    return f"{x:.{digits}g}"


def scene_report(out, scene, sr):
    """The rows of one scene, its line of the agreement table and its lines of the cost table."""
    refs = {r["renderer"]: r for r in sr if r["kind"] == "ref"}
    if "ours" not in refs or "cycles" not in refs:
        print(f"report.py: {scene}: a reference is missing, skipped", file=sys.stderr)
        return [], None, []
    ref_img = {k: image(v["exr"]) for k, v in refs.items()}
    configs = []
    for r in sr:
        if (r["renderer"], r["config"]) not in configs:
            configs.append((r["renderer"], r["config"]))
    table, costs, points, largest = [], [], {}, {}
    for renderer, config in configs:
        cr = [r for r in sr if (r["renderer"], r["config"]) == (renderer, config)]
        start, cost = startup_and_cost(cr)
        other = "cycles" if renderer == "ours" else "ours"
        inner = [r["inner"] / r["spp"] for r in sorted(cr, key=lambda r: r["spp"]) if r["spp"] > 1]
        label = "ours " + config if renderer == "ours" else "Cycles"
        costs.append(f"| {scene} | {label} | {fmt(start, 3)} | {fmt(1e3 * cost, 4)} | "
                     f"{fmt(1e3 * inner[-1], 4) if inner else '-'} |")
        pts = []
        for r in sorted((r for r in cr if r["kind"] == "test"), key=lambda r: r["spp"]):
            e_own = relmse(r["exr"], refs[renderer]["exr"])
            row = dict(scene=scene, renderer=renderer, config=config, spp=r["spp"], relmse_own=e_own,
                       relmse_other=relmse(r["exr"], refs[other]["exr"]), cpu_s=r["cpu"] - start,
                       cpu_s_model=cost * r["spp"], cpu_ms_per_spp=1e3 * cost,
                       own_wall_ms_per_spp=1e3 * r["inner"] / r["spp"], wall_s=r["wall"],
                       own_ref_spp=refs[renderer]["spp"], time_ratio_vs_cycles=float("nan"))
            table.append(row)
            pts.append((e_own, row["cpu_s_model"]))
            if config == "default" and (renderer not in largest or r["spp"] > largest[renderer][0]["spp"]):
                largest[renderer] = (r, e_own)
        points[(renderer, config)] = pts
    for row in table:
        cyc = [x for x in table if x["renderer"] == "cycles" and x["spp"] == row["spp"]]
        if row["renderer"] == "ours" and cyc:
            t_ours = time_at(points[("ours", row["config"])], cyc[0]["relmse_own"])
            row["time_ratio_vs_cycles"] = t_ours / cyc[0]["cpu_s_model"]
    # do the references agree?
    e_refs = relmse(refs["cycles"]["exr"], refs["ours"]["exr"])
    expected, var = 0.0, {}
    for renderer in ("ours", "cycles"):
        r, e_own = largest[renderer]
        expected += e_own * r["spp"] / refs[renderer]["spp"]
        var[renderer] = scaled_sq_err(image(r["exr"]), ref_img[renderer], r["spp"] / refs[renderer]["spp"])
    means_o, means_c = exrtool.channel_means(ref_img["ours"]), exrtool.channel_means(ref_img["cycles"])
    ratio = " ".join(fmt(c / o, 4) if o > 0 else "-" for c, o in zip(means_c, means_o))
    w, h = ref_img["ours"].width, ref_img["ours"].height
    blocks = block_z(luminance(ref_img["ours"]), luminance(ref_img["cycles"]), var["ours"], var["cycles"], w, h)
    flagged = [b for b in blocks if abs(b[2]) > Z_FLAG]
    zmax = max(blocks, key=lambda b: abs(b[2]))
    agree = (f"| {scene} | {refs['ours']['spp']} | {refs['cycles']['spp']} | {fmt(e_refs)} | {fmt(expected)} | "
             f"{fmt(e_refs / expected, 3) if expected > 0 else '-'} | {ratio} | {len(flagged)} of {len(blocks)} | "
             f"{zmax[2]:+.2f} at ({zmax[0]}, {zmax[1]}) |")
    tests = {}
    for renderer, config in configs:
        cand = [r for r in sr if (r["renderer"], r["config"]) == (renderer, config) and r["kind"] == "test"
                and r["spp"] <= 16]
        if cand:
            tests[f"{renderer}_{config}"] = max(cand, key=lambda r: r["spp"])
    write_pngs(out, scene, ref_img["ours"], ref_img["cycles"], blocks, tests)
    return table, agree, costs


def main():
    args = sys.argv[1:]
    if len(args) == 3 and args[1] == "--bench":
        _bench["path"] = args.pop(2)
        args.pop(1)
    if len(args) != 1:
        sys.exit(__doc__)
    out = args[0]
    rows = load_runs(out)
    path = os.path.join(out, "settings.txt")
    settings = open(path).read().strip() if os.path.exists(path) else ""
    scenes = []
    for r in rows:
        if r["scene"] not in scenes:
            scenes.append(r["scene"])
    csv_rows = []
    agree = ["| scene | ours ref spp | Cycles ref spp | relMSE, Cycles ref against ours | expected from noise | "
             "ratio | mean R G B, Cycles / ours | 16x16 blocks with abs(z) > 4 | largest z (block corner) |",
             "|---|---|---|---|---|---|---|---|---|"]
    costs = ["| scene | renderer | start-up CPU s | CPU ms per sample | own wall ms per sample |",
             "|---|---|---|---|---|"]
    for scene in scenes:
        table, line, cost_lines = scene_report(out, scene, [r for r in rows if r["scene"] == scene])
        csv_rows += table
        if line:
            agree.append(line)
            costs += cost_lines
    ours_configs = []
    for r in csv_rows:
        if r["renderer"] == "ours" and r["config"] not in ours_configs:
            ours_configs.append(r["config"])
    head = ["scene", "spp"] + [f"relMSE ours {c} (own ref / Cycles ref)" for c in ours_configs]
    head += ["relMSE Cycles (own / ours)"] + [f"time to equal relMSE, ours {c} / Cycles" for c in ours_configs]
    main_table = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for scene in scenes:
        sr = [r for r in csv_rows if r["scene"] == scene]
        for spp in sorted({r["spp"] for r in sr}):
            get = {(r["renderer"], r["config"]): r for r in sr if r["spp"] == spp}
            cells = []
            for key in [("ours", c) for c in ours_configs] + [("cycles", "default")]:
                r = get.get(key)
                cells.append(f"{fmt(r['relmse_own'])} / {fmt(r['relmse_other'])}" if r else "-")
            for c in ours_configs:
                r = get.get(("ours", c))
                cells.append(fmt(r["time_ratio_vs_cycles"], 3) if r else "-")
            main_table.append(f"| {scene} | {spp} | " + " | ".join(cells) + " |")
    md = ["# pt against Blender Cycles", "", "```", settings, "```", "",
          "## Error and time to equal error", "",
          "relMSE (src/metrics) of one render against the renderer's own long reference and against the other "
          "renderer's. Time to equal relMSE: our CPU time to reach Cycles' relMSE at that sample count (log-log "
          "interpolation over our sample counts) over Cycles' CPU time; times are CPU ms per sample times spp, "
          "start-up excluded; below 1, ours is faster.", ""] + main_table
    md += ["", "## Do the references agree?", "",
           "relMSE of Cycles' reference against ours, against what the two references' noise alone gives (each "
           "renderer's largest test render's relMSE against its own reference, times its spp over the "
           "reference's, summed); z-scores of the difference of 16 x 16-pixel block means of luminance, "
           "negative where Cycles is darker.", ""] + agree
    md += ["", "## Cost", "",
           "CPU seconds are user + sys of the whole process. CPU ms per sample: (T(L) - T(1)) / (L - 1), L the "
           "longest run of that configuration; start-up: T(1) less one sample. Own wall ms per sample: ours the "
           "sampling pass (ms_pt), Cycles the render call, at the longest run.", ""] + costs
    keys = ["scene", "renderer", "config", "spp", "relmse_own", "relmse_other", "cpu_s", "cpu_s_model",
            "cpu_ms_per_spp", "own_wall_ms_per_spp", "wall_s", "own_ref_spp", "time_ratio_vs_cycles"]
    with open(os.path.join(out, "cycles.csv"), "w", newline="") as f:
        wr = csv.writer(f)
        wr.writerow(keys)
        for r in csv_rows:
            wr.writerow([f"{r[k]:.6g}" if isinstance(r[k], float) else r[k] for k in keys])
    with open(os.path.join(out, "cycles.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
