#!/usr/bin/env python3
"""report.py OUTDIR: the tables of bench/cycles/run.sh, from OUTDIR/runs.csv and the images it lists.

Noise from independent runs, not against a reference: each renderer (ours in each configuration
run.sh ran; Cycles) renders every scene at every sample count once per seed. Per pixel and
channel the variance of one run is the sample variance over the seeds (two seeds: 0.5 (a - b)^2,
unbiased), and relVar = mean over pixels and channels of var / (m^2 + 1e-3), the relMSE a run
would have against the exact image (src/metrics/metrics.c's weighting and epsilon). m, the same
for every renderer and sample count of a scene, is our long reference render of it (run.sh
--ref-spp, another seed), so all rows of a scene weigh pixels alike, a ratio of two relVar is a
ratio of the same weighted variance, and m shares no noise with the runs measured (a mean of the
measured runs would: a bright outlier of one run would raise its own m and hide itself). Without a
reference run, m is the mean of all the scene's runs weighted by their sample counts, and the
tables say so.

CPU time is user + sys of the run's process less the start-up: with T1 the mean CPU time of that
renderer and configuration's 1-sample runs, a run of n samples and CPU time T costs
(T - T1) n / (n - 1) (the start-up is T1 less one sample). Time to equal noise, ours / Cycles, at a
sample count: (relVar_ours x CPU_ours) / (relVar_Cycles x CPU_Cycles), CPU the mean over the seeds
(relVar x time is what an unbiased estimator keeps constant as it renders more; the ratio is the
CPU time ours needs to reach Cycles' noise at that count, over Cycles'). Its 95% interval: the
variance ratio by a bootstrap over 16 x 16-pixel blocks (both renderers' blocks resampled
together), times the CPU time ratio with a normal error in log time whose spread is the
run-to-run scatter of log CPU time between seeds, pooled per renderer over every scene and count.
The verdict against the issue's target 0.8 says "below 0.8" or "above 0.8" only when the whole
interval is, else "undecided". On a shared machine a sample's CPU cost drifts with the load from
one sample count to the next, which the interval does not cover; a last column gives the ratio with
each renderer's CPU per sample over all its runs of the scene (every count and seed) instead.

Do the two renderers compute the same image? Per scene and configuration of ours against Cycles:
each renderer's mean over its runs (weighted by sample count), per 16 x 16 block the z-score of the
difference of the block means of luminance (variance from the seeds' spread), the count of blocks
beyond 4 standard errors, the mean of z^2 (about 1 when they agree; lower where the noise is
heavy-tailed, as each block's variance comes from the same runs as its difference) and the ratio
of the image means.
Writes OUTDIR/cycles.md, OUTDIR/cycles.csv and OUTDIR/png/*.png; prints cycles.md.
"""
import array
import csv
import math
import os
import random
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exrtool  # noqa: E402

BLOCK = 16
Z_FLAG = 4.0
TARGET = 0.8
BOOTSTRAP = 2000
LUMA = (0.2126, 0.7152, 0.0722)


def load_runs(out):
    with open(os.path.join(out, "runs.csv")) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        r["spp"] = int(r["spp"])
        r["seed"] = int(r["seed"])
        r["cpu"] = float(r["user_s"]) + float(r["sys_s"])
        r["wall"] = float(r["wall_s"])
    return rows


def read_image(path):
    img = exrtool.read_exr(path)
    return img.width, img.height, array.array("d", img.rgb)


def luminance(rgb):
    n = len(rgb) // 3
    r, g, b = LUMA
    return array.array("d", (r * rgb[3 * i] + g * rgb[3 * i + 1] + b * rgb[3 * i + 2] for i in range(n)))


def sample_variance(images):
    """Per entry, the unbiased sample variance over the images (two: 0.5 (a - b)^2)."""
    k = len(images)
    if k == 2:
        a, b = images
        return array.array("d", (0.5 * (x - y) * (x - y) for x, y in zip(a, b)))
    out = array.array("d", bytes(8 * len(images[0])))
    for i, xs in enumerate(zip(*images)):
        m = sum(xs) / k
        out[i] = sum((x - m) * (x - m) for x in xs) / (k - 1)
    return out


