# Thin wrapper over CMake presets. `make demo` and `make test` are the two
# commands a new user runs on a fresh Debian 12 machine.
JOBS   ?= $(shell nproc)
PRESET ?= release
BUILD  := build/$(PRESET)
BIN    := $(BUILD)/app/sdgbehave
PREFIX ?= /usr/local

.PHONY: deps configure build install test demo bench asan fuzz clean

deps:
	@tools/install-deps.sh

configure: deps
	@cmake --preset $(PRESET) >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# The executable, the plugin headers and the CMake package (docs/plugins.md).
install: build
	@cmake --install $(BUILD) --prefix $(PREFIX)

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

demo: build
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
