#!/bin/sh
# scripts/fuzz.sh BUILD SECONDS [HARNESS...]: runs each libFuzzer harness (BUILD/fuzz_NAME, from
# fuzz/fuzz_NAME.c; all of them when none is named) for SECONDS under ASan and UBSan. Seeds:
# fuzz/seeds/NAME, and for the mesh harness prefixed copies of small assimp test models (when
# assimp-testmodels is installed); dictionary fuzz/dict/NAME.dict where there is one. The corpus
# each grows stays in BUILD/corpus/NAME, its log in BUILD/NAME.log, a crashing input in
# BUILD/crash-NAME-*. Exits 1 at the first harness that finds something, showing its log's end.
set -eu
build=$1
seconds=$2
shift 2
names="$*"
[ -n "$names" ] || names=$(ls fuzz/fuzz_*.c | sed 's|fuzz/fuzz_||; s|\.c$||')

# Format byte (fuzz_mesh_import.c) + the file, for the models small enough to mutate quickly.
models=/usr/share/assimp/models
extra=$build/extra_seeds/mesh_import
mkdir -p "$extra"
if [ -d "$models" ]; then
    find "$models/OBJ" "$models/PLY" "$models/OFF" "$models/glTF2" -type f -size -64k \
        \( -name '*.gltf' -o -name '*.obj' -o -name '*.ply' -o -name '*.off' -o -name '*.glb' \) 2>/dev/null |
        while read -r f; do
            case "$f" in
            *.gltf) b='\000' ;; *.obj) b='\001' ;; *.ply) b='\002' ;; *.off) b='\003' ;; *) b='\004' ;;
            esac
            out="$extra/$(echo "$f" | sed 's|/|_|g')"
            { printf "$b"; cat "$f"; } >"$out"
        done
fi

for name in $names; do
    bin=$build/fuzz_$name
    [ -x "$bin" ] || { echo "fuzz.sh: $bin is missing (build it first)" >&2; exit 2; }
    mkdir -p "$build/corpus/$name"
    set -- -max_total_time="$seconds" -timeout=30 -rss_limit_mb=4096 -max_len=65536 -print_final_stats=1 \
        -artifact_prefix="$build/crash-$name-"
    [ -f "fuzz/dict/$name.dict" ] && set -- "$@" -dict="fuzz/dict/$name.dict"
    set -- "$@" "$build/corpus/$name" "fuzz/seeds/$name"
    [ "$name" = mesh_import ] && [ -n "$(ls "$extra")" ] && set -- "$@" "$extra"
    echo "== fuzz_$name for $seconds s"
    if ! ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=fuzz/lsan.supp "$bin" "$@" >"$build/$name.log" 2>&1; then
        tail -60 "$build/$name.log"
        echo "fuzz.sh: fuzz_$name found a problem (input: $build/crash-$name-*)" >&2
        exit 1
    fi
    grep -E '^stat::(number_of_executed_units|peak_rss_mb)|^#[0-9]+.*DONE|cov:' "$build/$name.log" | tail -3
done
