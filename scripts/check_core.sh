#!/usr/bin/env bash
# check_core.sh SRC: librestir builds alone (cmake -DRESTIR_BUILD_RENDERER=OFF: no Embree, OpenEXR,
# assimp or SDL2 needed), with FFTW and, hiding every pkg-config package, without it; and it exports
# only restir_-prefixed symbols. Exits 1 naming what failed. Run by ctest as lint.core_alone.
set -euo pipefail
src=${1:?usage: check_core.sh SRC}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
build() { # $1: folder; the rest: environment for the configure step
  local dir=$1
  shift
  if ! env "$@" cmake -S "$src" -B "$dir" -DRESTIR_BUILD_RENDERER=OFF -DCMAKE_BUILD_TYPE=Release > "$dir.log" 2>&1 ||
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
echo "check_core: librestir builds alone with and without FFTW; every exported symbol is restir_-prefixed"
