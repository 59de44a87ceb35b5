# A thin wrapper over CMake for the README's commands. Every target installs
# what is missing first (scripts/bootstrap.sh: the build's Debian packages,
# and for the tests and the wheel their tools too), so a fresh Debian machine
# needs nothing done by hand.
#
# Quiet by default: builds show only warnings and errors, the tests their
# failures in full, their skips with the reason, and the summaries. V=1 shows
# everything (every compile, every test).
PREFIX ?= /usr/local
BUILD ?= build
ASAN_BUILD ?= build-asan
TSAN_BUILD ?= build-tsan
PYTHON_BUILD ?= build-python
PYTHON_ASAN_BUILD ?= build-python-asan
FUZZ_BUILD ?= build-fuzz
DIST ?= dist
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=
V ?= 0

# $(call quietly,LOG,COMMAND): COMMAND's output into LOG, shown only if it
# fails; $(call stdout_to,LOG): a command's standard output into LOG (CMake's
# warnings and errors, on standard error, still shown). Under V=1 output is
# shown as it comes.
ifeq ($(V),0)
quietly = mkdir -p $(dir $(1)) && { $(2); } >$(1) 2>&1 || { cat $(1); echo "(log: $(1))"; exit 1; }
stdout_to = >$(1)
NINJA_QUIET := -- --quiet
CTEST := scripts/ctest_quiet.py --
else
quietly = $(2)
stdout_to =
NINJA_QUIET :=
CTEST := scripts/ctest_quiet.py --verbose --
endif

# $(call configure,DIR,PRESET): a build tree in DIR, configured by PRESET of
# CMakePresets.json (plain, asan, tsan, fuzz: the four configurations) and
# $(CMAKE_FLAGS).
configure = mkdir -p $(1) && cmake --preset $(2) -B $(1) $(CMAKE_FLAGS) $(call stdout_to,$(1)/configure.log)

.PHONY: all deps deps-test deps-wheel build build-all demo test test-c test-asan test-tsan test-fuzz \
        test-python test-python-asan test-docs docs python-install test-memcheck test-wheel wheel install \
        clean bench bench-accuracy \
        fuzz fuzz-long

all: build

deps:
	@scripts/bootstrap.sh

deps-test:
	@scripts/bootstrap.sh --test

deps-wheel:
	@scripts/bootstrap.sh --wheel

# One build tree for the command and the tests, configured with the tests
# and the benchmark programs (some Python tests run those): `make build`
# builds only the target hitray_runtime (the library, the shape modules, the
# command and its man page), build-all the rest.
$(BUILD)/build.ninja: | deps
	$(call configure,$(BUILD),plain)

build: deps $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS) --target hitray_runtime $(NINJA_QUIET)

build-all: deps-test build
	cmake --build $(BUILD) -j $(JOBS) $(NINJA_QUIET)

# The README's picture, with its size and samples per pixel
# (tests/python/test_demo_picture.py checks that the two agree).
demo: build
	@mkdir -p out
	$(BUILD)/bin/hitray render scenes/demo.sdl -o out/demo.png --exr out/demo.exr --size 960x720 --spp 4

# Every test: the C suite (ctest, with the numerical hard cases of
# tests/numerics and the fuzz corpora replayed), the same suite under
# AddressSanitizer and UndefinedBehaviorSanitizer, the tests that start
# threads under ThreadSanitizer, the fast tests under valgrind's memcheck,
# each libFuzzer harness for a short bounded time, and the Python tests (the
# command line, and the package installed into .venv), then the manylinux
# wheel built and tried in a fresh venv.
#
# Where each C test runs (its ctest labels, tests/CMakeLists.txt):
#   every test            test-c (plain) and test-asan (ASan+UBSan)
#   label threads         test-tsan too: ThreadSanitizer finds nothing in a
#                         test that starts no thread
#   label memcheck        test-memcheck too (valgrind, the optimised build)
#   label fuzz-replay     (the corpora, fuzz_replay_*) test-c and test-asan;
#                         four of them in test-memcheck, fuzz_replay_scene
#                         (a render on two threads) in test-tsan; test-fuzz
#                         starts each harness from its corpus (libFuzzer
#                         runs every seed before it mutates), under clang's
#                         ASan+UBSan
#   label install         test-c and test-asan
test: test-c test-asan test-tsan test-memcheck test-fuzz test-python test-docs test-wheel

test-c: build-all
	$(CTEST) --preset plain --test-dir $(BUILD) -j $(JOBS)

