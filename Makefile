# cutaway: the two commands of the README, and what they need.
#   make demo   installs dependencies, builds (Release), runs the main job on the default scene
#   make test   installs dependencies and test tools, builds, runs every test
BUILD ?= build
JOBS  ?= $(shell nproc)

.PHONY: all deps deps-test build demo test fuzz bench gallery template-sheet clean

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

bench: build
	cmake --build $(BUILD) --target benchmarks -j $(JOBS)

clean:
	rm -rf $(BUILD) out
