# cutaway: the two commands of the README, and what they need.
#   make demo   installs dependencies, builds (Release), runs the main job on the default scene
#   make test   installs dependencies and test tools, builds, runs every test
BUILD ?= build
JOBS  ?= $(shell nproc)

.PHONY: all deps deps-test build demo test sanitize fuzz bench gallery template-sheet clean

all: build

deps:
	@bash scripts/install-deps.sh

deps-test:
	@bash scripts/install-deps.sh --test

$(BUILD)/build.ninja:
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release

build: deps $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	@mkdir -p out
	./$(BUILD)/cutaway scene scenes/salad.yaml -o out/salad.glb -o out/salad.pov --png out/salad.png --render out/salad-povray.png
	@echo "demo: wrote out/salad.glb, out/salad.pov, out/salad.png (OpenGL preview), out/salad-povray.png (POV-Ray)"

test: deps-test $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

gallery: build
	bash scripts/make-gallery.sh

template-sheet: build
	bash scripts/template-sheet.sh

# The geometry, parsing and export tests under AddressSanitizer and UBSan (a separate build,
# build-asan/; about 15 minutes on 2 cores, so not part of `make test`).
sanitize: deps-test
	cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCUTAWAY_SANITIZE=ON
	cmake --build build-asan --target cutaway_tests -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ./build-asan/cutaway_tests --gtest_filter='Pieces*:CutCells*:ClipMesh*:*PiecesTest*:SceneLayout*:Silhouettes*:CutSpec*:SceneParser*:CrossSection*:*TemplateLibrary*:PovExport*:ColourModulation*:Perlin*'

bench: build
	cmake --build $(BUILD) --target benchmarks -j $(JOBS)

clean:
	rm -rf $(BUILD) out
