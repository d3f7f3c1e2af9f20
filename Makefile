# The two commands of the README:
#   make run    set up, build, and show the default scene in a window
#               (or render it to cgfs.ppm when there is no display)
#   make test   set up, build, and run the whole test suite
# `make deps-build` installs what the build and the window need from Debian's
# packages, `make deps` that and what the tests need too (a virtual X server,
# Chromium, Slurm, sshd, npm's playwright-core); each does nothing when
# everything is already there. `make run` installs only the first.

# Debian packages: the build, then the tests (virtual X server, screenshots;
# js_of_ocaml and node run the core library as JavaScript, Chromium the web
# page; a real Slurm cluster and sshd for the render-farm recipes, docs/farm.md).
BUILD_PKGS = ocaml ocaml-dune ocaml-findlib libcmdliner-ocaml-dev libparsexp-ocaml-dev \
  libsexplib0-ocaml-dev libppx-deriving-ocaml-dev libgraphics-ocaml-dev libcamlimages-ocaml-dev \
  libx11-dev js-of-ocaml libjs-of-ocaml-dev
TEST_PKGS = libalcotest-ocaml-dev libqcheck-ocaml-dev libzarith-ocaml-dev libcrowbar-ocaml-dev xvfb \
  x11-apps xdotool imagemagick parallel rsync slurmctld slurmd slurm-client munge openssh-server \
  openssh-client chromium libembree-dev
# The plots of the run time against error benchmarks (make bench-quality and bench-soft only).
BENCH_PKGS = gnuplot-nox

SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: run test deps deps-build build golden screenshot web web-screenshot clean bench bench-quality bench-soft bench-embree fuzz

# Only what the program needs (dune build's default would build the tests too,
# and their libraries come with `make deps`).
run: deps-build
	dune build @install
	@if [ -n "$$DISPLAY" ]; then \
	  dune exec --no-print-directory -- raytrace; \
	else \
	  echo "No display: rendering the default scene to cgfs.ppm instead of opening a window."; \
	  dune exec --no-print-directory -- raytrace render -o cgfs.ppm; \
	fi

test: deps
	dune build @install @runtest

