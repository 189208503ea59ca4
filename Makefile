# The two commands of README.md: `make run` and `make test`. Everything else is a step of them.
BUILD ?= build
BUILD_ASAN ?= build-asan
BUILD_FUZZ ?= build-fuzz
FUZZ_SECONDS ?= 7
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=
OUT ?= out
# The Debian release this machine does not run, for test-other-debian (docs/install.md).
OTHER_DEBIAN ?= $(shell . /etc/os-release 2>/dev/null; [ "$$VERSION_CODENAME" = trixie ] && echo bookworm || echo trixie)

.PHONY: all deps deps-run data configure configure-run build build-cli run test test-release test-asan test-fuzz test-other-debian other-debian-root bench format clean

all: build

# What rendering needs (make run) and what the suite needs on top (make test): tools/install-deps.
deps-run:
	@tools/install-deps run

deps:
	@tools/install-deps test

data: deps
	@tools/fetch-data data

# Configured every time (cheap): a tree first configured by `make run` without GoogleTest gets
# its tests once `make test` has installed it.
configure-run: deps-run
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)

configure: deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON $(CMAKE_FLAGS)

# Only the command-line program: no test targets, no test packages.
build-cli: configure-run
	cmake --build $(BUILD) -j $(JOBS) --target parallax

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# Renders the built-in scene with the built-in display into out/: the two layer images
# (image.png, mask.png, render.json) and an ordinary picture of the scene (view.png).
run: build-cli
	./$(BUILD)/parallax render -o $(OUT)
	./$(BUILD)/parallax view -o $(OUT)/view.png

# The three suites one after the other, each saying how long it took (docs/install.md, "How long
# each make target takes").
test:
	@for suite in test-release test-asan test-fuzz; do \
	  start=$$(date +%s); $(MAKE) --no-print-directory $$suite || exit $$?; \
	  echo "=== make $$suite took $$(( $$(date +%s) - start )) s" >&2; \
	done

test-release: data build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The same suite under AddressSanitizer and UBSan (debug-optimised, no -march=native). Line
# tables only (-g1): the reports keep file and line, and a scene_file.cpp compiles in 17.7 s
# instead of 24.4 s (-g), most of CI's time being this build and its suite.
test-asan: data deps
	cmake -S . -B $(BUILD_ASAN) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
	  -DPARALLAX_SANITIZE=ON -DPARALLAX_NATIVE=OFF $(CMAKE_FLAGS)
	cmake --build $(BUILD_ASAN) -j $(JOBS)
	cd $(BUILD_ASAN) && ASAN_OPTIONS=detect_leaks=1 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tools/lsan-suppressions.txt:print_suppressions=0 \
	  ctest --output-on-failure -j $(JOBS)

# Every fuzz target of fuzz/ for FUZZ_SECONDS seconds (clang, libFuzzer, ASan + UBSan; fuzz/README.md).
test-fuzz: data deps
	BUILD_FUZZ=$(BUILD_FUZZ) JOBS=$(JOBS) tools/fuzz --ci $(FUZZ_SECONDS)

# The other Debian release in a debootstrap root (tools/in-debian; Debian 13 on a Debian 12
# machine): `make run` and the Release suite there, then the built-in layers of both releases'
# builds compared (tests/releases_agree.sh). Its builds go to build-RELEASE, beside ours. The
# isa-sse4.2 copies of the tests run in this machine's suite only (docs/install.md, "Where each
# test runs").
test-other-debian: build
	tools/in-debian $(OTHER_DEBIAN) -- make run test-release \
	  CMAKE_FLAGS="-DPARALLAX_NARROW_ISA_TESTS=OFF $(CMAKE_FLAGS)"
	tests/releases_agree.sh $(OTHER_DEBIAN)

# Only the other release's root and the packages of both README commands in it: downloading and
# unpacking, which CI does while this machine compiles (.ci/run).
other-debian-root:
	tools/in-debian $(OTHER_DEBIAN) -- tools/install-deps test

bench: build
	./$(BUILD)/parallax bench

format:
	clang-format -i $$(git ls-files 'src/*.cpp' 'src/*.h')

clean:
	rm -rf $(BUILD) $(BUILD_ASAN) $(BUILD_FUZZ)
