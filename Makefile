# cutaway: the two commands of the README, and what they need.
#   make demo   installs dependencies, builds (Release), runs the main job on the default template
#   make test   installs dependencies and test tools, builds, runs every test
BUILD ?= build
JOBS  ?= $(shell nproc)

.PHONY: all deps deps-test build demo test fuzz bench clean

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
	./$(BUILD)/cutaway model templates/tomato.yaml -o out/tomato.glb --png out/tomato.png
	./$(BUILD)/cutaway section templates/tomato.yaml --plane y=26 -o out/tomato-section.glb --png out/tomato-section.png
	@echo "demo: wrote out/tomato.glb, out/tomato.png, out/tomato-section.glb, out/tomato-section.png"

test: deps-test $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	cmake --build $(BUILD) --target benchmarks -j $(JOBS)

clean:
	rm -rf $(BUILD) out