# Installs the Debian packages of $(1) that are missing (one apt-get for all).
define apt_missing
	@missing=$$(for p in $(1); do \
	  dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed' || echo $$p; done; \
	  $(2)); \
	if [ -n "$$missing" ]; then \
	  echo "Installing from Debian:" $$missing; \
	  $(SUDO) apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing >/dev/null; \
	fi
endef

deps-build:
	$(call apt_missing,$(BUILD_PKGS),true)

# Node.js drives Chromium in the web page's tests (test/web): Debian's nodejs
# and npm only where there is no node or npm (Debian's npm conflicts with
# other builds of node), then playwright-core, pinned in test/web.
deps:
	$(call apt_missing,$(BUILD_PKGS) $(TEST_PKGS),command -v node >/dev/null || echo nodejs; command -v npm >/dev/null || echo npm)
	@[ -d test/web/node_modules/playwright-core ] || \
	  { echo "Installing playwright-core from npm (test/web)"; cd test/web && npm ci --no-audit --no-fund --loglevel=error; }

build:
	dune build

# Regenerates the golden images of the tests from the current renderer.
# Only after a deliberate change of the pictures: say why in the commit.
golden: build
	dune build test/test.exe
	cd _build/default/test && RAYTRACE_WRITE_GOLDEN=$(CURDIR)/test/golden ./test.exe test golden 0 >/dev/null
	dune exec --no-print-directory -- examples/hello_scene.exe test/golden/hello_scene.ppm

# Regenerates the picture of the window in docs/window.md, taken as the window test
# takes its screenshots (test/window_session.sh, in a virtual X server).
screenshot: build
	@d=$$(mktemp -d) && cp scenes/cgfs.scene $$d/ && \
	xvfb-run -a -s "-screen 0 1024x768x24" test/window_session.sh \
	  $(CURDIR)/_build/default/bin/main.exe $$d/cgfs.scene $$d keys:D,Q,a press:h keys:r shot:window && \
	convert $$d/window.ppm docs/window.png && rm -rf $$d && echo "wrote docs/window.png"

# The ray tracer in a web page (docs/web.md): one HTML file and one
# JavaScript file, opened from the file system.
web: deps-build
	dune build web/index.html web/raytrace.js
	@echo "Open file://$(CURDIR)/_build/default/web/index.html in a browser."

# Regenerates the README's picture of the web page, taken in headless
# Chromium by the web tests' driver (test/web/drive.js).
web-screenshot: web
	@d=$$(mktemp -d) && \
	NODE_PATH=$(CURDIR)/test/web/node_modules node test/web/drive.js _build/default/web/index.html $$d \
	  wait keys:h screenshot:$(CURDIR)/docs/web.png && rm -rf $$d && echo "wrote docs/web.png"

# Run time against error (bench/quality.ml): regenerates docs/quality.csv,
# docs/quality.png, docs/quality.md and docs/quality.gp. Takes minutes; the timings are only
# as quiet as the machine. Built in release mode in its own build directory,
# so that the dev build of `make test` stays as it is. BENCH_NICE= runs it
# at normal priority.
BENCH_NICE = nice -n 19
bench-quality:
	@$(MAKE) --no-print-directory deps TEST_PKGS="$(TEST_PKGS) $(BENCH_PKGS)"
	dune build --profile release --build-dir _build-release bench/quality.exe
	$(BENCH_NICE) _build-release/default/bench/quality.exe --out docs

# Soft shadows and depth of field, run time against error (bench/quality.ml --soft):
# regenerates docs/soft.csv, docs/soft.png, docs/soft.md and docs/soft.gp (a few
# minutes). Release build, as bench-quality.
bench-soft:
	@$(MAKE) --no-print-directory deps TEST_PKGS="$(TEST_PKGS) $(BENCH_PKGS)"
	dune build --profile release --build-dir _build-release bench/quality.exe
	$(BENCH_NICE) _build-release/default/bench/quality.exe --soft --out docs

clean:
	dune clean

# The speed benchmark (bench/speed.ml): prints a table. Release build.
bench: deps
	dune build --profile release bin/main.exe bench/speed.exe
	./_build/default/bench/speed.exe --raytrace ./_build/default/bin/main.exe

# Raytrace against Intel's Embree 3 (issue 28; bench/embree/compare.sh): build time, ns per
# camera ray, hit-mask agreement and peak bytes per triangle, one thread each, on the same
# rays, for a torus knot and a terrain of each size in EMBREE_SIZES (triangles), on an
# EMBREE_WIDTH x EMBREE_HEIGHT canvas, medians of EMBREE_REPEATS runs in alternation. A
# benchmark, not a test (make test only checks the masks of a small mesh,
# test/test_embree.ml). Release build in _build-release; the driver is built with cc
# against Debian's libembree-dev. Minutes with 4000000 in EMBREE_SIZES.
EMBREE_SIZES ?= 100000 1000000
EMBREE_WIDTH ?= 400
EMBREE_HEIGHT ?= 300
EMBREE_REPEATS ?= 3
bench-embree: deps
	dune build --profile release --build-dir _build-release bench/gen.exe bench/embree/raytrace_rays.exe
	cc -O2 -Wall -o _build-release/embree_rays bench/embree/embree_rays.c -lembree3
	$(BENCH_NICE) bench/embree/compare.sh _build-release/default/bench/gen.exe \
	  _build-release/default/bench/embree/raytrace_rays.exe _build-release/embree_rays \
	  _build-release/embree-bench $(EMBREE_WIDTH) $(EMBREE_HEIGHT) $(EMBREE_REPEATS) $(EMBREE_SIZES)

# A coverage-guided fuzzing campaign (AFL++ driving the crowbar target
# fuzz/fuzz_raytrace.ml, built instrumented in _build_fuzz) on the scene
# parser and the PPM reader, for FUZZ_SECONDS, at the lowest priority.
# Findings go to $(FUZZ_OUT)/default/crashes and hangs; a finding becomes a
# regression file in test/corpus/. `make fuzz` resumes an earlier campaign.
FUZZ_SECONDS ?= 1800
FUZZ_OUT ?= _fuzz
fuzz: deps
	@command -v afl-fuzz >/dev/null || DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq afl++
	dune build --profile fuzz --build-dir _build_fuzz ./fuzz/fuzz_raytrace.exe
	AFL_SKIP_CPUFREQ=1 AFL_NO_UI=1 AFL_AUTORESUME=1 AFL_I_DONT_CARE_ABOUT_MISSING_CRASHES=1 \
	  nice -n 19 afl-fuzz -V $(FUZZ_SECONDS) -i fuzz/seeds -o $(FUZZ_OUT) -t 2000 -m none \
	  -- _build_fuzz/default/fuzz/fuzz_raytrace.exe @@
	@grep -E 'run_time|execs_done|execs_per_sec|corpus_count|saved_crashes|saved_hangs' $(FUZZ_OUT)/default/fuzzer_stats
