#!/bin/sh
# evaluation_check.sh RESTIR DATA: the ctest lint.evaluation_check (CI runs it on docs/evaluation/data):
# `RESTIR evaluate --check DATA`, which renders every row of every table recorded there tiny with its
# recorded settings and fails (exit 1, naming the tables) when today's code renders one differently,
# so a stale verdict cannot sit in the docs. Passes, saying so, while DATA holds no step yet.
set -eu
if [ $# -ne 2 ]; then
    echo "usage: scripts/evaluation_check.sh RESTIR DATA" >&2
    exit 2
fi
bin=$1
data=$2
if [ ! -d "$data" ] || [ -z "$(find "$data" \( -name settings.json -o -name provenance.json -o -name study.csv \
    -o -name compare.csv \) -print | head -n 1)" ]; then
    echo "evaluation_check.sh: $data holds no evaluation step yet: nothing to check (scripts/evaluation_export.sh puts them there)"
    exit 0
fi
exec "$bin" evaluate --check "$data"
