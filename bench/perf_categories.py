#!/usr/bin/env python3
"""bench/perf_categories.py PERF.DATA: a perf profile's self time by kind of work (docs/BENCHMARKS.md's
profile summary): Embree (its DSO), the kernel, the OpenMP runtime, and our functions grouped by
name into the candidate loop, shifts, BSDF work, G-buffer, reuse passes and the rest. Prints
Markdown table rows. Record with e.g.
    perf record -g -o di.perf build/restir render --scene many-lights --method restir-di --frames 16
"""
import re, subprocess, sys, collections
data = sys.argv[1]
out = subprocess.run(['perf', 'report', '-i', data, '--no-children', '--sort', 'dso,symbol', '-g', 'none', '--stdio'],
                     capture_output=True, text=True).stdout
cats = collections.OrderedDict((k, 0.0) for k in ['Embree', 'kernel (page faults, interrupts)', 'OpenMP runtime', 'candidate loop (initial RIS)', 'shifts and path replay', 'BSDF evaluation / sampling', 'G-buffer and history', 'reuse passes (merges, MIS, selection)', 'reconstruction / cells / other passes', 'libm / libc', 'other'])
rules = [
 ('candidate loop (initial RIS)', r'initial_pixel|di_initial|light_pool|bsdf_frame_eval_batch|pt_initial|path_walk|di_unshadowed|warp_|sample_light|emitter'),
 ('shifts and path replay', r'path_shift|reconnection|shift_|path_vertex|replay'),
 ('BSDF evaluation / sampling', r'bsdf_|ggx|schlick|frame_'),
 ('G-buffer and history', r'gbuffer|camera_|history|reproject'),
 ('reuse passes (merges, MIS, selection)', r'spatial|temporal|restir_mis|gris|select|prepare_search|neighbor|merge|shade|target|wrs|spmis|cell'),
 ('reconstruction / cells / other passes', r'poisson|rp_|grad|nonfinite|exr|png'),
]
for line in out.splitlines():
    m = re.match(r'\s*([\d.]+)%\s+(\S+)\s+\[(.)\]\s+(\S+)', line)
    if not m: continue
    pct, dso, kind, sym = float(m.group(1)), m.group(2), m.group(3), m.group(4)
    if 'embree' in dso: c = 'Embree'
    elif kind == 'k' or 'kernel' in dso: c = 'kernel (page faults, interrupts)'
    elif 'gomp' in dso: c = 'OpenMP runtime'
    elif 'libm' in dso or 'libc' in dso: c = 'libm / libc'
    else:
        c = 'other'
        for name, pat in rules:
            if re.search(pat, sym): c = name; break
    cats[c] += pct
for k, v in cats.items():
    print(f'| {k} | {v:.1f}% |')