def block_ids(w, h):
    nbx = (w + BLOCK - 1) // BLOCK
    return [(y // BLOCK) * nbx + x // BLOCK for y in range(h) for x in range(w)], nbx * ((h + BLOCK - 1) // BLOCK)


def percentile(sorted_xs, q):
    pos = q * (len(sorted_xs) - 1)
    lo = int(math.floor(pos))
    hi = min(lo + 1, len(sorted_xs) - 1)
    return sorted_xs[lo] + (pos - lo) * (sorted_xs[hi] - sorted_xs[lo])


def fmt(x, digits=3):
    if x is None or x != x:
        return "-"
    return f"{x:.{digits}g}"


class Scene:
    """One scene's groups (renderer, config, spp) -> runs, with relVar and block sums per group."""

    def __init__(self, name, rows):
        self.name = name
        self.startup = {}
        for key in {(r["renderer"], r["config"]) for r in rows if r["kind"] == "startup"}:
            cpus = [r["cpu"] for r in rows if r["kind"] == "startup" and (r["renderer"], r["config"]) == key]
            self.startup[key] = sum(cpus) / len(cpus)
        self.groups = {}
        for r in rows:
            if r["kind"] == "test":
                self.groups.setdefault((r["renderer"], r["config"], r["spp"]), []).append(r)
        for runs in self.groups.values():
            runs.sort(key=lambda r: r["seed"])
        refs = [r for r in rows if r["kind"] == "ref"]
        self.ref = max(refs, key=lambda r: r["spp"]) if refs else None
        self.stats = {}
        self.missing_startup = set()

    def net_cpu(self, r):
        t1 = self.startup.get((r["renderer"], r["config"]))
        if t1 is None:
            self.missing_startup.add((r["renderer"], r["config"]))
            return r["cpu"]
        return (r["cpu"] - t1) * r["spp"] / (r["spp"] - 1)

    def cost_per_sample(self, renderer, config):
        """Net CPU s per sample over every test run of a renderer and configuration (all counts, all seeds)."""
        sts = [st for (r, cf, _), st in self.stats.items() if (r, cf) == (renderer, config)]
        n = sum(r["spp"] for st in sts for r in st["runs"])
        return sum(sum(st["cpu"]) for st in sts) / n if n else float("nan")

    def measure(self):
        """relVar, block sums and per-pixel luminance variance of every group with two or more seeds."""
        images, size = {}, None
        for runs in self.groups.values():
            for r in runs:
                w, h, rgb = read_image(r["exr"])
                if size and (w, h) != size:
                    sys.exit(f"report.py: {r['exr']} is {w}x{h}, other renders of {self.name} are {size[0]}x{size[1]}")
                size = (w, h)
                images[r["exr"]] = rgb
        if not images:
            return False
        self.size = size
        w, h = size
        n3 = 3 * w * h
        if self.ref:
            rw, rh, den = read_image(self.ref["exr"])
            if (rw, rh) != size:
                sys.exit(f"report.py: {self.ref['exr']} is {rw}x{rh}, the renders of {self.name} {w}x{h}")
            self.denominator = f"ours {self.ref['config']}, {self.ref['spp']} spp, seed {self.ref['seed']}"
        else:
            total = sum(r["spp"] for runs in self.groups.values() for r in runs)
            den = array.array("d", bytes(8 * n3))
            for runs in self.groups.values():
                for r in runs:
                    f = r["spp"] / total
                    img = images[r["exr"]]
                    for i in range(n3):
                        den[i] += f * img[i]
            self.denominator = "no reference run: the mean of the measured runs (biased low where noise is heavy-tailed)"
        weight = array.array("d", (1.0 / (m * m + exrtool.RELMSE_EPS) for m in den))
        bid, nblocks = block_ids(w, h)
        for key, runs in self.groups.items():
            imgs = [images[r["exr"]] for r in runs]
            lums = [luminance(img) for img in imgs]
            st = {"runs": runs, "cpu": [self.net_cpu(r) for r in runs], "lum_mean": None}
            st["lum_mean"] = array.array("d", (sum(xs) / len(xs) for xs in zip(*lums)))
            if len(runs) >= 2:
                var = sample_variance(imgs)
                blocks = [0.0] * nblocks
                for p in range(w * h):
                    blocks[bid[p]] += (var[3 * p] * weight[3 * p] + var[3 * p + 1] * weight[3 * p + 1]
                                       + var[3 * p + 2] * weight[3 * p + 2])
                st["blocks"] = blocks
                st["relvar"] = sum(blocks) / n3
                st["lum_var"] = sample_variance(lums)
            self.stats[key] = st
        return True


def pooled_log_time_sd(scenes):
    """Per renderer, the pooled sample standard deviation of log net CPU time between seeds."""
    acc = {}
    for sc in scenes:
        for (renderer, _, _), st in sc.stats.items():
            logs = [math.log(t) for t in st["cpu"] if t > 0]
            if len(logs) < 2:
                continue
            m = sum(logs) / len(logs)
            ss, dof = acc.get(renderer, (0.0, 0))
            acc[renderer] = (ss + sum((x - m) ** 2 for x in logs), dof + len(logs) - 1)
    return {k: (math.sqrt(ss / dof), dof) for k, (ss, dof) in acc.items() if dof > 0}


def ratio_row(sc, config, spp, sd, rng):
    o = sc.stats.get(("ours", config, spp))
    c = sc.stats.get(("cycles", "default", spp))
    if not o or not c or "relvar" not in o or "relvar" not in c:
        return None
    t_o = sum(o["cpu"]) / len(o["cpu"])
    t_c = sum(c["cpu"]) / len(c["cpu"])
    row = dict(scene=sc.name, config=config, spp=spp, cpu_ours=o["cpu"], cpu_cycles=c["cpu"],
               relvar_ours=o["relvar"], relvar_cycles=c["relvar"], var_ratio=o["relvar"] / c["relvar"],
               time_ratio=t_o / t_c if t_c > 0 else float("nan"))
    row["ratio"] = row["var_ratio"] * row["time_ratio"]
    cost_o, cost_c = sc.cost_per_sample("ours", config), sc.cost_per_sample("cycles", "default")
    row["ratio_pooled_cost"] = row["var_ratio"] * cost_o / cost_c if cost_c > 0 else float("nan")
    se_t = math.sqrt(sd.get("ours", (0.0, 0))[0] ** 2 / len(o["cpu"]) + sd.get("cycles", (0.0, 0))[0] ** 2 / len(c["cpu"]))
    row["se_log_time"] = se_t
    if not row["time_ratio"] > 0:  # runs too short to tell their cost from the start-up's jitter
        row.update(ratio=float("nan"), lo=float("nan"), hi=float("nan"), verdict="CPU time not measurable")
        return row
    bo, bc = o["blocks"], c["blocks"]
    nb = len(bo)
    log_t = math.log(row["time_ratio"])
    draws = []
    for _ in range(BOOTSTRAP):
        pick = rng.choices(range(nb), k=nb)
        so, sc_ = sum(bo[j] for j in pick), sum(bc[j] for j in pick)
        if so > 0 and sc_ > 0:
            draws.append(math.log(so / sc_) + log_t + rng.gauss(0.0, se_t))
    draws.sort()
    row["lo"], row["hi"] = math.exp(percentile(draws, 0.025)), math.exp(percentile(draws, 0.975))
    if row["hi"] < TARGET:
        row["verdict"] = f"below {TARGET}"
    elif row["lo"] > TARGET:
        row["verdict"] = f"above {TARGET}"
    else:
        row["verdict"] = "undecided"
    return row


def combined(sc, renderer, config):
    """Sample-count-weighted mean luminance over a renderer's runs and its per-pixel variance."""
    groups = [st for (r, cf, _), st in sc.stats.items() if (r, cf) == (renderer, config) and "lum_var" in st]
    if not groups:
        return None
    total = sum(len(st["runs"]) * st["runs"][0]["spp"] for st in groups)
    n = len(groups[0]["lum_mean"])
    mean = array.array("d", bytes(8 * n))
    var = array.array("d", bytes(8 * n))
    for st in groups:
        k, spp = len(st["runs"]), st["runs"][0]["spp"]
        f = k * spp / total  # the group's mean weighs k * spp
        g = k * (spp / total) ** 2  # variance of sum over its k runs of (spp / total) x_run
        lm, lv = st["lum_mean"], st["lum_var"]
        for i in range(n):
            mean[i] += f * lm[i]
            var[i] += g * lv[i]
    spps = sorted({st["runs"][0]["spp"] for st in groups})
    return mean, var, sum(len(st["runs"]) for st in groups), spps


def agreement(sc, config):
    o = combined(sc, "ours", config)
    c = combined(sc, "cycles", "default")
    if not o or not c:
        return None
    w, h = sc.size
    bid, nblocks = block_ids(w, h)
    n = w * h
    sums = [[0.0, 0.0, 0.0, 0.0, 0] for _ in range(nblocks)]
    for p in range(n):
        s = sums[bid[p]]
        s[0] += o[0][p]
        s[1] += c[0][p]
        s[2] += o[1][p]
        s[3] += c[1][p]
        s[4] += 1
    zs = []
    for b, (so, sc_, vo, vc, k) in enumerate(sums):
        se = math.sqrt(vo + vc)
        zs.append((b, (sc_ - so) / se if se > 0 else 0.0))
    mo, mc = sum(o[0]) / n, sum(c[0]) / n
    se_o, se_c = math.sqrt(sum(o[1])) / n, math.sqrt(sum(c[1])) / n
    ratio = mc / mo if mo > 0 else float("nan")
    se_ratio = ratio * math.sqrt((se_o / mo) ** 2 + (se_c / mc) ** 2) if mo > 0 and mc > 0 else float("nan")
    zmax = max(zs, key=lambda t: abs(t[1]))
    nbx = (w + BLOCK - 1) // BLOCK
    return dict(scene=sc.name, config=config, runs_ours=o[2], runs_cycles=c[2], spp_ours=o[3], spp_cycles=c[3],
                flagged=sum(1 for _, z in zs if abs(z) > Z_FLAG), blocks=nblocks,
                mean_z2=sum(z * z for _, z in zs) / len(zs), zmax=zmax[1],
                zmax_at=((zmax[0] % nbx) * BLOCK, (zmax[0] // nbx) * BLOCK), ratio=ratio, se_ratio=se_ratio,
                z_image=(mc - mo) / math.sqrt(se_o ** 2 + se_c ** 2) if se_o + se_c > 0 else 0.0,
                zs=zs, mean_ours=o[0], mean_cycles=c[0])


def exposure(lum):
    s = sorted(lum)
    p = s[int(0.97 * (len(s) - 1))]
    return 0.85 / p if p > 0 else 1.0


def write_pngs(out, sc, ag):
    pdir = os.path.join(out, "png")
    os.makedirs(pdir, exist_ok=True)
    w, h = sc.size
    k = exposure(ag["mean_ours"])
    grey = lambda lum: [v for x in lum for v in (x, x, x)]  # noqa: E731
    tag = f"{sc.name}_{ag['config']}"
    exrtool.write_png(os.path.join(pdir, f"{tag}_mean_ours.png"), w, h, grey(ag["mean_ours"]), k)
    exrtool.write_png(os.path.join(pdir, f"{tag}_mean_cycles.png"), w, h, grey(ag["mean_cycles"]), k)
    nbx = (w + BLOCK - 1) // BLOCK
    img = [0.0] * (3 * w * h)
    for b, z in ag["zs"]:  # red where Cycles is brighter, blue darker; full at |z| = 2 Z_FLAG
        v = min(1.0, abs(z) / (2 * Z_FLAG))
        col = (v, 0.0, 0.0) if z > 0 else (0.0, 0.0, v)
        bx, by = (b % nbx) * BLOCK, (b // nbx) * BLOCK
        for y in range(by, min(h, by + BLOCK)):
            for x in range(bx, min(w, bx + BLOCK)):
                img[3 * (y * w + x):3 * (y * w + x) + 3] = col
    exrtool.write_png(os.path.join(pdir, f"{tag}_blockz.png"), w, h, img)


def main():
    if len(sys.argv) != 2 or sys.argv[1].startswith("-"):
        sys.exit(__doc__)
    out = sys.argv[1]
    rows = load_runs(out)
    path = os.path.join(out, "settings.txt")
    settings = open(path).read().strip() if os.path.exists(path) else ""
    names = []
    for r in rows:
        if r["scene"] not in names:
            names.append(r["scene"])
    scenes = []
    for name in names:
        sc = Scene(name, [r for r in rows if r["scene"] == name])
        if sc.measure():
            scenes.append(sc)
    configs = []
    for r in rows:
        if r["renderer"] == "ours" and r["config"] not in configs:
            configs.append(r["config"])
    sd = pooled_log_time_sd(scenes)
    rng = random.Random(57)
    ratios = []
    for sc in scenes:
        for spp in sorted({k[2] for k in sc.stats}):
            for config in configs:
                row = ratio_row(sc, config, spp, sd, rng)
                if row:
                    ratios.append(row)
    md = ["# pt against Blender Cycles: time to equal noise", "", "```", settings, "```", "",
          "relVar: the variance of one run (from the spread between seeds) relative to the scene's mean image, "
          "averaged over pixels and channels. CPU s: user + sys of the run less the start-up, per seed. Ratio: "
          "(relVar x CPU) ours / Cycles, the CPU time ours needs for Cycles' noise at that sample count over "
          "Cycles'; below 1 ours is faster. 95% interval: block bootstrap of the variance ratio and the pooled "
          "seed-to-seed scatter of CPU time "
          + ", ".join(f"{k} {100 * v[0]:.1f}% ({v[1]} dof)" for k, v in sorted(sd.items())) + " (the "
          "interval does not cover the load changing between sample counts). Last column: the same ratio with "
          "each renderer's CPU per sample taken over all its runs of the scene, at every count, which averages "
          "the load over more runs. m in relVar's var / (m^2 + 1e-3), per scene: "
          + "; ".join(f"{sc.name} {sc.denominator}" for sc in scenes) + ".", ""]
    for spp in sorted({r["spp"] for r in ratios}):
        md += [f"## {spp} samples per pixel", "",
               "| scene | ours config | CPU s ours (per seed) | CPU s Cycles (per seed) | relVar ours | relVar Cycles "
               "| variance ratio | CPU ratio | time to equal noise, ours / Cycles | 95% interval | target 0.8 "
               "| same, CPU per sample over all counts |",
               "|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in (r for r in ratios if r["spp"] == spp):
            md.append(f"| {r['scene']} | {r['config']} | {', '.join(fmt(t, 4) for t in r['cpu_ours'])} | "
                      f"{', '.join(fmt(t, 4) for t in r['cpu_cycles'])} | {fmt(r['relvar_ours'], 4)} | "
                      f"{fmt(r['relvar_cycles'], 4)} | {fmt(r['var_ratio'])} | {fmt(r['time_ratio'])} | "
                      f"**{fmt(r['ratio'])}** | {fmt(r['lo'])} - {fmt(r['hi'])} | {r['verdict']} | "
                      f"{fmt(r['ratio_pooled_cost'])} |")
        md.append("")
    md += ["## Do the renderers compute the same image?", "",
           "Each renderer's mean over all its runs (weighted by sample count; `runs`, at the sample counts listed), "
           f"z-scores of the difference of {BLOCK} x {BLOCK}-pixel block means of luminance (negative where Cycles "
           "is darker; variance from the seeds' spread), the mean of z^2 (about 1 when they agree, less with "
           "heavy-tailed noise) and the ratio "
           "of the image means of luminance, Cycles / ours, with its standard error and z.", "",
           "| scene | ours config | runs ours / Cycles | spp | blocks abs(z) > 4 | mean z^2 | largest z (block corner) | "
           "image mean, Cycles / ours | z |", "|---|---|---|---|---|---|---|---|---|"]
    agree_rows = []
    for sc in scenes:
        for config in configs:
            ag = agreement(sc, config)
            if not ag:
                continue
            agree_rows.append(ag)
            md.append(f"| {sc.name} | {config} | {ag['runs_ours']} / {ag['runs_cycles']} | "
                      f"{' '.join(map(str, ag['spp_ours']))} | {ag['flagged']} of {ag['blocks']} | "
                      f"{fmt(ag['mean_z2'])} | {ag['zmax']:+.2f} at {ag['zmax_at']} | "
                      f"{ag['ratio']:.5f} +- {ag['se_ratio']:.5f} | {ag['z_image']:+.2f} |")
            write_pngs(out, sc, ag)
    all_spp = sorted({k[2] for sc in scenes for k in sc.stats})
    md += ["", "## Start-up and cost per sample", "",
           "Start-up: mean CPU s of the 1-sample runs (less one sample at the largest count's cost). CPU ms per "
           "sample at each count: net CPU / spp, mean over seeds (on a shared machine it drifts with the load).", "",
           "| scene | renderer | start-up CPU s | " + " | ".join(f"CPU ms per sample at {n}" for n in all_spp) + " |",
           "|---|---|---|" + "---|" * len(all_spp)]
    for sc in scenes:
        for key, t1 in sorted(sc.startup.items(), key=lambda kv: (kv[0][0] != "ours", kv[0][1])):
            per = {spp: sum(st["cpu"]) / len(st["cpu"]) / spp
                   for (r, cf, spp), st in sc.stats.items() if (r, cf) == key}
            if not per:
                continue
            label = "Cycles" if key[0] == "cycles" else "ours " + key[1]
            md.append(f"| {sc.name} | {label} | {fmt(t1 - per[max(per)], 3)} | "
                      + " | ".join(fmt(1e3 * per[n], 4) if n in per else "-" for n in all_spp) + " |")
        for key in sorted(sc.missing_startup):
            md.append(f"| {sc.name} | {key[0]} {key[1]} | no 1-sample run: CPU times include the start-up |"
                      + " |" * len(all_spp))
    keys = ["scene", "config", "spp", "cpu_ours", "cpu_cycles", "relvar_ours", "relvar_cycles", "var_ratio",
            "time_ratio", "ratio", "lo", "hi", "verdict", "se_log_time", "ratio_pooled_cost"]
    with open(os.path.join(out, "cycles.csv"), "w", newline="") as f:
        wr = csv.writer(f)
        wr.writerow(keys)
        for r in ratios:
            wr.writerow([" ".join(f"{t:.4f}" for t in r[k]) if isinstance(r[k], list)
                         else f"{r[k]:.6g}" if isinstance(r[k], float) else r[k] for k in keys])
    with open(os.path.join(out, "cycles.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
