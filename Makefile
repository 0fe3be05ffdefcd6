# pdesurf: the two commands (make run, make test) and their parts.
BUILD ?= build
JOBS ?= $(shell nproc)

.PHONY: all setup configure build web test run examples bench accuracy format clean

all: build

setup:
	scripts/setup

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

configure: setup $(BUILD)/CMakeCache.txt

build: configure
	cmake --build $(BUILD) -j $(JOBS)
	@$(MAKE) --no-print-directory web

# The studio's web front-end (web/, TypeScript + three.js, built by Vite into web/dist, which
# `pdesurf studio` serves) and the packages of its browser tests (e2e/). `npm ci` runs only
# when node_modules is missing or package-lock.json changed; no browser is downloaded (the
# tests use Debian's chromium).
WEB_SOURCES := $(wildcard web/src/* web/index.html web/vite.config.ts web/tsconfig.json)
NPM_CI = PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error

ifneq ($(shell command -v npm 2>/dev/null),)
web: web/dist/index.html e2e/node_modules/.installed
	@:
else
web:
	@echo "make: npm not found, the studio front-end is not built (run scripts/setup)" >&2
endif

web/node_modules/.installed: web/package-lock.json
	cd web && $(NPM_CI)
	touch $@

e2e/node_modules/.installed: e2e/package-lock.json
	cd e2e && $(NPM_CI)
	touch $@

web/dist/index.html: web/node_modules/.installed $(WEB_SOURCES)
	cd web && npm run --silent build

# Every test: unit, CLI and example suites, and the format check.
test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The main job: the studio on a bundled example (prints its URL; Ctrl+C stops it).
run: build
	scripts/run_studio $(BUILD)/pdesurf

# Every model in examples/ built into meshes under out/, one summary line each.
examples: build
	scripts/run_examples $(BUILD)/pdesurf out

bench: build
	scripts/run_bench $(BUILD)

# The accuracy-versus-storage benchmark: writes docs/accuracy-storage.md and its images.
accuracy: build
	scripts/setup accuracy
	PDESURF_BUILD=$(BUILD) scripts/accuracy --jobs 2

format:
	clang-format -i $$(git ls-files '*.cpp' '*.hpp')

clean:
	rm -rf $(BUILD) $(BUILD)-core-only out web/dist e2e/artifacts
