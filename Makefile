# ode-bpp: the two commands (make demo, make test) and the longer jobs.
# Each target installs what is missing (Debian packages, ODE's source with our patches) first.
SHELL := /bin/bash
BUILD      ?= build
CMAKE_DIR  := $(BUILD)/cmake
ASAN_DIR   := $(BUILD)/asan
JOBS       ?= $(shell nproc)
CMAKE_ARGS ?=
# no "make[N]: Entering directory" lines, here or in the builds cmake runs (MAKEFLAGS is exported)
MAKEFLAGS  += --no-print-directory

.PHONY: all deps ode configure build test test-sanitize demo bench bench-report convergence stability fuzz ode-demos install clean distclean

all: build

deps:
	@bash scripts/install-deps.sh

ode: deps
	@bash scripts/build-ode.sh $(BUILD) patches

# CMake's own lines go to a log; shown only when configuring fails
$(CMAKE_DIR)/CMakeCache.txt: | ode
	@echo "[configure] cmake (Release); log: $(BUILD)/configure.log"
	@cmake -S . -B $(CMAKE_DIR) -DCMAKE_BUILD_TYPE=Release -DODE_ROOT=$(abspath $(BUILD))/ode-install $(CMAKE_ARGS) \
	  >$(BUILD)/configure.log 2>&1 || { cat $(BUILD)/configure.log; rm -f $(CMAKE_DIR)/CMakeCache.txt; exit 1; }

configure: ode $(CMAKE_DIR)/CMakeCache.txt

# Compiler messages in full, otherwise a progress line per 10 % (scripts/quiet-build.awk); the
# whole output in $(BUILD)/build.log
build: configure
	@echo "[build] compiling ode-bpp with $(JOBS) jobs; log: $(BUILD)/build.log"
	@set -o pipefail; cmake --build $(CMAKE_DIR) -j$(JOBS) 2>&1 | tee $(BUILD)/build.log | awk -f scripts/quiet-build.awk

# The whole suite through ctest; non-zero exit on any failure.
test: build
	@echo "[test] running the test suite (ctest); logs in $(CMAKE_DIR)/Testing"
	@cd $(CMAKE_DIR) && ctest --output-on-failure -j$(JOBS) --timeout 1200

# The unit tests again under AddressSanitizer + UndefinedBehaviorSanitizer.
test-sanitize: ode
	@cmake -S . -B $(ASAN_DIR) -DCMAKE_BUILD_TYPE=Debug -DODE_BPP_SANITIZE=ON \
	  -DODE_BPP_BUILD_BENCH=OFF -DODE_BPP_BUILD_DEMOS=OFF -DODE_ROOT=$(abspath $(BUILD))/ode-install >/dev/null
	@echo "[test-sanitize] compiling the unit tests with ASan+UBSan"
	@cmake --build $(ASAN_DIR) -j$(JOBS)
	@cd $(ASAN_DIR) && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --output-on-failure -j$(JOBS) -L "unit|integration" --timeout 1200

# libFuzzer on the file reader and the solver entry point, for a bounded time per target.
FUZZ_DIR     := $(BUILD)/fuzz
FUZZ_SECONDS ?= 60
fuzz: ode
	@cmake -S . -B $(FUZZ_DIR) -DCMAKE_BUILD_TYPE=Debug -DODE_BPP_FUZZ=ON -DCMAKE_C_COMPILER=clang \
	  -DCMAKE_CXX_COMPILER=clang++ -DODE_BPP_BUILD_DEMOS=OFF -DODE_BPP_BUILD_BENCH=OFF \
	  -DODE_ROOT=$(abspath $(BUILD))/ode-install >/dev/null
	@echo "[fuzz] compiling the fuzz targets with clang (libFuzzer, ASan, UBSan)"
	@cmake --build $(FUZZ_DIR) -j$(JOBS) --target fuzz_read_mlcp fuzz_solve
	@echo "[fuzz] $(FUZZ_SECONDS) s per target; crashes are kept in tests/data/fuzz-regressions/"
	@bash tests/fuzz/run-fuzz.sh $(FUZZ_DIR) $(FUZZ_SECONDS)

