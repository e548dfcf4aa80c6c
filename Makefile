# The front door. `make demo` renders the default scene; `make test` builds and runs every test.
# Both install missing Debian packages first (as root, through apt-get).

BUILD ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
DEB_PACKAGES = build-essential cmake pkg-config libembree-dev libopenexr-dev libpng-dev libcjson-dev libfftw3-dev libassimp-dev libstb-dev libsdl2-dev
# Test only (make test): real assets nobody here wrote and deliberately broken ones, and a
# browser that loads the HTML reports, and python3 for scripts/check_layers.py.
TEST_PACKAGES = assimp-testmodels chromium xvfb xauth parallel slurm-wlm munge python3
# make fuzz: clang, its libFuzzer and OpenMP runtimes.
FUZZ_PACKAGES = clang libclang-rt-14-dev libomp-dev
FUZZ_SECONDS ?= 20
SUDO = $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: all deps test-deps build demo test bench asan sanitize fuzz tsan clean

all: build

# $(call apt_install,PACKAGES): installs those of PACKAGES that are missing.
define apt_install
	@missing=""; for p in $(1); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "installing Debian packages:$$missing"; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; \
	fi
endef

deps:
	$(call apt_install,$(DEB_PACKAGES))

test-deps:
	$(call apt_install,$(TEST_PACKAGES))

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	./scripts/demo.sh $(BUILD)/restir

test: build test-deps
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	./scripts/bench.sh $(BUILD)

asan: deps test-deps
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DRESTIR_SANITIZE=ON
	cmake --build build-asan -j $(JOBS)
	cd build-asan && ctest --output-on-failure -j $(JOBS)

# ASan + UBSan over the unit, statistical, CLI, scene and report tests (what CI runs; `make asan`
# runs every test). The viewer's test is left out: SDL's video drivers leak on their own; and the
# BSDF chi-square test, 43 s under ASan for arithmetic the render tests here shade with (CI's time).
SANITIZE_TESTS = ^(unit|stat|core)\.|cli_errors|scene_export|report|determinism|reference_resume|reference_target|interrupt|plans|params_replay
SANITIZE_SKIP = ^stat\.bsdf_chi2$$
# Only what those tests run is built: the restir binary and their executables (a test named
# GROUP.NAME is built from the target GROUP_test_NAME; script tests have none).
sanitize: deps test-deps
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DRESTIR_SANITIZE=ON
	@targets=$$(cd build-asan && ctest -N -R '$(SANITIZE_TESTS)' -E '$(SANITIZE_SKIP)' | \
	  sed -n 's/^ *Test *#[0-9]*: \([a-z]*\)\.\([a-z0-9_]*\)$$/\1_test_\2/p'); \
	known=$$(cmake --build build-asan --target help | sed -n 's/^\.\.\. //p'); \
	build=restir; for t in $$targets; do echo "$$known" | grep -qx "$$t" && build="$$build $$t"; done; \
	echo "cmake --build build-asan -j $(JOBS) --target $$build"; \
	cmake --build build-asan -j $(JOBS) --target $$build
	cd build-asan && ctest --output-on-failure -j $(JOBS) -R '$(SANITIZE_TESTS)' -E '$(SANITIZE_SKIP)'

# Every libFuzzer harness of fuzz/ (one per reader: fuzz/fuzz_NAME.c) under ASan and UBSan for
# FUZZ_SECONDS each (scripts/fuzz.sh: seeds in fuzz/seeds/NAME, the corpora they grow in
# build-fuzz/corpus). FUZZ_HARNESSES=NAME... runs only those.
fuzz: deps
	$(call apt_install,$(FUZZ_PACKAGES))
	CC=clang cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRESTIR_FUZZ=ON -DRESTIR_WERROR=OFF
	cmake --build build-fuzz -j $(JOBS) --target $(patsubst fuzz/%.c,%,$(wildcard fuzz/fuzz_*.c))
	./scripts/fuzz.sh build-fuzz $(FUZZ_SECONDS) $(FUZZ_HARNESSES)

# ThreadSanitizer with Archer, LLVM's OpenMP race detection (CMake option RESTIR_TSAN): the render
# tests that run at tiny sizes, each on 2 OpenMP threads, then every method and reuse variant
# through the restir command (scripts/tsan.sh). Not in CI: the statistical tests would take hours.
TSAN_TESTS = ^render\.(determinism|kernel_paths|temporal_reject|denoise|env_pt|nonfinite|interrupt|compare_track|gradient_cli|reference_target|reference_resume|params_replay|scene_export)$$
tsan: deps test-deps
	$(call apt_install,$(FUZZ_PACKAGES))
	CC=clang cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRESTIR_TSAN=ON -DRESTIR_WERROR=OFF
	cmake --build build-tsan -j $(JOBS)
	cd build-tsan && ctest --output-on-failure -j $(JOBS) -R '$(TSAN_TESTS)'
	./scripts/tsan.sh build-tsan

clean:
	rm -rf $(BUILD) build-asan build-fuzz build-tsan
