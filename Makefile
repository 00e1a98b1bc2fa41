# The README's two commands. Both install what is missing (deploy/install-deps.sh is fast when nothing is),
# configure and build in build/, then act.
BUILD ?= build
JOBS ?= 2
CMAKE_FLAGS ?=
RUN_ARGS ?= run --sim

# ccache, when installed (deploy/install-deps.sh adds it, so it is looked for when configuring, after deps), makes
# rebuilds fast; paths are hashed relative to the checkout, so another checkout of the tree reuses the same cache.
export CCACHE_BASEDIR := $(CURDIR)

.PHONY: run test build deps clean bench fuzz format install

deps:
	@bash deploy/install-deps.sh

$(BUILD)/build.ninja:
	@launcher=; command -v ccache >/dev/null && \
	  launcher="-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache"; \
	  cmake -S . -B $(BUILD) -G Ninja $$launcher $(CMAKE_FLAGS)

build: deps $(BUILD)/build.ninja
	@cmake --build $(BUILD) -j $(JOBS)

# The virtual car on a shared track with the full stack and the dashboard, driving on what it sees (the defaults:
# the LiDAR and camera stages, GNSS-INS fused with the wheel speeds and the LiDAR odometry).
run: build
	@$(BUILD)/daemon/fsd $(RUN_ARGS)

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 600

bench: build
	@cmake --build $(BUILD) -j $(JOBS) --target benchmarks
	@for b in $(BUILD)/bench/*_bench; do [ -x "$$b" ] && "$$b"; done

# The libFuzzer targets (clang, ASan/UBSan) in build-fuzz/, each for FUZZ_SECONDS (default 45); findings fail the
# step and stay in test-artifacts/fuzz/. FUZZ_RUNS=N runs N executions per target instead.
fuzz: deps
	@bash tests/fuzz/run.sh

# The car's computer (as root): binary, model, dashboard, /etc/fsd, the systemd unit and udev rules
# (deploy/install.sh; docs/operations.md). PREFIX=/usr/local by default.
install: build
	@BUILD=$(BUILD) bash deploy/install.sh

clean:
	@rm -rf $(BUILD)

# The house style (.clang-format) over every C++ file of the tree.
format:
	@git ls-files '*.cpp' '*.hpp' | xargs clang-format -i
