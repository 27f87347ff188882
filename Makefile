# Facet's two quick-start commands, on a fresh Debian 12 machine as root:
#   make demo   installs what is missing, builds, renders the demo scene, prints the image path
#   make test   installs what is missing, builds, runs every test suite
#   make fuzz   builds the libFuzzer targets and fuzzes each for FUZZ_SECONDS (not in make test)
# Other targets: deps, build (all but bench/'s timing programs), plugin (the ParaView plugin),
#                test-plugin, bench (builds the timing programs: the target `benchmarks`),
#                bench-peers, stability-report, report (error against time of the quality
#                modes), clean.

SHELL := /bin/bash
.SHELLFLAGS := -eu -o pipefail -c

BUILD_DIR ?= build
# Everything (core, adapters, their C++ tests, the fuzz targets) built by clang under
# AddressSanitizer + UndefinedBehaviorSanitizer with assertions on; VTK is not instrumented.
# It is also the build without IceT (tests/parallel check there that MPI ranks render as
# before, each its own piece); the main build composites.
SANITIZE_BUILD_DIR ?= build-sanitize
# Its fuzz targets run their seed corpora only: no coverage instrumentation (a call on every
# comparison: ~37 % of the sanitized core tests' run time). Of Highway's SIMD targets it compiles
# one per vector width: EMU128 (the 128-bit baseline, as SSSE3 and SSE4), AVX2 and AVX3, each
# under AddressSanitizer; the main build checks the rest byte for byte.
SANITIZE_SIMD_TARGETS := AVX2;AVX3
# The core alone, without VTK (it must build and test where VTK is absent), under
# ThreadSanitizer: the thread pool and the parallel phases. The allocation test is left out
# (it replaces operator new, as TSan's runtime does).
TSAN_BUILD_DIR ?= build-tsan
# ThreadSanitizer checks threads, not instruction sets: the baseline and AVX2 only (runtime
# dispatch still chooses between two); the main and sanitized builds cover the other targets.
TSAN_SIMD_TARGETS := AVX2
# make fuzz: the sanitized build with libFuzzer's coverage feedback in everything.
FUZZ_BUILD_DIR ?= build-fuzz
JOBS ?= $(shell nproc)
# ccache keys paths inside the checkout relative to the build folder, so the plugin's build of
# the core (build-plugin/core/...: the same unity sources at the same relative paths, the
# same flags) reuses the main build's objects.
export CCACHE_BASEDIR := $(CURDIR)
# $(call stage-mark,WHAT): when WHAT ended, in seconds after make started (CI's time budget).
MAKE_STARTED := $(shell date +%s)
define stage-mark
@echo "== $(1): $$(( $$(date +%s) - $(MAKE_STARTED) )) s after make started"
endef
CMAKE_FLAGS ?=

# Build tools and the core's libraries; VTK with its Python wrapping tools; Xvfb for the
# tests that compare with VTK's own OpenGL renderer; clang with its sanitizer and libFuzzer
# runtimes for the sanitized builds and the fuzz targets; Embree for the mesh reference
# (reference/); scikit-image and Pillow to cross-check the image metrics; NumPy for the
# stability catalogue (tests/stability/); matplotlib for facet-render --report's plot; Google
# Highway for the core's SIMD set-up (runtime dispatch); ccache, because the ParaView plugin
# compiles the VTK-free core and reference with the main build's exact commands (the CMake
# files use ccache when they find it; a fresh machine's empty cache still saves that second
# compile of make test).
PACKAGES := cmake ninja-build ccache g++ libglm-dev libhwy-dev libgtest-dev libbenchmark-dev libpng-dev \
            libvtk9-dev python3-vtk9 python3-dev xvfb xauth clang libclang-rt-14-dev \
            libembree-dev python3-skimage python3-pil python3-numpy python3-matplotlib
