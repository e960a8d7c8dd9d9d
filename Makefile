# Tranche: the two commands of the README, and a few more for developers.
#   make slice [MODEL=path/to/model.stl] [OUT=out]   install deps, build, slice (default: the demo model)
#   make test                                          install deps, build, run every test suite and fuzz smoke run
# The build lives in build/ (CMake + Ninja, ccache when available).

BUILD      ?= build
BUILD_TYPE ?= Release
MODEL      ?= examples/models/demo.stl
OUT        ?= out
ARGS       ?=
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
FUZZ_SECONDS ?= 30

NAME := $(basename $(notdir $(MODEL)))

.PHONY: all deps configure build slice test check fuzz fuzz-build bench format clean example preview-screenshot

all: build

deps:
	@scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

slice: build
	@mkdir -p $(OUT)
	@$(BUILD)/apps/tranche slice $(MODEL) -o $(OUT)/$(NAME).gcode --export-svg $(OUT)/$(NAME).svg $(ARGS)
	@echo "G-code: $(OUT)/$(NAME).gcode   layers preview (open in a browser): $(OUT)/$(NAME).svg"

# The whole test suite: unit, language, end-to-end tests, then a bounded fuzz run of every fuzz target.
test: check fuzz

check: build
	@scripts/fetch-models.sh || true
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

fuzz-build: deps
	@cmake -S . -B $(BUILD)-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
	  -DCMAKE_CXX_COMPILER=clang++ -DTRANCHE_FUZZ=ON -DTRANCHE_TESTS=OFF -DTRANCHE_BENCH=OFF \
	  -DTRANCHE_PYTHON=OFF >/dev/null
	@cmake --build $(BUILD)-fuzz -j $(JOBS) --target fuzz_all

fuzz: fuzz-build
	@scripts/run-fuzzers.sh $(BUILD)-fuzz $(FUZZ_SECONDS)

bench: build
	@bench/run.sh $(BUILD)

# docs/images/preview.png, made by the preview's browser test (needs node, npm and Chromium).
preview-screenshot: build
	@bash tests/geometry/preview/browser/run.sh $(BUILD)/preview-browser-test $(BUILD)/tests/preview_fixture \
	  --screenshot docs/images/preview.png

example: build
	@scripts/run-example.sh $(BUILD) $(NAME)

format:
	@find apps compiler geometry grammar runtime tests bench fuzz -name '*.cpp' -o -name '*.h' | \
	  grep -v '/generated/' | xargs clang-format -i

clean:
	rm -rf $(BUILD) $(BUILD)-fuzz
