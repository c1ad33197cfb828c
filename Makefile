# phasor — the two commands of the README, plus developer targets.
#   make demo      install what is missing, build Release, render scenes/demo.wscene with grt and ray
#   make test      install what is missing, build, run the test suite (ctest)
JOBS      ?= $(shell nproc)
BUILD     ?= build
CMAKE_ARGS ?=

.PHONY: all deps configure build demo test sanitize bench fuzz docs gallery clean

all: build

deps:
	@scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_ARGS) > /dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# The wave-optical renderer beside the classical one on one scene: out/demo/grid.png, out/demo/index.html.
demo: build
	@mkdir -p out
	$(BUILD)/bin/phasor compare scenes/demo.wscene --integrators grt,ray --reference none -o out/demo

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 900

# Unit tests under AddressSanitizer + UndefinedBehaviorSanitizer (separate build tree; about 35 min
# on 2 cores from scratch). tests/lsan.supp names the leaks of libraries phasor uses.
sanitize: deps
	@cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g" \
	  -DPHASOR_SANITIZE=ON -DPHASOR_BUILD_BENCH=OFF > /dev/null
	@cmake --build build-asan -j $(JOBS)
	@cd build-asan && ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --output-on-failure -j $(JOBS) -L unit --timeout 1800

bench: build
	@bash $(BUILD)/bench/run_benchmarks.sh $(BUILD)

# Regenerates docs/plugins.md from the plug-ins' schemas, and docs/python.md's API reference from the
# Python module's docstrings when the module is built.
docs: build
	@$(BUILD)/bin/phasor describe --markdown > docs/plugins.md
	@if [ -d $(BUILD)/python/phasor ]; then \
	  PYTHONPATH=$(BUILD)/python "$$(sed -n 's/^Python3_EXECUTABLE:FILEPATH=//p' $(BUILD)/CMakeCache.txt)" \
	    -m phasor._apidoc docs/python.md; fi

# Renders the showcase scenes with `phasor compare` (grt, ray, sample_solve) into docs/gallery/ (minutes
# per scene); INTEGRATORS=grt,ray for fewer (scripts/make_gallery.sh).
gallery: build
	@scripts/make_gallery.sh $(BUILD)

clean:
	rm -rf $(BUILD) build-asan out