# The ParaView plugin (a separate configure against ParaView's own VTK 9.2). paraview-dev
# without recommends: its recommended python3-paraview conflicts with python3-vtk9, so that
# package is unpacked into the plugin's build tree instead (it holds pvbatch's Python modules
# and the hierarchy files the plugin build needs).
# The parallel tests (tests/parallel): Open MPI's mpirun, mpi4py, and the IceT that ParaView
# ships (libraries in paraview, headers in paraview-dev; without recommends, as below). A
# build finds IceT when it configures; without it, it builds and renders as before.
PARALLEL_PACKAGES := openmpi-bin python3-mpi4py paraview-dev
PLUGIN_BUILD_DIR ?= build-plugin
PLUGIN_PACKAGES := paraview-dev python3-numpy openmpi-bin
PARAVIEW_PYTHON_ROOT := $(PLUGIN_BUILD_DIR)/python3-paraview
# The peers of `make bench-peers` (optional: the build skips a peer whose library is missing).
PEER_PACKAGES := libosmesa6-dev
DEMO_MESH ?= ../shared/data/meshes/stanford-bunny.obj
SUDO := $(if $(filter 0,$(shell id -u)),,sudo)

# Sanitizer reports fail the test that triggers them (the builds also use
# -fno-sanitize-recover); LeakSanitizer runs with ASan.
ASAN_OPTIONS_ALL := detect_stack_use_after_return=1:check_initialization_order=1
SANITIZER_ENV := ASAN_OPTIONS=$(ASAN_OPTIONS_ALL) UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1
# Tests labelled asan-preload run without leak checking, with clang's ASan runtime preloaded:
# Python loads the instrumented module (the runtime must come first; Python's own allocations
# are not ours to check), and VtkAgreement's OpenGL driver unloads itself leaving leaks
# without a stack (nothing to suppress them by). Label every test run by Python so.
ASAN_RUNTIME = $(shell clang -print-file-name=libclang_rt.asan-x86_64.so)
# make fuzz: seconds per target, and the libFuzzer options of every run.
FUZZ_SECONDS ?= 120
FUZZ_TARGETS := facet_fuzz_core facet_fuzz_filter
FUZZ_FLAGS ?= -max_len=4096 -len_control=0 -timeout=60 -rss_limit_mb=4096 -print_final_stats=1

.PHONY: all deps deps-parallel deps-plugin build plugin test test-main test-sanitized test-thread-sanitized \
        test-plugin fuzz fuzz-build demo bench bench-peers stability-report report clean

all: build

# $(call install-missing,PACKAGES): installs those not installed yet, without recommends.
define install-missing
@missing=""; \
	for p in $(1); do \
	  dpkg-query -W -f='$${Status}' "$$p" 2>/dev/null | grep -q 'install ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "Installing:$$missing"; \
	  $(SUDO) apt-get update -q; \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -q --no-install-recommends \
	    -o DPkg::Lock::Timeout=900 $$missing; \
	fi
endef

deps:
	$(call install-missing,$(PACKAGES))

deps-parallel: deps
	$(call install-missing,$(PARALLEL_PACKAGES))

deps-plugin: deps
	$(call install-missing,$(PLUGIN_PACKAGES))

$(BUILD_DIR)/build.ninja:
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)

# Everything but bench/'s timing programs (make bench builds those: the target `benchmarks`).
build: deps $(BUILD_DIR)/build.ninja
	cmake --build $(BUILD_DIR) -j $(JOBS)

test-main: deps-parallel build
	$(call stage-mark,main build)
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)
	$(call stage-mark,main suite)

# $(call configure-sanitized,DIR,FLAGS): the clang build under AddressSanitizer and UBSan.
define configure-sanitized
CC=clang CXX=clang++ cmake -S . -B $(1) -G Ninja \
	  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFACET_SANITIZE=address,undefined -DFACET_FUZZ=ON \
	  -DFACET_BUILD_BENCHMARKS=OFF -DFACET_ENABLE_ICET=OFF $(2)
endef

$(SANITIZE_BUILD_DIR)/build.ninja:
	$(call configure-sanitized,$(SANITIZE_BUILD_DIR),-DFACET_FUZZ_COVERAGE=OFF \
	  '-DFACET_SIMD_TARGETS=$(SANITIZE_SIMD_TARGETS)')

