# Entry points for a fresh Debian 12 machine. Each target installs missing system packages first
# (scripts/install-deps), then configures and builds with the CMake presets.
JOBS ?= 2
# ccache hits across clones in other folders (CI builds a fresh clone): hash paths relative to the tree.
export CCACHE_BASEDIR ?= $(CURDIR)
export CCACHE_NOHASHDIR ?= 1

# The modules whose quick tests `make sanitize` builds and runs under ASan + UBSan: the readers, the numerical
# kernels and the two simulations; craniofacial, cli and server join when CI sees them change (.ci/run), and
# `make sanitize SANITIZE_MODULES=` runs every module; SANITIZE_EXTRA adds modules to the list.
SANITIZE_MODULES ?= core geometry mesh_io tet_io image volume spatial mesh_processing render report texture wound \
	phantoms fem tetrahedralize desiccation body pbd skin
space := $(subst ,, )

.PHONY: all deps build demo test test-slow sanitize bench format clean

all: build

deps:
	bash scripts/install-deps

build: deps
	cmake --preset release
	cmake --build --preset release -j $(JOBS)

demo: build
	./build/release/bin/forensim demo --out out/demo
	@echo "forensim demo: open out/demo/report.html"
	@echo "forensim demo: browse and edit its runs with  ./build/release/bin/forensim serve out/demo  (http://127.0.0.1:8080/)"

test: build
	ctest --preset release

test-slow: build
	ctest --preset release-slow

sanitize: deps
	cmake --preset sanitize -DFORENSIM_TEST_MODULES="$(subst $(space),;,$(strip $(SANITIZE_MODULES) $(SANITIZE_EXTRA)))"
	cmake --build --preset sanitize -j $(JOBS) --target forensim_tests
	ctest --preset sanitize

bench: build
	@for b in build/release/bin/forensim_bench_*; do echo "== $$b"; $$b --benchmark_min_time=0.2; done

format:
	git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

clean:
	rm -rf build out
