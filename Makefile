# Thin wrapper over CMake presets. `make demo` and `make test` are the two
# commands a new user runs on a fresh Debian 12 machine.
JOBS   ?= $(shell nproc)
PRESET ?= release
BUILD  := build/$(PRESET)
BIN    := $(BUILD)/app/sdgbehave
PREFIX ?= /usr/local

.PHONY: deps-run deps configure build install test demo bench asan fuzz clean

# What the tool and its demo need (deps-run), and what the suite, fuzzers
# and benchmarks add (deps).
deps-run:
	@tools/install-deps.sh third_party_notes/debian-packages.txt

deps: deps-run
	@tools/install-deps.sh third_party_notes/debian-packages-test.txt

configure: deps
	@cmake --preset $(PRESET) -DBUILD_TESTING=ON >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# The executable, the plugin headers and the CMake package (docs/plugins.md).
install: build
	@cmake --install $(BUILD) --prefix $(PREFIX)

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# Only the tool (and its image module): no tests, no developer tools.
demo: deps-run
	@cmake --preset release -DBUILD_TESTING=OFF >/dev/null
	@cmake --build build/release -j $(JOBS) --target sdgbehave sdgbehave_images
	@$(BIN) validate scenes/warehouse.yaml
	@$(BIN) run scenes/warehouse.yaml --frames 6 --seed 10 --out out/demo --overwrite
	@echo "demo: dataset written to out/demo"

bench: build
	@tools/bench.sh $(BUILD)

# The suite under AddressSanitizer + UndefinedBehaviorSanitizer; Mesa's own
# allocations are suppressed (tests/lsan.supp). tools/asan-test.sh says why
# a test that failed only by a crash of LeakSanitizer's tracer is rerun once.
asan:
	@$(MAKE) build PRESET=asan
	@JOBS=$(JOBS) tools/asan-test.sh build/asan

# libFuzzer on the scene loader and the --set parser, FUZZ_SECONDS each (60).
fuzz: deps
	@tools/fuzz.sh

clean:
	rm -rf build out
