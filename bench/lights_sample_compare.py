#!/usr/bin/env python3
"""lights_sample_compare.py: pt's time per sample and variance per sample under several settings
(lights.sample=area against solid-angle), measured in one run on the same machine.

    bench/lights_sample_compare.py [--bin build/restir] [--scenes a,b,...] [--res WxH] [--spp N]
        [--seeds N] [--threads N] [--out DIR] [--config NAME=key=value,key=value ...]

Per scene, every configuration renders SEEDS independent one-frame images of SPP paths per pixel and
as many 1-sample renders for the start-up, configurations alternating seed by seed (a busy machine
slows them alike). Reported per configuration:
  - CPU us per path: (user + system CPU time of the SPP render - that of a 1-sample render) /
    ((SPP - 1) x pixels), each the median over seeds (CPU time, not wall time: the machine is shared,
    and the median, as a render now and then takes 20% longer there);
  - variance per sample: the mean over pixels and channels of the seeds' sample variance of a pixel
    over (R^2 + 1e-3), R the mean of every image of the scene (all configurations are unbiased, so
    R is one denominator for all), times SPP;
  - the ratios to the first configuration of both and of their product (time to equal variance:
    below 1, the configuration reaches a noise level sooner).
Default configurations: area (lights.sample=area) and solid-angle (lights.sample=solid-angle), on
top of pt's defaults.
"""
import argparse
import os
import resource
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "cycles"))
import exrtool  # noqa: E402


def cpu_of_child(cmd, env=None):
    """Runs cmd (output discarded) and returns its user + system CPU seconds."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, env=env)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def median(values):
    v = sorted(values)
    return 0.5 * (v[(len(v) - 1) // 2] + v[len(v) // 2])


def render(args, scene, sets, spp, seed, out):
    binary = next((kv[1:] for kv in sets if kv.startswith("@")), args.bin)
    env = dict(os.environ)
    env.update(kv[1:].split("=", 1) for kv in sets if kv.startswith("%"))
    sets = [kv for kv in sets if kv[0] not in "@%"]
    cmd = [binary, "render", "--scene", scene, "--method", "pt", "--res", args.res, "--spp", str(spp),
           "--seed", str(seed), "--threads", str(args.threads), "--out", out, "--force"]
    for kv in sets:
        cmd += ["--set", kv]
    cpu = cpu_of_child(cmd, env)
    return cpu, os.path.join(out, "frame_0000.exr")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", default="build/restir")
    ap.add_argument("--scenes", default="cornell,bench/cycles/scenes/box.json,many-lights")
    ap.add_argument("--res", default="160x120")
    ap.add_argument("--spp", type=int, default=32)
    ap.add_argument("--seeds", type=int, default=4)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--out", default="out/lights-sample-compare")
    ap.add_argument("--config", action="append", default=[],
                    help="NAME=key=value,key=value (repeatable; default: area and solid-angle); an item @PATH "
                         "renders that configuration with the binary PATH (an earlier build), %%VAR=VALUE sets an "
                         "environment variable for it")
    args = ap.parse_args()
    configs = []
    for c in args.config or ["area=lights.sample=area", "solid-angle=lights.sample=solid-angle"]:
        name, _, sets = c.partition("=")
        configs.append((name, [kv for kv in sets.split(",") if kv]))
    w, h = (int(v) for v in args.res.split("x"))
    os.makedirs(args.out, exist_ok=True)
    print("| scene | configuration | CPU us / path | variance / sample | time ratio | variance ratio | "
          "time to equal variance |")
    print("|---|---|---|---|---|---|---|")
    for scene in args.scenes.split(","):
        name = os.path.splitext(os.path.basename(scene))[0]
        start = {c: [] for c, _ in configs}
        cpu = {c: [] for c, _ in configs}
        images = {c: [] for c, _ in configs}
        for seed in range(1, args.seeds + 1):
            for cname, sets in configs:
                t, _ = render(args, scene, sets, 1, 1000 + seed, os.path.join(args.out, "start"))
                start[cname].append(t)
                t, exr = render(args, scene, sets, args.spp, seed, os.path.join(args.out, "run"))
                cpu[cname].append(t)
                images[cname].append(exrtool.read_exr(exr).rgb)
        n = 3 * w * h
        mean = [0.0] * n
        count = 0
        for cname, _ in configs:
            for img in images[cname]:
                count += 1
                for i in range(n):
                    mean[i] += img[i]
        denom = [(m / count) ** 2 + 1e-3 for m in mean]
        rows = []
        for cname, _ in configs:
            imgs = images[cname]
            k = len(imgs)
            total = 0.0
            for i in range(n):
                m = sum(img[i] for img in imgs) / k
                total += sum((img[i] - m) ** 2 for img in imgs) / (k - 1) / denom[i]
            var_sample = total / n * args.spp
            us_path = (median(cpu[cname]) - median(start[cname])) / ((args.spp - 1) * w * h) * 1e6
            rows.append((cname, us_path, var_sample))
        base = rows[0]
        for cname, us, var in rows:
            print("| %s | %s | %.3f | %.4g | %.3f | %.3f | %.3f |" % (name, cname, us, var, us / base[1], var / base[2],
                                                                   us * var / (base[1] * base[2])))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
