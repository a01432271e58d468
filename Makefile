# The two commands of the README, and a few conveniences. Everything goes through CMake presets.
PRESET ?= release
BUILD  := build/$(PRESET)
JOBS   ?= $(shell nproc)

.PHONY: demo test deps configure build bench clean

demo: build
	mkdir -p out
	$(BUILD)/apps/caligo/caligo render default -o out/default.exr

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

deps:
	scripts/install-deps

configure: deps
	cmake --preset $(PRESET)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

bench: build
	$(BUILD)/bench/caligo_bench

clean:
	rm -rf build out
