#!/usr/bin/env bash
# demo.sh: renders the default scene (many-lights) with ReSTIR DI and with path tracing at equal
# time, writes EXR and PNG to out/demo/, and prints frame time and error against a reference. The two
# methods are the registry's (`restir list --json`): its "demo" method against its "reference".
set -euo pipefail
restir=${1:-build/restir}
out=out/demo
registry() { python3 "$(dirname "$0")/registry.py" "$restir" "$@"; }
demo=$(registry role demo)
reference=$(registry role reference)
echo "Rendering many-lights at 640x360: a 512-spp direct-lighting reference, then 17 frames of"
echo "$demo and path tracing given the same time per frame (error measured at frame 16)."
"$restir" compare --scene many-lights --methods "$demo,$reference" --equal-time --frames 17 --res 640x360 \
    --ref-spp 512 --out "$out" --force # each demo replaces the last one's images
echo
echo "Images: $out/$demo/frame_0016.png, $out/$reference/frame_0016.png, reference $out/reference.exr"
