# cutaway: the two commands of the README, and what they need.
#   make demo   installs dependencies, builds (Release), runs the main job on the default scene
#   make test   installs dependencies and test tools, builds, runs every test
BUILD ?= build
JOBS  ?= $(shell nproc)

.PHONY: all deps deps-test build demo test check test-times test-cpus sanitize fuzz bench gallery template-sheet clean

all: build

deps:
	@bash scripts/install-deps.sh

deps-test:
	@bash scripts/install-deps.sh --test

$(BUILD)/build.ninja:
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release

build: deps $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)

# The demo builds only the executable it runs (not the tests and benchmarks).
demo: deps $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS) --target cutaway
	@mkdir -p out
	./$(BUILD)/cutaway scene scenes/salad.yaml -o out/salad.glb -o out/salad.pov --png out/salad.png --render out/salad-povray.png
	@echo "demo: wrote out/salad.glb, out/salad.pov, out/salad.png (OpenGL preview), out/salad-povray.png (POV-Ray)"

# Configured again: a build folder made by `make demo` before GoogleTest was installed has no
# tests yet. TIER: a CTest label expression (-L), empty for every tier.
TIER ?=
CTEST_RUN = cd $(BUILD) && ctest --output-on-failure --no-tests=error -j $(JOBS) \
	  $(if $(TIER),-L $(TIER)) --output-junit Testing/junit.xml
test: deps-test
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD) -j $(JOBS)
	$(CTEST_RUN)
	@python3 scripts/test-times.py $(BUILD)

# The inner loop: the unit tier alone (no scenes, no external programs), after a build.
check:
	$(MAKE) test TIER=unit

# The slowest 20 tests and the time per tier of the last `make test` or `make check`.
test-times:
	python3 scripts/test-times.py $(BUILD)

# Same bytes on an older CPU: a small scene made natively and under qemu-user emulating an
# SSE4.2-only CPU (Nehalem: no AVX, no FMA), compared byte for byte (about 2 minutes; not part
# of `make test`).
test-cpus: build
	@bash scripts/install-deps.sh --cpus
	bash tests/app/cli/emulated_cpu_test.sh ./$(BUILD)/cutaway $(BUILD)/test-tmp/emulated-cpu

gallery: build
	bash scripts/make-gallery.sh

template-sheet: build
	bash scripts/template-sheet.sh

# Every test of cutaway_tests under AddressSanitizer and UBSan (a separate build, build-asan/;
# about 15 minutes of build on 2 cores and a slow run, so not part of `make test`).
sanitize: deps-test
	cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCUTAWAY_SANITIZE=ON
	cmake --build build-asan -j $(JOBS)
	cd build-asan && ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --output-on-failure -j $(JOBS) --timeout 1800

# Longer hunts than `make test` makes (CI may skip this; about 25 minutes on 2 cores): every
# libFuzzer target for FUZZ_SECONDS each, then the random-plane property test with
# RANDOM_PLANES planes per template (and half as many per seeded variant) from another seed,
# the seeded-dice closedness test with DICE_SEEDS seeds per template (templates with grains
# also halved and cut in 4 wedges), and VARIANT_SEEDS seeded variants of every template built.
FUZZ_SECONDS ?= 240
RANDOM_PLANES ?= 300
RANDOM_PLANES_SEED ?= 1
DICE_SEEDS ?= 6
VARIANT_SEEDS ?= 200
fuzz: deps-test $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)
	for kind in build template scene ply cut cache; do \
	  cmake -DKIND=$$kind -DSOURCE_DIR=$(CURDIR) -DBINARY_DIR=$(CURDIR)/$(BUILD)/fuzz \
	    -DCLANGXX=$$(command -v clang++ || command -v clang++-14) -DSECONDS=$(FUZZ_SECONDS) \
	    -DGENERATOR=Ninja -P tests/fuzz/run_fuzz.cmake || exit 1; \
	done
	cd $(BUILD) && CUTAWAY_RANDOM_PLANES=$(RANDOM_PLANES) CUTAWAY_RANDOM_PLANES_SEED=$(RANDOM_PLANES_SEED) \
	  ./cutaway_tests --gtest_filter='Templates/RandomPlanes.*'
	cd $(BUILD) && CUTAWAY_DICE_SEEDS=$(DICE_SEEDS) ./cutaway_tests --gtest_filter='Templates/SeededDice.*'
	cd $(BUILD) && CUTAWAY_VARIANT_SEEDS=$(VARIANT_SEEDS) ./cutaway_tests --gtest_filter='Templates/ShippedVariation.*'

bench: build
	cmake --build $(BUILD) --target benchmarks -j $(JOBS)

clean:
	rm -rf $(BUILD) out
