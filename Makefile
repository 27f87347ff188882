# Facet's two quick-start commands, on a fresh Debian 12 machine as root:
#   make demo   installs what is missing, builds, renders the demo scene, prints the image path
#   make test   installs what is missing, builds, runs every test suite
#   make fuzz   builds the libFuzzer targets and fuzzes each for FUZZ_SECONDS (not in make test)
# Other targets: deps, build, bench, clean.

SHELL := /bin/bash
.SHELLFLAGS := -eu -o pipefail -c

BUILD_DIR ?= build
# Everything (core, adapters, their C++ tests, the fuzz targets) built by clang under
# AddressSanitizer + UndefinedBehaviorSanitizer with assertions on; VTK is not instrumented.
SANITIZE_BUILD_DIR ?= build-sanitize
# The core alone, without VTK (it must build and test where VTK is absent), under
# ThreadSanitizer: the thread pool and the parallel phases. The allocation test is left out
# (it replaces operator new, as TSan's runtime does).
TSAN_BUILD_DIR ?= build-tsan
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

# Build tools and the core's libraries; VTK with its Python wrapping tools; Xvfb for the
# tests that compare with VTK's own OpenGL renderer; clang with its sanitizer and libFuzzer
# runtimes for the sanitized builds and the fuzz targets.
PACKAGES := cmake ninja-build g++ libglm-dev libgtest-dev libbenchmark-dev libpng-dev \
            libvtk9-dev python3-vtk9 python3-dev xvfb xauth clang libclang-rt-14-dev
DEMO_MESH ?= ../shared/data/meshes/stanford-bunny.obj
SUDO := $(if $(filter 0,$(shell id -u)),,sudo)

# Sanitizer reports fail the test that triggers them (the builds also use
# -fno-sanitize-recover); LeakSanitizer runs with ASan.
ASAN_OPTIONS_ALL := detect_stack_use_after_return=1:check_initialization_order=1
SANITIZER_ENV := ASAN_OPTIONS=$(ASAN_OPTIONS_ALL) UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1
# Tests run without leak checking, with clang's ASan runtime preloaded: Python loads the
# instrumented module (the runtime must come first; Python's own allocations are not ours to
# check), and VtkAgreement's OpenGL driver unloads itself leaving leaks without a stack
# (nothing to suppress them by).
SANITIZED_WITHOUT_LEAK_CHECK := PythonPipeline|InstallTree|VtkAgreement
ASAN_RUNTIME = $(shell clang -print-file-name=libclang_rt.asan-x86_64.so)
# make fuzz: seconds per target, and the libFuzzer options of every run.
FUZZ_SECONDS ?= 120
FUZZ_TARGETS := facet_fuzz_core facet_fuzz_filter
FUZZ_FLAGS ?= -max_len=4096 -len_control=0 -timeout=60 -rss_limit_mb=4096 -print_final_stats=1

.PHONY: all deps build test test-main test-sanitized test-thread-sanitized fuzz fuzz-build \
        demo bench clean

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

$(SANITIZE_BUILD_DIR)/build.ninja:
	CC=clang CXX=clang++ cmake -S . -B $(SANITIZE_BUILD_DIR) -G Ninja \
	  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFACET_SANITIZE=address,undefined -DFACET_FUZZ=ON \
	  -DFACET_BUILD_BENCHMARKS=OFF

fuzz-build: deps $(SANITIZE_BUILD_DIR)/build.ninja
	cmake --build $(SANITIZE_BUILD_DIR) -j $(JOBS) --target $(FUZZ_TARGETS)

test-sanitized: deps $(SANITIZE_BUILD_DIR)/build.ninja
	cmake --build $(SANITIZE_BUILD_DIR) -j $(JOBS)
	cd $(SANITIZE_BUILD_DIR) && $(SANITIZER_ENV) \
	  ctest --output-on-failure -j $(JOBS) -E '$(SANITIZED_WITHOUT_LEAK_CHECK)'
	cd $(SANITIZE_BUILD_DIR) && $(SANITIZER_ENV) ASAN_OPTIONS=$(ASAN_OPTIONS_ALL):detect_leaks=0 \
	  LD_PRELOAD=$(ASAN_RUNTIME) ctest --output-on-failure -j $(JOBS) -R '$(SANITIZED_WITHOUT_LEAK_CHECK)'

test-thread-sanitized: deps
	CC=clang CXX=clang++ cmake -S . -B $(TSAN_BUILD_DIR) -G Ninja \
	  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFACET_CORE_ONLY=ON -DCMAKE_DISABLE_FIND_PACKAGE_VTK=ON \
	  -DFACET_SANITIZE=thread -DFACET_BUILD_BENCHMARKS=OFF
	cmake --build $(TSAN_BUILD_DIR) -j $(JOBS) --target facet_core_tests facet-core-demo
	$(SANITIZER_ENV) $(TSAN_BUILD_DIR)/tests/core/facet_core_tests

test: test-main test-sanitized test-thread-sanitized
	@echo "All test suites passed."

# Each target fuzzes for FUZZ_SECONDS from its seed corpus (fuzz/corpus/, read only) and what
# earlier runs found ($(SANITIZE_BUILD_DIR)/fuzzing/corpus/). A crash, hang or failed check
# leaves its input in $(SANITIZE_BUILD_DIR)/fuzzing/crashes/ and fails the target.
fuzz: fuzz-build
	@failed=""; \
	for target in $(FUZZ_TARGETS); do \
	  work=$(SANITIZE_BUILD_DIR)/fuzzing; mkdir -p $$work/corpus/$$target $$work/crashes; \
	  echo "== $$target: fuzzing for $(FUZZ_SECONDS) s (log: $$work/$$target.log)"; \
	  if $(SANITIZER_ENV) $(SANITIZE_BUILD_DIR)/bin/$$target $(FUZZ_FLAGS) \
	       -max_total_time=$(FUZZ_SECONDS) -artifact_prefix=$$work/crashes/$$target- \
	       $$work/corpus/$$target fuzz/corpus/$$target > $$work/$$target.log 2>&1; then \
	    grep -E '^(Done|stat::number_of_executed_units|stat::peak_rss_mb)' $$work/$$target.log; \
	  else \
	    failed="$$failed $$target"; tail -n 60 $$work/$$target.log; \
	  fi; \
	done; \
	if [ -n "$$failed" ]; then echo "Fuzzing found a problem in:$$failed"; exit 1; fi; \
	echo "Fuzzing found nothing."

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
	rm -rf $(BUILD_DIR) $(SANITIZE_BUILD_DIR) $(TSAN_BUILD_DIR)
