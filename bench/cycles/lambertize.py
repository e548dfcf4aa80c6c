#!/usr/bin/env python3
"""lambertize.py IN.json OUT.json: a restir JSON scene with every material made a pure Lambertian.

Each material gets "lambert": true (no specular layer: what Cycles' Diffuse BSDF computes) and loses
"metallic" and "roughness", which a Lambertian ignores; its base colour becomes the diffuse albedo,
so a metal block of base colour C becomes a diffuse block of albedo C. Emission is kept. The result
is a different scene from IN (no glossy reflections), used by bench/cycles/run.sh to compare the
same integral in both renderers: `restir scene export cornell --out DIR` then this script.
"""
import json
import os
import sys


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1]) as f:
        scene = json.load(f)
    changed = 0
    for m in scene.get("materials", []):
        if m.get("metallic", 0) != 0 or m.get("roughness", 1) != 1 or not m.get("lambert", False):
            changed += 1
        m.pop("metallic", None)
        m.pop("roughness", None)
        m["lambert"] = True
    scene["name"] = scene.get("name", "scene")
    tmp = sys.argv[2] + ".tmp"
    with open(tmp, "w") as f:
        json.dump(scene, f, indent=1)
    os.replace(tmp, sys.argv[2])
    print(f"{sys.argv[2]}: {changed} of {len(scene.get('materials', []))} materials made Lambertian")


if __name__ == "__main__":
    main()
