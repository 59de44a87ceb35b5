# A thin wrapper over CMake for the README's commands. Every target installs
# what is missing first (scripts/bootstrap.sh), so a fresh Debian machine
# needs nothing done by hand.
PREFIX ?= /usr/local
BUILD ?= build
ASAN_BUILD ?= build-asan
TSAN_BUILD ?= build-tsan
PYTHON_BUILD ?= build-python
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all deps build demo test test-c test-asan test-tsan test-python install clean

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

# Every test: the C suite (ctest), the same suite under AddressSanitizer and
# UndefinedBehaviorSanitizer and again under ThreadSanitizer, and the Python
# tests (the command line, and the package installed into .venv).
test: test-c test-asan test-tsan test-python

test-c: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

$(ASAN_BUILD)/build.ninja: | deps
	cmake -S . -B $(ASAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Debug -DHITRAY_SANITIZE=ON $(CMAKE_FLAGS)

test-asan: deps $(ASAN_BUILD)/build.ninja
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	    ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS)

$(TSAN_BUILD)/build.ninja: | deps
	cmake -S . -B $(TSAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Debug -DHITRAY_TSAN=ON $(CMAKE_FLAGS)

test-tsan: deps $(TSAN_BUILD)/build.ninja
	cmake --build $(TSAN_BUILD) -j $(JOBS)
	TSAN_OPTIONS=halt_on_error=1 ctest --test-dir $(TSAN_BUILD) --output-on-failure -j $(JOBS)

# The package is (re)installed into .venv as a user installs it, from
# bindings/python; its CMake build directory is kept in $(PYTHON_BUILD), so
# an install with nothing changed compiles nothing.
test-python: build
	.venv/bin/python -m pip install -q --no-build-isolation \
	    -C build-dir=$(abspath $(PYTHON_BUILD)) ./bindings/python
	HITRAY_BUILD_DIR=$(abspath $(BUILD)) .venv/bin/python -m pytest -q -rs tests/python

install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(TSAN_BUILD) $(PYTHON_BUILD) out
