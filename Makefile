# The two commands of the README:
#   make run    set up, build, and show the default scene in a window
#               (or render it to cgfs.ppm when there is no display)
#   make test   set up, build, and run the whole test suite
# `make deps` installs what the build and the tests need from Debian's
# packages; it does nothing when everything is already there.

# Debian packages: the build, then the tests (virtual X server, screenshots;
# js_of_ocaml and node run the core library as JavaScript; a real Slurm
# cluster and sshd for the render-farm recipes, docs/farm.md).
BUILD_PKGS = ocaml ocaml-dune ocaml-findlib libcmdliner-ocaml-dev libparsexp-ocaml-dev \
  libsexplib0-ocaml-dev libppx-deriving-ocaml-dev libgraphics-ocaml-dev libcamlimages-ocaml-dev \
  libx11-dev
TEST_PKGS = libalcotest-ocaml-dev libqcheck-ocaml-dev libzarith-ocaml-dev libcrowbar-ocaml-dev xvfb \
  x11-apps xdotool imagemagick parallel rsync slurmctld slurmd slurm-client munge openssh-server \
  openssh-client js-of-ocaml libjs-of-ocaml-dev nodejs
# The plot of the run time against error benchmark (make bench-quality only).
BENCH_PKGS = gnuplot-nox

SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: run test deps build golden screenshot clean bench bench-quality fuzz

run: deps build
	@if [ -n "$$DISPLAY" ]; then \
	  dune exec --no-print-directory -- raytrace; \
	else \
	  echo "No display: rendering the default scene to cgfs.ppm instead of opening a window."; \
	  dune exec --no-print-directory -- raytrace render -o cgfs.ppm; \
	fi

test: deps
	dune build @install @runtest

deps:
	@missing=$$(for p in $(BUILD_PKGS) $(TEST_PKGS); do \
	  dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "Installing from Debian:" $$missing; \
	  $(SUDO) apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing >/dev/null; \
	fi

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

clean:
	dune clean

# The speed benchmark (bench/speed.ml): prints a table. Release build.
bench: deps
	dune build --profile release bin/main.exe bench/speed.exe
	./_build/default/bench/speed.exe --raytrace ./_build/default/bin/main.exe

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
