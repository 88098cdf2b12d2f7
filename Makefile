# Lucent: the commands a newcomer needs.
#   make demo   install what is needed, build, run the main job
#   make test   install, build, run every test (then again under ASan + UBSan)
#   make        build build/lucent and the library
#   make install PREFIX=dir   install the command, headers, libraries, pkg-config, CMake and Python packages
#   make setup  install Debian packages and fetch the sample meshes
#   make bench  run the benchmarks in bench/
#   make fuzz   fuzz the parsers (clang's libFuzzer; FUZZ_SECONDS per target; docs/fuzzing.md)
#   make fuzz-smoke  30 s per fuzz target (not part of make test)
BUILD      ?= build
ASAN_BUILD ?= build-asan
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_FLAGS ?=
DEMO_OUT   ?= out/demo
PREFIX     ?= /usr/local

.PHONY: all build install setup test test-fast test-asan demo bench fuzz fuzz-smoke clean distclean

all: build

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo $(CMAKE_FLAGS)

build: $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

setup:
	scripts/setup.sh

test: setup
	$(MAKE) test-fast
	$(MAKE) test-asan

test-fast: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

test-asan:
	cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=Debug -DLUCENT_SANITIZE=ON $(CMAKE_FLAGS)
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ctest --output-on-failure -j $(JOBS) -L unit

# The demo's first screen is the demo: the build talks only when it fails.
demo: setup
	@mkdir -p $(BUILD)
	@echo "Building Lucent (log: $(BUILD)/build.log) ..."
	@$(MAKE) --no-print-directory build > $(BUILD)/build.log 2>&1 || { tail -n 40 $(BUILD)/build.log; exit 1; }
	@scripts/demo.sh $(BUILD)/lucent $(DEMO_OUT)

bench: build
	scripts/bench.sh $(BUILD)/bench

FUZZ_SECONDS ?= 60
fuzz:
	fuzz/build.sh $(FUZZ_SECONDS)

fuzz-smoke:
	fuzz/build.sh 30

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) build-fuzz

distclean: clean
	rm -rf data/meshes out
