#!/usr/bin/env bash
# check_core.sh SRC: librestir alone, as an engine programmer gets it. Run by ctest as
# lint.core_alone; exits 1 naming what failed.
#  - Three core-only builds (cmake -DRESTIR_BUILD_RENDERER=OFF): "full" (OpenMP and FFTW), "clean"
#    (pkg-config sees no package: what a Debian 12 machine with only build-essential, cmake and
#    pkg-config has, OpenMP coming with gcc) and "minimal" (no OpenMP, no FFTW). For each: it
#    compiles with no include folder outside the source and build trees, the shared library needs
#    no library beyond what that configuration allows (readelf NEEDED), and its ctest (core.*, the
#    bad-input contract) passes.
#  - The static and shared libraries define only restir_-prefixed global symbols (nm, nm -D).
#  - The public headers compile as C++ (g++ -std=c++11 -Wall -Wextra -Wpedantic -Werror).
#  - `cmake --install --prefix` of the full and clean builds, into a prefix other than the configured one, gives
#    packages that the examples (ris_1d, restir_di, poisson) build and run against through find_package(restir)
#    and through pkg-config; examples/cuda is compiled with nvcc and run (its CPU half without a GPU) when nvcc
#    is on the PATH or in /usr/local/cuda/bin, and skipped with a message when not.
set -euo pipefail
src=${1:?usage: check_core.sh SRC}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() {
  echo "check_core: $1"
  [ -z "${2:-}" ] || tail -20 "$2"
  exit 1
}

# build NAME ALLOWED_NEEDED CMAKE_ARGS...: configure, build and test one core-only build in
# $work/NAME, configured for the prefix $work/NAME.configured but installed with `cmake --install --prefix` into
# $work/NAME.prefix (as docs/API.md does), so that nothing installed may depend on the configured prefix
# (restir.pc and restirConfig.cmake find theirs from where they lie). ALLOWED_NEEDED: a regex of the shared
# libraries librestir.so may need. PKG_CONFIG_LIBDIR in the environment is passed on to the configure step.
build() {
  local name=$1 allowed=$2 dir="$work/$1"
  shift 2
  cmake -S "$src" -B "$dir" -DRESTIR_BUILD_RENDERER=OFF -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXPORT_COMPILE_COMMANDS=ON \
    -DCMAKE_INSTALL_PREFIX="$dir.configured" "$@" > "$dir.log" 2>&1 ||
    fail "the $name build does not configure:" "$dir.log"
  cmake --build "$dir" -j 2 >> "$dir.log" 2>&1 || fail "the $name build does not build:" "$dir.log"
  local outside
  outside=$(grep -oE -- '-(I|isystem) ?[^ "]+' "$dir/compile_commands.json" | sed -E 's/^-(I|isystem) ?//' | sort -u |
    awk -v a="$src" -v b="$dir" 'index($0 "/", a "/") != 1 && index($0 "/", b "/") != 1' || true)
  [ -z "$outside" ] || fail "the $name build includes from outside the source and build trees: $outside"
  local so needed
  so=$(ls "$dir"/librestir.so.* 2> /dev/null | head -1)
  [ -n "$so" ] || fail "the $name build made no shared librestir.so.N"
  needed=$(readelf -d "$so" | sed -nE 's/.*NEEDED.*\[(.*)\]/\1/p' | grep -vE "^($allowed)" || true)
  [ -z "$needed" ] || fail "the $name build's $(basename "$so") needs $needed"
  (cd "$dir" && ctest --output-on-failure > "$dir.ctest.log" 2>&1) || fail "the $name build's tests fail:" "$dir.ctest.log"
  cmake --install "$dir" --prefix "$dir.prefix" > "$dir.install.log" 2>&1 ||
    fail "cmake --install of the $name build failed:" "$dir.install.log"
}
base='libc\.so|libm\.so|ld-linux'
build full "$base|libgomp\.so|libfftw3\.so|libpthread\.so"
PKG_CONFIG_LIBDIR=/nonexistent build clean "$base|libgomp\.so"
PKG_CONFIG_LIBDIR=/nonexistent build minimal "$base" -DRESTIR_WITH_OPENMP=OFF -DRESTIR_WITH_FFTW=OFF
for b in clean minimal; do
  ! nm "$work/$b/librestir_core.a" | grep -q fftw || fail "the $b build references FFTW"