$(FUZZ_BUILD_DIR)/build.ninja:
	$(call configure-sanitized,$(FUZZ_BUILD_DIR),-DFACET_BUILD_TESTS=OFF)

# python3-paraview, the same version as the installed ParaView, unpacked (not installed).
$(PARAVIEW_PYTHON_ROOT)/.unpacked: | deps-plugin
	rm -rf $(PARAVIEW_PYTHON_ROOT) && mkdir -p $(PARAVIEW_PYTHON_ROOT)
	version=$$(dpkg-query -W -f='$${Version}' paraview) && cd $(PARAVIEW_PYTHON_ROOT) && \
	  { apt-get download -q -o APT::Sandbox::User=root python3-paraview=$$version || \
	    { $(SUDO) apt-get update -q && apt-get download -q -o APT::Sandbox::User=root python3-paraview=$$version; }; } && \
	  dpkg-deb -x python3-paraview_*.deb . && rm python3-paraview_*.deb
	touch $@

$(PLUGIN_BUILD_DIR)/build.ninja: | $(PARAVIEW_PYTHON_ROOT)/.unpacked
	cmake -S plugin -B $(PLUGIN_BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release \
	  -DFACET_PARAVIEW_PYTHON_ROOT=$(CURDIR)/$(PARAVIEW_PYTHON_ROOT) $(CMAKE_FLAGS)

plugin: deps-plugin $(PARAVIEW_PYTHON_ROOT)/.unpacked $(PLUGIN_BUILD_DIR)/build.ninja
	cmake --build $(PLUGIN_BUILD_DIR) -j $(JOBS)

test-plugin: plugin
	$(call stage-mark,plugin build)
	cd $(PLUGIN_BUILD_DIR) && ctest --output-on-failure -j $(JOBS)
	$(call stage-mark,plugin suite)


fuzz-build: deps $(FUZZ_BUILD_DIR)/build.ninja
	cmake --build $(FUZZ_BUILD_DIR) -j $(JOBS) --target $(FUZZ_TARGETS)

# Convergence checks of the references and the error estimate: minutes under AddressSanitizer
# (ray casting at up to 128 samples a pixel) for code the other sanitized tests run in small;
# the main build runs them.
SANITIZED_SKIP := ConvergesAsSamplesDouble|ConvergesToTheAnalyticSphere|SsimAgainstSkimage
SANITIZED_SKIP := $(SANITIZED_SKIP)|ErrorEstimate\.BoundsTheMeasuredError|FlatSphereErrorFallsWithTessellation
# The 500k-triangle sphere on every SIMD target (a minute under AddressSanitizer): the same
# code paths run sanitized on small scenes (SmallScenesRenderTheSameBytesOnEveryTarget).
SANITIZED_SKIP := $(SANITIZED_SKIP)|SphereOf500kTrianglesRendersTheSameBytesOnEveryTarget
# The install tree's layout and find_package(Facet) (15-30 s: an install and a CMake project
# built against it): the same files in both builds; the main build checks them.
SANITIZED_SKIP := $(SANITIZED_SKIP)|^InstallTree$$

test-sanitized: deps-parallel $(SANITIZE_BUILD_DIR)/build.ninja
	cmake --build $(SANITIZE_BUILD_DIR) -j $(JOBS)
	$(call stage-mark,sanitized build)
	cd $(SANITIZE_BUILD_DIR) && $(SANITIZER_ENV) \
	  ctest --output-on-failure -j $(JOBS) -LE asan-preload -E '$(SANITIZED_SKIP)'
	cd $(SANITIZE_BUILD_DIR) && $(SANITIZER_ENV) ASAN_OPTIONS=$(ASAN_OPTIONS_ALL):detect_leaks=0 \
	  LD_PRELOAD=$(ASAN_RUNTIME) ctest --output-on-failure -j $(JOBS) -L asan-preload \
	  -E '$(SANITIZED_SKIP)'
	$(call stage-mark,sanitized suites)

test-thread-sanitized: deps
	CC=clang CXX=clang++ cmake -S . -B $(TSAN_BUILD_DIR) -G Ninja \
	  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFACET_CORE_ONLY=ON -DCMAKE_DISABLE_FIND_PACKAGE_VTK=ON \
	  -DFACET_SANITIZE=thread -DFACET_BUILD_BENCHMARKS=OFF '-DFACET_SIMD_TARGETS=$(TSAN_SIMD_TARGETS)'
	cmake --build $(TSAN_BUILD_DIR) -j $(JOBS) --target facet_core_tests facet-core-demo
	$(call stage-mark,thread-sanitized build)
	$(SANITIZER_ENV) tests/support/run_gtest_shards.sh $(JOBS) $(TSAN_BUILD_DIR)/tests/core/facet_core_tests
	$(call stage-mark,thread-sanitized suite)

test: test-main test-sanitized test-thread-sanitized test-plugin
	@echo "All test suites passed."

# Each target fuzzes for FUZZ_SECONDS from its seed corpus (fuzz/corpus/, read only) and what
# earlier runs found ($(FUZZ_BUILD_DIR)/fuzzing/corpus/). A crash, hang or failed check
# leaves its input in $(FUZZ_BUILD_DIR)/fuzzing/crashes/ and fails the target.
fuzz: fuzz-build
	@failed=""; \
	for target in $(FUZZ_TARGETS); do \
	  work=$(FUZZ_BUILD_DIR)/fuzzing; mkdir -p $$work/corpus/$$target $$work/crashes; \
	  echo "== $$target: fuzzing for $(FUZZ_SECONDS) s (log: $$work/$$target.log)"; \
	  if $(SANITIZER_ENV) $(FUZZ_BUILD_DIR)/bin/$$target $(FUZZ_FLAGS) \
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
	cmake --build $(BUILD_DIR) -j $(JOBS) --target benchmarks
	$(BUILD_DIR)/bin/facet_bench

# Facet against VTK (MSAA off and default), raw llvmpipe (OSMesa), an Embree ray caster and
# the memory-bound limit, in one run and one table (bench/peers.py). Configures again so
# that CMake finds the peers' libraries just installed. Under Xvfb as the plugin suite runs it
# (tests/plugin/xvfb_run.sh: a display and an X authority file of its own outside /tmp, and
# Xvfb -noreset: without it VTK's next window, opened milliseconds after the last one closed,
# could connect while the server reset and abort on "bad X server connection").
bench-peers: deps
	$(call install-missing,$(PEER_PACKAGES))
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)
	cmake --build $(BUILD_DIR) -j $(JOBS) --target all benchmarks
	XVFB_SCREEN=1920x1080x24 tests/plugin/xvfb_run.sh \
	  /usr/bin/python3 bench/peers.py --build-dir $(BUILD_DIR)

# The stability catalogue (tests/stability/) through Facet and through VTK's OpenGL pipeline
# (a subprocess per case, under Xvfb), in one run: prints the table and writes it to
# $(STABILITY_REPORT), which the README links.
STABILITY_REPORT ?= docs/stability-report.md
stability-report: build
	version=$$(/usr/bin/python3 -c 'import sys; print("%d.%d" % sys.version_info[:2])') && \
	PYTHONPATH=$(CURDIR)/$(BUILD_DIR)/lib/python$$version/dist-packages \
	  tests/plugin/xvfb_run.sh /usr/bin/python3 tests/stability/report.py \
	  --output $(STABILITY_REPORT)

# Error against run time (facet-render --report) on the built-in set at 1920x1080: the
# Markdown table (also on stdout), the CSV and the plot, which the README embeds.
REPORT_PREFIX ?= docs/quality-report
report: build
	$(BUILD_DIR)/bin/facet-render --report -o $(REPORT_PREFIX) --progress | tee $(REPORT_PREFIX).md

clean:
	rm -rf $(BUILD_DIR) $(SANITIZE_BUILD_DIR) $(TSAN_BUILD_DIR) $(FUZZ_BUILD_DIR) $(PLUGIN_BUILD_DIR)
