# Facet's two quick-start commands, on a fresh Debian 12 machine as root:
#   make demo   installs what is missing, builds, renders the demo scene, prints the image path
#   make test   installs what is missing, builds, runs every test suite
# Other targets: deps, build, bench, clean.

SHELL := /bin/bash
.SHELLFLAGS := -eu -o pipefail -c

BUILD_DIR ?= build
# The core alone, without VTK (it must build and test where VTK is absent), under
# AddressSanitizer + UndefinedBehaviorSanitizer with assertions on.
CORE_BUILD_DIR ?= build-core-sanitize
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

# Build tools and the core's libraries; VTK with its Python wrapping tools; Xvfb for the
# tests that compare with VTK's own OpenGL renderer; Embree for the mesh reference
# (reference/); scikit-image and Pillow to cross-check the image metrics.
PACKAGES := cmake ninja-build g++ libglm-dev libgtest-dev libbenchmark-dev libpng-dev \
            libvtk9-dev python3-vtk9 python3-dev xvfb xauth libembree-dev \
            python3-skimage python3-pil
DEMO_MESH ?= ../shared/data/meshes/stanford-bunny.obj
SUDO := $(if $(filter 0,$(shell id -u)),,sudo)

.PHONY: all deps build test test-main test-core-sanitized demo bench clean

all: build

deps:
	@missing=""; \
	for p in $(PACKAGES); do \
	  dpkg-query -W -f='$${Status}' "$$p" 2>/dev/null | grep -q 'install ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "Installing:$$missing"; \
	  $(SUDO) apt-get update -q; \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -q --no-install-recommends $$missing; \
	fi

$(BUILD_DIR)/build.ninja:
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)

build: deps $(BUILD_DIR)/build.ninja
	cmake --build $(BUILD_DIR) -j $(JOBS)

test-main: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

test-core-sanitized: deps
	cmake -S . -B $(CORE_BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DFACET_CORE_ONLY=ON -DCMAKE_DISABLE_FIND_PACKAGE_VTK=ON -DFACET_SANITIZE=ON \
	  -DFACET_BUILD_BENCHMARKS=OFF
	cmake --build $(CORE_BUILD_DIR) -j $(JOBS)
	cd $(CORE_BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

test: test-main test-core-sanitized
	@echo "All test suites passed."

demo: build
	mkdir -p out
	$(BUILD_DIR)/bin/facet-render $(DEMO_MESH) -o out/facet-demo.png --size 1280x960 \
	  --azimuth 20 --elevation 10 --color 0.95,0.9,0.85 --ambient 0.12,0.12,0.15 \
	  --light point:-0.3,0.4,0.4@0.9,0.68,0.45 --light directional:1,-0.4,-0.6@0.35,0.5,0.9 \
	  --light headlight@0.25,0.25,0.25
	@echo "Demo image: $(CURDIR)/out/facet-demo.png"

bench: build
	$(BUILD_DIR)/bench/facet_bench

clean:
	rm -rf $(BUILD_DIR) $(CORE_BUILD_DIR)
