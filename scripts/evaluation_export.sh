#!/bin/sh
# evaluation_export.sh EVALDIR DEST: copies the small files of a `restir evaluate` folder into DEST
# (docs/evaluation/data/NAME), so the campaign's tables outlive its machine and its jobs' outputs:
# EVALDIR/plan.json, and for each step (a folder of EVALDIR with a plan.json) its plan.json, the CSV
# files the merge wrote at its top (study.csv or compare.csv, runs.csv, passes.csv, ...),
# provenance.json and settings.json. Nothing else: no images, no runs/, no job logs. On the copy,
#   restir evaluate --tables DEST   writes DEST/evaluation.md and claims.csv from these files alone
#   restir evaluate --check DEST    renders every row of every table tiny and compares the hashes
# A step that is not merged yet (no settings.json) is copied with its plan.json only and named;
# `restir evaluate --tables DEST --partial` then names it as not finished.
set -eu
if [ $# -ne 2 ]; then
    echo "usage: scripts/evaluation_export.sh EVALDIR DEST (e.g. docs/evaluation/data/004-1080-pillars)" >&2
    exit 2
fi
src=$1
dest=$2
if [ ! -f "$src/plan.json" ] || ! grep -q '"kind":[[:space:]]*"evaluate"' "$src/plan.json"; then
    echo "evaluation_export.sh: $src holds no evaluation (no plan.json of restir evaluate)" >&2
    exit 2
fi
mkdir -p "$dest"
cp "$src/plan.json" "$dest/plan.json"
steps=0
unmerged=""
for step in "$src"/*/; do
    step=${step%/}
    name=$(basename "$step")
    [ "$name" = runs ] && continue
    [ -f "$step/plan.json" ] || continue
    mkdir -p "$dest/$name"
    cp "$step/plan.json" "$dest/$name/plan.json"
    for f in "$step"/*.csv "$step/provenance.json" "$step/settings.json"; do
        [ -f "$f" ] && cp "$f" "$dest/$name/"
    done
    if [ ! -f "$step/settings.json" ]; then
        unmerged="$unmerged $name"
    fi
    steps=$((steps + 1))
done
echo "evaluation_export.sh: $steps steps of $src copied into $dest ($(du -sh "$dest" | cut -f1))"
if [ -n "$unmerged" ]; then
    echo "evaluation_export.sh: not merged yet (plan.json only):$unmerged"
fi
