# The two commands of the README, and a few conveniences. Everything goes through CMake presets.
PRESET ?= release
BUILD  := build/$(PRESET)
JOBS   ?= $(shell nproc)

.PHONY: demo test deps configure build build-caligo bench clean

# The demo builds only what it runs: the caligo executable and the libraries it links (no tests,
# no benchmarks). `make test` builds everything.
demo: build-caligo
	mkdir -p out
	$(BUILD)/apps/caligo/caligo render default -o out/default.exr

test: build
	scripts/install-deps --tests
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

deps:
	scripts/install-deps

configure: deps
	cmake --preset $(PRESET)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

build-caligo: configure
	cmake --build $(BUILD) -j $(JOBS) --target caligo

bench: configure
	cmake --build $(BUILD) -j $(JOBS) --target caligo_bench
	$(BUILD)/bench/caligo_bench

clean:
	rm -rf build out
