# pdesurf: the two commands (make run, make test) and their parts.
BUILD ?= build
JOBS ?= $(shell nproc)

.PHONY: all setup configure build test run bench format clean

all: build

setup:
	scripts/setup

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

configure: setup $(BUILD)/CMakeCache.txt

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# Every test: unit, CLI and example suites, and the format check.
test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The main job: build every model in examples/ into meshes under out/.
run: build
	scripts/run_examples $(BUILD)/pdesurf out

bench: build
	scripts/run_bench $(BUILD)

format:
	clang-format -i $$(git ls-files '*.cpp' '*.hpp')

clean:
	rm -rf $(BUILD) out
