# Entry points: `make demo` and `make test` set everything up and run; `make build` only builds.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
# make fuzz: seconds per harness, and which harnesses (all when empty; docs/fuzzing.md).
FUZZ_DIR ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZERS ?=

.PHONY: deps configure build test test-sanitize demo bench fuzz clean

deps:
	@bash scripts/install-deps.sh

configure:
	@cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

test: deps
	@$(MAKE) --no-print-directory build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

# The whole suite again, built with AddressSanitizer and UndefinedBehaviorSanitizer into
# build-sanitize/ (the benchmarks are left out: they are not tests), but for the tests below:
# they train for hundreds of steps to check what training reaches, a quality figure rather
# than a code path. `make test` runs them; under the sanitizers the shorter trainer tests run
# the same lines (reflections, the far field, whole-image batches, resuming), and these three
# took 450 s of the 1,290 s the sanitized tests took (docs/testing.md).
SANITIZE_SKIP = ^TrainerTest[.](LossFallsAndTestViewsImprove|ReflectionLossLowersTheSpecularError|WholeImageTrainingImprovesTheTestViewsAndResumesBitExact)$$
test-sanitize: deps
	@cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Release -DGLINT_SANITIZE=ON -DGLINT_CUDA=OFF -DGLINT_BUILD_BENCH=OFF >/dev/null
	@cmake --build build-sanitize -j $(JOBS)
	@rm -rf build-sanitize/reports && mkdir -p build-sanitize/reports
	@cd build-sanitize && \
		ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:log_path=$(CURDIR)/build-sanitize/reports/asan \
		UBSAN_OPTIONS=print_stacktrace=1:log_path=$(CURDIR)/build-sanitize/reports/ubsan \
		ctest --output-on-failure -j $(JOBS) -E '$(SANITIZE_SKIP)'
	@# Reports of the glint processes the end-to-end tests start land here too, even where
	@# the test only expected a non-zero exit: any report fails the target.
	@if [ -n "$$(ls -A build-sanitize/reports)" ]; then \
		echo "test-sanitize: sanitizer reports:"; cat build-sanitize/reports/*; exit 1; fi
	@echo "test-sanitize: no sanitizer reports"

demo: deps
	@$(MAKE) --no-print-directory build
	@bash scripts/demo.sh $(BUILD_DIR)

bench: deps
	@$(MAKE) --no-print-directory build
	@$(BUILD_DIR)/bench/synth_bench --json $(BUILD_DIR)/bench/synth_bench.json

# The harnesses of fuzz/ built with clang, libFuzzer, ASan and UBSan in $(FUZZ_DIR), each run
# for FUZZ_SECONDS one after another; crashes land in $(FUZZ_DIR)/crashes/<harness>/.
fuzz:
	@bash scripts/install-deps.sh --fuzz
	@cmake -S . -B $(FUZZ_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 \
	  -DGLINT_FUZZ=ON -DGLINT_CUDA=OFF -DGLINT_BUILD_TESTS=OFF -DGLINT_BUILD_BENCH=OFF >/dev/null
	@cmake --build $(FUZZ_DIR) -j $(JOBS) --target glint_fuzzers
	@FUZZ_SECONDS=$(FUZZ_SECONDS) bash scripts/run-fuzzers.sh $(FUZZ_DIR) $(FUZZERS)

clean:
	rm -rf $(BUILD_DIR) build-sanitize $(FUZZ_DIR)
