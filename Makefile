# Thin wrapper over CMake presets. `make demo` and `make test` are the two
# commands a new user runs on a fresh Debian 12 machine.
JOBS   ?= $(shell nproc)
PRESET ?= release
BUILD  := build/$(PRESET)
BIN    := $(BUILD)/app/sdgbehave

.PHONY: deps configure build test demo bench asan clean

deps:
	@tools/install-deps.sh

configure: deps
	@cmake --preset $(PRESET) >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

demo: build
	@$(BIN) validate scenes/warehouse.yaml
	@$(BIN) inspect scenes/warehouse.yaml
	@mkdir -p out/demo && $(BIN) inspect scenes/warehouse.yaml > out/demo/inspect.txt
	@echo "demo: scene inspected; tree written to out/demo/inspect.txt"

bench: build
	@tools/bench.sh $(BUILD)

asan:
	@$(MAKE) test PRESET=asan

clean:
	rm -rf build out
