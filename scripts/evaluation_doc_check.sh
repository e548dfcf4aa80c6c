#!/bin/sh
# evaluation_doc_check.sh RESTIR SOURCE_DIR: the ctest lint.evaluation_doc: docs/EVALUATION.md is what
# `scripts/evaluation_doc.sh RESTIR docs/evaluation/data` writes today, so the page holds only tables
# regenerated from the committed data (no hand edit, no table of another commit).
set -eu
if [ $# -ne 2 ]; then
    echo "usage: scripts/evaluation_doc_check.sh RESTIR SOURCE_DIR" >&2
    exit 2
fi
src=$2
out=$(mktemp)
trap 'rm -f "$out"' EXIT
sh "$src/scripts/evaluation_doc.sh" "$1" "$src/docs/evaluation/data" > "$out"
if ! diff -u "$src/docs/EVALUATION.md" "$out"; then
    echo "evaluation_doc_check.sh: docs/EVALUATION.md is not what the data gives: run" >&2
    echo "  scripts/evaluation_doc.sh build/restir docs/evaluation/data > docs/EVALUATION.md" >&2
    exit 1
fi
echo "docs/EVALUATION.md is regenerated from docs/evaluation/data"