$(ASAN_BUILD)/build.ninja: | deps-test
	$(call configure,$(ASAN_BUILD),asan)

# The sanitizers' options are the test presets' (CMakePresets.json).
test-asan: deps-test $(ASAN_BUILD)/build.ninja
	cmake --build $(ASAN_BUILD) -j $(JOBS) $(NINJA_QUIET)
	$(CTEST) --preset asan --test-dir $(ASAN_BUILD) -j $(JOBS)

# The tests labelled memcheck (tests/CMakeLists.txt: the fast ones) under
# valgrind's memcheck on the plain build: what the sanitizers do not see
# (conditions on uninitialised memory in optimised code). Any error fails.
MEMCHECK_OPTIONS ?= --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite --track-origins=yes
test-memcheck: build-all
	$(CTEST) --test-dir $(BUILD) -T memcheck -L memcheck -j $(JOBS) \
	    --overwrite MemoryCheckCommand=$$(command -v valgrind) \
	    --overwrite "MemoryCheckCommandOptions=$(MEMCHECK_OPTIONS)"

$(TSAN_BUILD)/build.ninja: | deps-test
	$(call configure,$(TSAN_BUILD),tsan)

# The tests labelled threads alone (the preset's filter).
test-tsan: deps-test $(TSAN_BUILD)/build.ninja
	cmake --build $(TSAN_BUILD) -j $(JOBS) $(NINJA_QUIET)
	$(CTEST) --preset tsan --test-dir $(TSAN_BUILD) -j $(JOBS)

# The libFuzzer harnesses (tests/fuzz), built with clang and ASan+UBSan in
# $(FUZZ_BUILD) (the fuzz preset). `make fuzz` runs each for FUZZ_SECONDS
# (FUZZ_TARGETS picks some); `make test-fuzz` runs each harness from its
# committed corpus (every corpus file first, as libFuzzer starts) with the
# fixed seed FUZZ_TEST_SEED for FUZZ_TEST_RUNS inputs (at most
# FUZZ_TEST_SECONDS), so CI repeats the same inputs rather than exploring
# anew; the corpus is not replayed apart first, test-asan has replayed it
# under ASan+UBSan already. See FUZZING.md.
FUZZ_SECONDS ?= 300
FUZZ_TEST_SECONDS ?= 30
FUZZ_TEST_RUNS ?= 50000
FUZZ_TEST_SEED ?= 1
FUZZ_TARGETS ?=
fuzz: deps-test
	tests/fuzz/run_fuzzers.sh --build $(FUZZ_BUILD) --seconds $(FUZZ_SECONDS) $(FUZZ_TARGETS)

test-fuzz: deps-test
	tests/fuzz/run_fuzzers.sh $(if $(filter 0,$(V)),--quiet) --build $(FUZZ_BUILD) --seconds $(FUZZ_TEST_SECONDS) \
	    --runs $(FUZZ_TEST_RUNS) --seed $(FUZZ_TEST_SEED) $(FUZZ_TARGETS)

# Hours of exploring: every harness for FUZZ_LONG_SECONDS (an hour each by
# default, five hours for the five) from a fresh seed, then what each found
# that reaches new coverage merged into its committed corpus
# (tests/fuzz/corpus/<harness>), ready to be reviewed and committed.
FUZZ_LONG_SECONDS ?= 3600
fuzz-long: deps-test
	tests/fuzz/run_fuzzers.sh --build $(FUZZ_BUILD) --seconds $(FUZZ_LONG_SECONDS) --replay --merge \
	    $(FUZZ_TARGETS)

# The package is (re)installed into .venv as a user installs it, from the
# repository's root (pyproject.toml); its CMake build directory is kept in
# $(PYTHON_BUILD), so an install with nothing changed compiles nothing. The
# tests run on every core (pytest-xdist): each is independent of the others.
python-install: build-all
	.venv/bin/python -m pip install -q --no-build-isolation \
	    -C build-dir=$(abspath $(PYTHON_BUILD)) .

test-python: python-install
	HITRAY_BUILD_DIR=$(abspath $(BUILD)) .venv/bin/python -m pytest -q -rs -n $(JOBS) tests/python tests/cli tests/view tests/bench

# Every fenced block of README.md and docs/*.md run as its page says, or
# marked not run with the reason, and docs/effects.md's tables rerun
# (tests/docs/test_docs.py says how each kind of block is run); every
# picture rendered again by its caption's command and compared
# (tests/docs/test_pictures.py).
test-docs: python-install
	HITRAY_BUILD_DIR=$(abspath $(BUILD)) .venv/bin/python -m pytest -q -rs -rx -n $(JOBS) -p no:cacheprovider tests/docs

