#!/usr/bin/env bash
# check_core.sh SRC: librestir builds alone (cmake -DRESTIR_BUILD_RENDERER=OFF: no Embree, OpenEXR,
# assimp or SDL2 needed), with FFTW and, hiding every pkg-config package, without it; it exports
# only restir_-prefixed symbols; and `cmake --install` gives a package that examples/ris_1d builds
# and runs against through find_package(restir) and through pkg-config. Exits 1 naming what failed.
# Run by ctest as lint.core_alone.
set -euo pipefail
src=${1:?usage: check_core.sh SRC}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
build() { # $1: folder; the rest: environment for the configure step
  local dir=$1
  shift
  if ! env "$@" cmake -S "$src" -B "$dir" -DRESTIR_BUILD_RENDERER=OFF -DCMAKE_BUILD_TYPE=Release \
       -DCMAKE_INSTALL_PREFIX="$dir.prefix" > "$dir.log" 2>&1 ||
     ! cmake --build "$dir" -j 2 >> "$dir.log" 2>&1; then
    echo "check_core: librestir alone does not build ($*):"; tail -20 "$dir.log"; exit 1
  fi
}
build "$work/with_fftw"
build "$work/without_fftw" PKG_CONFIG_LIBDIR=/nonexistent
if grep -q 'fftw' <(nm "$work/without_fftw/librestir_core.a"); then
  echo "check_core: the build without FFTW still references it"; exit 1
fi
bad=$(nm -g --defined-only "$work/with_fftw/librestir_core.a" | awk '$2 ~ /^[TDBR]$/ && $3 !~ /^restir_/ {print $3}' | sort -u)
if [ -n "$bad" ]; then
  echo "check_core: librestir exports symbols without the restir_ prefix:"; echo "$bad"; exit 1
fi
so=$(ls "$work"/with_fftw/librestir.so.* 2> /dev/null | head -1)
[ -n "$so" ] || { echo "check_core: no shared librestir.so.N was built"; exit 1; }
# (a named OpenMP critical section is the symbol .gomp_critical_user_NAME; ours are named restir_*)
bad=$(nm -D --defined-only "$so" | awk '$2 ~ /^[TDBRVW]$/ && $3 !~ /^restir_/ && $3 !~ /^_(init|fini)$/ &&
                                        $3 !~ /^\.gomp_critical_user_restir_/ {print $3}' | sort -u)
if [ -n "$bad" ]; then
  echo "check_core: $so exports symbols without the restir_ prefix:"; echo "$bad"; exit 1
fi
prefix="$work/with_fftw.prefix"
if ! cmake --install "$work/with_fftw" > "$work/install.log" 2>&1; then
  echo "check_core: cmake --install failed:"; tail -20 "$work/install.log"; exit 1
fi
if ! cmake -S "$src/examples/ris_1d" -B "$work/example" -DCMAKE_PREFIX_PATH="$prefix" > "$work/example.log" 2>&1 ||
   ! cmake --build "$work/example" >> "$work/example.log" 2>&1 || ! "$work/example/ris_1d"; then
  echo "check_core: examples/ris_1d through find_package(restir):"; tail -20 "$work/example.log"; exit 1
fi
pc="$prefix/lib/pkgconfig"
[ -d "$pc" ] || pc=$(dirname "$(find "$prefix" -name restir.pc | head -1)")
flags=$(PKG_CONFIG_PATH="$pc" pkg-config --cflags --libs --static restir)
# shellcheck disable=SC2086
if ! cc -std=c11 -O2 "$src/examples/ris_1d/ris_1d.c" $flags -o "$work/ris_1d_pc" || ! "$work/ris_1d_pc"; then
  echo "check_core: examples/ris_1d through pkg-config ($flags) failed"; exit 1
fi
echo "check_core: librestir (static and $(basename "$so")) builds alone with and without FFTW, exports only"
echo "restir_ symbols, installs, and"
echo "examples/ris_1d builds and passes against the installed package (find_package and pkg-config)"
