# A thin wrapper over CMake for the README's commands. Every target installs
# what is missing first (scripts/bootstrap.sh), so a fresh Debian machine
# needs nothing done by hand.
PREFIX ?= /usr/local
BUILD ?= build
ASAN_BUILD ?= build-asan
TSAN_BUILD ?= build-tsan
PYTHON_BUILD ?= build-python
PYTHON_ASAN_BUILD ?= build-python-asan
FUZZ_BUILD ?= build-fuzz
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all deps build demo test test-c test-asan test-tsan test-fuzz test-python test-python-asan \
        test-memcheck install clean bench bench-accuracy fuzz fuzz-long

all: build

deps:
	@scripts/bootstrap.sh

$(BUILD)/build.ninja: | deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo $(CMAKE_FLAGS)

build: deps $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	@mkdir -p out
	$(BUILD)/bin/hitray render scenes/demo.sdl -o out/demo.png --exr out/demo.exr

# Every test: the C suite (ctest, with the numerical hard cases of
# tests/numerics and the fuzz corpora replayed), the same suite under
# AddressSanitizer and UndefinedBehaviorSanitizer and again under
# ThreadSanitizer, the fast tests under valgrind's memcheck, each libFuzzer
# harness for a short bounded time, and the Python tests (the command line,
# and the package installed into .venv).
test: test-c test-asan test-tsan test-memcheck test-fuzz test-python

test-c: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

$(ASAN_BUILD)/build.ninja: | deps
	cmake -S . -B $(ASAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Debug -DHITRAY_SANITIZE=ON $(CMAKE_FLAGS)

test-asan: deps $(ASAN_BUILD)/build.ninja
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	    ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS)

# The tests labelled memcheck (tests/CMakeLists.txt: the fast ones) under
# valgrind's memcheck on the plain build: what the sanitizers do not see
# (conditions on uninitialised memory in optimised code). Any error fails.
MEMCHECK_OPTIONS ?= --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite --track-origins=yes
test-memcheck: build
	ctest --test-dir $(BUILD) -T memcheck -L memcheck -j $(JOBS) --output-on-failure \
	    --overwrite MemoryCheckCommand=$$(command -v valgrind) \
	    --overwrite "MemoryCheckCommandOptions=$(MEMCHECK_OPTIONS)"

$(TSAN_BUILD)/build.ninja: | deps
	cmake -S . -B $(TSAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Debug -DHITRAY_TSAN=ON $(CMAKE_FLAGS)

test-tsan: deps $(TSAN_BUILD)/build.ninja
	cmake --build $(TSAN_BUILD) -j $(JOBS)
	TSAN_OPTIONS=halt_on_error=1 ctest --test-dir $(TSAN_BUILD) --output-on-failure -j $(JOBS)

# The libFuzzer harnesses (tests/fuzz), built with clang and ASan+UBSan in
# $(FUZZ_BUILD). `make fuzz` runs each for FUZZ_SECONDS (FUZZ_TARGETS picks
# some); `make test-fuzz` replays every corpus file, then runs each harness
# from the fixed seed FUZZ_TEST_SEED for FUZZ_TEST_RUNS inputs (at most
# FUZZ_TEST_SECONDS), so CI repeats the same inputs rather than exploring
# anew. See FUZZING.md.
FUZZ_SECONDS ?= 300
FUZZ_TEST_SECONDS ?= 30
FUZZ_TEST_RUNS ?= 50000
FUZZ_TEST_SEED ?= 1
FUZZ_TARGETS ?=
fuzz: deps
	tests/fuzz/run_fuzzers.sh --build $(FUZZ_BUILD) --seconds $(FUZZ_SECONDS) $(FUZZ_TARGETS)

test-fuzz: deps
	tests/fuzz/run_fuzzers.sh --build $(FUZZ_BUILD) --seconds $(FUZZ_TEST_SECONDS) --replay \
	    --runs $(FUZZ_TEST_RUNS) --seed $(FUZZ_TEST_SEED) $(FUZZ_TARGETS)

# Hours of exploring: every harness for FUZZ_LONG_SECONDS (an hour each by
# default, five hours for the five) from a fresh seed, then what each found
# that reaches new coverage merged into its committed corpus
# (tests/fuzz/corpus/<harness>), ready to be reviewed and committed.
FUZZ_LONG_SECONDS ?= 3600
fuzz-long: deps
	tests/fuzz/run_fuzzers.sh --build $(FUZZ_BUILD) --seconds $(FUZZ_LONG_SECONDS) --replay --merge \
	    $(FUZZ_TARGETS)

# The package is (re)installed into .venv as a user installs it, from
# bindings/python; its CMake build directory is kept in $(PYTHON_BUILD), so
# an install with nothing changed compiles nothing.
test-python: build
	.venv/bin/python -m pip install -q --no-build-isolation \
	    -C build-dir=$(abspath $(PYTHON_BUILD)) ./bindings/python
	HITRAY_BUILD_DIR=$(abspath $(BUILD)) .venv/bin/python -m pytest -q -rs tests/python

# The package built with ASan+UBSan (library, modules and extension) into
# $(PYTHON_ASAN_BUILD)/site, its tests run by the venv's interpreter with the
# sanitizer runtimes preloaded (Python itself is not instrumented, so leak
# detection is off; the tests that start a bare interpreter or run mypy are
# left out, and so are the command line's and the viewer's, which test the
# plain build's programs, not the package). Not part of `make test`: it
# builds everything again.
test-python-asan: build
	.venv/bin/python -m pip install -q --no-build-isolation --no-deps --upgrade \
	    --target $(abspath $(PYTHON_ASAN_BUILD))/site -C build-dir=$(abspath $(PYTHON_ASAN_BUILD))/cmake \
	    -C cmake.build-type=Debug -C cmake.define.HITRAY_SANITIZE=ON ./bindings/python
	PYTHONPATH=$(abspath $(PYTHON_ASAN_BUILD))/site \
	    LD_PRELOAD="$$(gcc -print-file-name=libasan.so) $$(gcc -print-file-name=libubsan.so)" \
	    ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	    HITRAY_BUILD_DIR=$(abspath $(BUILD)) .venv/bin/python -m pytest -q -p no:cacheprovider \
	    tests/python --ignore=tests/python/test_cli.py --ignore=tests/python/test_view.py \
	    -k "not stubs and not no_environment"

install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

# hitray against POV-Ray 3.7 and Embree 3, on the bench scenes and the SPD's
# (bench/run_bench.py writes bench/RESULTS.md); never part of `make test`.
# BENCH_FLAGS passes options (--runs, --scenes, --spd-size, --note, ...).
BENCH_FLAGS ?=
bench: build
	@scripts/bootstrap.sh --bench
	cmake -S . -B $(BUILD) -DHITRAY_BUILD_BENCH=ON >/dev/null
	cmake --build $(BUILD) -j $(JOBS)
	python3 bench/run_bench.py --build $(BUILD) $(BENCH_FLAGS)

# What accuracy costs in time (bench/accuracy): measures every accuracy knob
# on this machine and writes docs/accuracy.md with its tables and plots.
bench-accuracy: build
	.venv/bin/python bench/accuracy/run_accuracy.py --build $(BUILD)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(TSAN_BUILD) $(FUZZ_BUILD) $(PYTHON_BUILD) $(PYTHON_ASAN_BUILD) out