# The headline comparison: the scenes stepped with ODE's Dantzig and with ode-bpp.
demo: build
	@mkdir -p results
	@echo "[demo] the paper's six scenes, 20 s each, stepped with ODE's dantzig and with bpp side by side (under a minute)"
	@echo "[demo] per island and step: rows, tight fraction, solve time, pivots, residual -> results/demo.csv"
	@echo "[demo] the table and its legend -> results/demo.txt"
	@set -o pipefail; $(CMAKE_DIR)/demos/ode-bpp-demo paper --compare dantzig,bpp --csv results/demo.csv | tee results/demo.txt

.PHONY: bench-kernels deps-peers

# The peer solvers of `make bench` (DART, Bullet, Siconos numerics), from Debian.
PEER_PACKAGES := libdart-dev libbullet-dev libsiconos-numerics-dev
deps-peers: deps
	@bash scripts/install-deps.sh $(PEER_PACKAGES)

# Speed against accuracy, side by side with ODE's Dantzig and the peers, on one captured corpus:
# corpus -> every method and peer in one process -> CSV, charts (PNG, SVG), report.md in
# results/bench/ (docs/benchmarks.md). About 23 minutes; BENCH_ARGS=--quick for about 3,
# BENCH_ARGS=--no-peers without the peers. The peers' packages are installed first (as deps-peers);
# without them (not root, no network) the report says so and compares ode-bpp's methods alone.
BENCH_REPORT_ARGS ?=
BENCH_ARGS ?= $(BENCH_REPORT_ARGS)
bench: build
	@bash scripts/install-deps.sh $(PEER_PACKAGES) || \
	  echo "[bench] warning: the peers' packages could not be installed; the report runs without them"
	@echo "[bench] reconfiguring so that bench/peers finds the peer packages"
	@cmake -S . -B $(CMAKE_DIR) >/dev/null
	@cmake --build $(CMAKE_DIR) -j$(JOBS) --target bench_corpus bench_fig4 bench_fig5 ode-bpp-demo bench_world_step \
	  chain_conditioning
	@bash scripts/bench-report.sh $(CMAKE_DIR) results/bench $(BENCH_ARGS)

# The former name of `make bench`.
bench-report: bench

# Google Benchmark: the kernels (factor, delete one row, solve) and the paper's Fig. 4; CSV in results/.
bench-kernels: build
	@mkdir -p results
	@echo "[bench-kernels] kernels: factorization, row deletion, solve, skyline vs dense (about 2 minutes)"
	@$(CMAKE_DIR)/bench/bench_kernels --benchmark_out=results/bench_kernels.csv --benchmark_out_format=csv
	@echo "[bench-kernels] Fig. 4: speed-up of deletion over refactoring by % tight (about 1 minute)"
	@$(CMAKE_DIR)/bench/bench_fig4 --benchmark_out=results/bench_fig4.csv --benchmark_out_format=csv

# Convergence of bpp inside ODE per scene and CFM regime (frozen and consistent friction) -> results/convergence/
convergence: build
	@bash scripts/convergence.sh $(CMAKE_DIR) results/convergence

# Where each method stops working: mass ratio, compliance, time step, loops, chain length
# (dantzig, every bpp variant, pgs, quickstep) -> results/stability/ (CSV, charts, report.md).
# STABILITY_ARGS=--quick for a few seconds; the full grid takes about 3 minutes.
STABILITY_ARGS ?=
stability: build
	@bash scripts/stability.sh $(CMAKE_DIR) results/stability $(STABILITY_ARGS)

# Soak: each paper scene and each pile for 100,000 steps with bpp; bodies finite, no new fallbacks
# after step 10,000, the live heap's floor flat within 1 % beyond its two largest rises and RSS
# within 5 % (README, "Soak") -> results/soak/ (CSV, report.md). Long: the piles alone take hours. SOAK_ARGS="--steps 20000 --scenes 'winch forklift'" for a shorter run.
.PHONY: soak
SOAK_ARGS ?=
soak: build
	@bash scripts/soak.sh $(CMAKE_DIR) results/soak $(SOAK_ARGS)

# ODE's own demos (ode/demo), unchanged, headless under Xvfb, dantzig vs bpp; results/ode-demos/
ode-demos: build
	@bash scripts/ode-demos.sh $(BUILD) results/ode-demos

install: build
	cmake --install $(CMAKE_DIR) --prefix $(or $(PREFIX),/usr/local/ode-bpp)

clean:
	rm -rf $(CMAKE_DIR) $(ASAN_DIR)

distclean:
	rm -rf $(BUILD)
