# footprint: top-level driver. Every target first installs missing Debian packages (quietly).
#   make        Release build with debug info into build/ (build/footprint, build/footprint-bench)
#   make demo   ... then runs the demo on the built-in image (writes out/)
#   make test   ... then runs the unit tests, in Release and under ASan+UBSan (build-asan/)
#   make test-tsan ... the threaded tests under ThreadSanitizer (build-tsan/; CI runs it too)
#   make soak   ... then renders SOAK_SCENES (10000) random scenes in every mode (tests/soak/)
#   make python ... the Python module into build/python/ (PYTHONPATH=build/python python3)
#   make bench  ... then runs the texture and environment benchmarks (bench-out/texture.json, env.json)
#   make instructions  ... then counts instructions per environment lookup under callgrind
#   make format clang-formats the sources
#   make fuzz   ... the libFuzzer targets (clang) into build-fuzz/, each run FUZZ_SECONDS (default 60)
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=
# ccache, where installed, makes rebuilds in fresh clones and other build folders cheap.
CCACHE := $(shell command -v ccache 2>/dev/null)
ifneq ($(CCACHE),)
    CMAKE_FLAGS += -DCMAKE_CXX_COMPILER_LAUNCHER=$(CCACHE)
endif

.PHONY: all deps build build-asan build-tsan demo test test-release test-asan test-tsan soak bench instructions format clean python fuzz

all: build

deps:
	@scripts/install-deps.sh

build: deps
	@cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS) >/dev/null
	@cmake --build build -j $(JOBS)

build-asan: deps
	@cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DFOOTPRINT_SANITIZE=ON \
	    -DFOOTPRINT_TESTS_ONLY=ON $(CMAKE_FLAGS) >/dev/null
	@cmake --build build-asan -j $(JOBS) --target footprint-tests fuzz-replay

build-tsan: deps
	@cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DFOOTPRINT_TSAN=ON \
	    -DFOOTPRINT_TESTS_ONLY=ON $(CMAKE_FLAGS) >/dev/null
	@cmake --build build-tsan -j $(JOBS) --target footprint-tsan-tests

python: build

demo: build
	./build/footprint demo --out out

test-release: build
	cd build && ctest --output-on-failure -j $(JOBS)

# new_delete_type_mismatch=0: OpenImageIO 2.4.7's TextureSystem::destroy() deletes its
# implementation through the base class inside libOpenImageIO (the OpenImageIO adapter's tests
# create and destroy OpenImageIO texture systems); ASan reports that as a type mismatch.
test-asan: build-asan
	cd build-asan && ASAN_OPTIONS=detect_leaks=1:new_delete_type_mismatch=0 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
	    ctest --output-on-failure -j $(JOBS)

test: test-release test-asan

# history_size=7: ThreadSanitizer keeps the stacks of older accesses, so that a hand-over inside
# oneTBB (tests/tsan.supp) is matched by its suppression rather than reported with the other
# access's stack lost ("failed to restore the stack").
test-tsan: build-tsan
	cd build-tsan && TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 history_size=7 suppressions=$(CURDIR)/tests/tsan.supp" \
	    ctest --output-on-failure -j $(JOBS)

SOAK_SCENES ?= 10000
soak: build
	./build/tests/footprint-soak $(SOAK_SCENES)

bench: build
	./build/footprint-bench texture --json bench-out/texture.json
	./build/footprint-bench env --json bench-out/env.json

instructions: build
	bash bench/env-instructions.sh build

# Fuzzing (docs/testing.md#fuzzing): the fuzz targets built with clang, libFuzzer and the
# sanitizers, each run FUZZ_SECONDS over its seed corpus (fuzz/corpus/), FUZZ_JOBS at a time.
# Fails if any target crashes; its crash files stay in build-fuzz/fuzz-out/<target>/.
FUZZ_SECONDS ?= 60
FUZZ_JOBS ?= 1
FUZZ_TARGETS ?= scene_json image_load env_layouts mesh texture_file lookup
fuzz: deps
	@cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_COMPILER=clang++-14 \
	    -DFOOTPRINT_FUZZ=ON -DFOOTPRINT_TESTS_ONLY=ON $(CMAKE_FLAGS) >/dev/null
	@cmake --build build-fuzz -j $(JOBS) --target fuzz-targets
	@FUZZ_SECONDS=$(FUZZ_SECONDS) FUZZ_JOBS=$(FUZZ_JOBS) fuzz/run.sh build-fuzz $(FUZZ_TARGETS)

format:
	clang-format -i $$(git ls-files '*.h' '*.cpp')

clean:
	rm -rf build build-asan build-tsan build-fuzz