done
! nm "$work/minimal/librestir_core.a" | grep -q GOMP_ || fail "the minimal build references OpenMP"

bad=$(nm -g --defined-only "$work/full/librestir_core.a" | awk '$2 ~ /^[TDBR]$/ && $3 !~ /^restir_/ {print $3}' | sort -u)
[ -z "$bad" ] || fail "librestir_core.a defines symbols without the restir_ prefix: $bad"
so=$(ls "$work"/full/librestir.so.* | head -1)
bad=$(nm -D --defined-only "$so" | awk '$2 ~ /^[TDBRVW]$/ && $3 !~ /^restir_/ && $3 !~ /^_(init|fini)$/ {print $3}' | sort -u)
[ -z "$bad" ] || fail "$so exports symbols without the restir_ prefix: $bad"

g++ -std=c++11 -Wall -Wextra -Wpedantic -Werror -I"$src/include" -I"$work/full/generated" "$src/tests/core/all_headers.cpp" \
  -o "$work/all_headers" > "$work/cpp.log" 2>&1 || fail "the public headers do not compile as C++:" "$work/cpp.log"
"$work/all_headers" > /dev/null || fail "tests/core/all_headers.cpp (C++) fails"

# example PREFIX NAME: examples/NAME against the package in PREFIX, through find_package(restir)
# and through pkg-config.
example() {
  local prefix=$1 ex=$2 dir="$work/example_$(basename "$1")_$2" pc flags
  { cmake -S "$src/examples/$ex" -B "$dir" -DCMAKE_PREFIX_PATH="$prefix" && cmake --build "$dir" && "$dir/$ex"; } \
    > "$dir.log" 2>&1 || fail "examples/$ex against $(basename "$prefix") through find_package(restir):" "$dir.log"
  pc=$(dirname "$(find "$prefix" -name restir.pc | head -1)")
  flags=$(PKG_CONFIG_PATH="$pc" pkg-config --cflags --libs restir)
  # shellcheck disable=SC2086
  { cc -std=c11 -O2 "$src/examples/$ex/$ex.c" $flags -o "$dir.pc" && "$dir.pc"; } > "$dir.pc.log" 2>&1 ||
    fail "examples/$ex against $(basename "$prefix") through pkg-config ($flags):" "$dir.pc.log"
}
examples="ris_1d restir_di poisson"
for ex in $examples; do
  example "$work/full.prefix" "$ex"
  example "$work/clean.prefix" "$ex"
done
example "$work/minimal.prefix" poisson

nvcc=$(command -v nvcc || true)
[ -n "$nvcc" ] || [ ! -x /usr/local/cuda/bin/nvcc ] || nvcc=/usr/local/cuda/bin/nvcc
if [ -n "$nvcc" ]; then
  { cmake -S "$src/examples/cuda" -B "$work/cuda" -DCMAKE_PREFIX_PATH="$work/clean.prefix" \
      -DCMAKE_CUDA_COMPILER="$nvcc" &&
    cmake --build "$work/cuda" && "$work/cuda/ris_pairwise"; } > "$work/cuda.log" 2>&1 ||
    fail "examples/cuda ($nvcc):" "$work/cuda.log"
  if grep -q 'GPU vs CPU' "$work/cuda.log"; then
    cuda="examples/cuda compiled with nvcc and run on the GPU"
  else
    cuda="examples/cuda compiled with nvcc and run (its CPU half: no GPU here)"
  fi
else
  cuda="examples/cuda SKIPPED: no nvcc on the PATH or in /usr/local/cuda/bin"
fi
echo "check_core: librestir builds alone (full, clean: no pkg-config package, minimal: no OpenMP or FFTW), passes its"
echo "core tests in each, exports only restir_ symbols, its headers compile as C++, it installs, and"
echo "examples/{${examples// /,}} pass against the installed packages (find_package and pkg-config); $cuda"