# The package built with ASan+UBSan (library, modules and extension) into
# $(PYTHON_ASAN_BUILD)/site, its tests run by the venv's interpreter with the
# sanitizer runtimes preloaded (Python itself is not instrumented, so leak
# detection is off; the tests that start a bare interpreter or run mypy are
# left out, and so are the command line's and the viewer's, tests/cli and
# tests/view, which test the plain build's programs, not the package). Not
# part of `make test`: it builds everything again.
test-python-asan: build-all
	.venv/bin/python -m pip install -q --no-build-isolation --no-deps --upgrade \
	    --target $(abspath $(PYTHON_ASAN_BUILD))/site -C build-dir=$(abspath $(PYTHON_ASAN_BUILD))/cmake \
	    -C cmake.build-type=Debug -C cmake.define.HITRAY_SANITIZE=ON .
	PYTHONPATH=$(abspath $(PYTHON_ASAN_BUILD))/site \
	    LD_PRELOAD="$$(gcc -print-file-name=libasan.so) $$(gcc -print-file-name=libubsan.so)" \
	    ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	    HITRAY_BUILD_DIR=$(abspath $(BUILD)) .venv/bin/python -m pytest -q -p no:cacheprovider \
	    tests/python \
	    -k "not stubs and not no_environment"

# Every picture of README.md and docs/ remade by the command its caption
# names (scripts/docs_pictures.py reads them from the captions), and
# docs/effects.md's tables by bench/savings.sh; `make test-docs` checks that
# both are what those commands make now.
docs: python-install
	HITRAY_BUILD_DIR=$(abspath $(BUILD)) .venv/bin/python scripts/docs_pictures.py --write
	HITRAY=$(abspath $(BUILD))/bin/hitray bench/savings.sh --write docs/effects.md

install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

# The sdist, a wheel built from it (so the sdist is known to be complete),
# and that wheel made a manylinux one by auditwheel (libpng, OpenEXRCore and
# libstb copied into hitray.libs/, RPATHs rewritten with patchelf; zlib is
# the system's, which the manylinux policy allows):
# $(DIST)/hitray-*.tar.gz and $(DIST)/wheelhouse/hitray-*manylinux*.whl.
# The files are the working tree's (.gitignore leaves out the build trees).
wheel: deps-wheel
	rm -rf $(DIST)
	@$(call quietly,$(DIST)/build.log,.venv/bin/python -m build --no-isolation --outdir $(DIST) .)
	@$(call quietly,$(DIST)/repair.log,PATH=$(abspath .venv/bin):$$PATH \
	    .venv/bin/auditwheel repair -w $(DIST)/wheelhouse $(DIST)/*.whl)
	.venv/bin/auditwheel show $(DIST)/wheelhouse/*.whl
	@ls $(DIST)/*.tar.gz $(DIST)/wheelhouse/*.whl

# The manylinux wheel installed into a fresh venv and used there with no
# library search path (tests/wheel/test_wheel.py).
test-wheel: wheel deps-test
	.venv/bin/python -m pytest -q -rs -p no:cacheprovider tests/wheel \
	    --wheel $(abspath $(wildcard $(DIST)/wheelhouse/*.whl))

# hitray against POV-Ray 3.7 and Embree 3, on the bench scenes and the SPD's
# (bench/drivers/run_bench.py writes bench/results/RESULTS.md); never part of `make test`.
# BENCH_FLAGS passes options (--runs, --scenes, --spd-size, --note, ...).
BENCH_FLAGS ?=
# sdl2pov.py reads the scenes through the hitray package, so it runs in .venv.
bench: python-install
	@scripts/bootstrap.sh --bench
	cmake -S . -B $(BUILD) -DHITRAY_BUILD_BENCH=ON >/dev/null
	cmake --build $(BUILD) -j $(JOBS) $(NINJA_QUIET)
	.venv/bin/python bench/drivers/run_bench.py --build $(BUILD) $(BENCH_FLAGS)

# What accuracy costs in time (bench/programs/accuracy, driven by
# bench/drivers/run_accuracy.py): measures every accuracy knob
# on this machine and writes docs/accuracy.md with its tables and plots.
bench-accuracy: build-all
	.venv/bin/python bench/drivers/run_accuracy.py --build $(BUILD)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(TSAN_BUILD) $(FUZZ_BUILD) $(PYTHON_BUILD) $(PYTHON_ASAN_BUILD) $(DIST) out
