# The two commands of README.md:
#   make run    installs what is missing, builds (Release) and runs the main job
#   make test   installs what is missing, builds (Release) and runs the test suite (one OpenMP
#               thread per test, as many tests at a time as there are cores)
# and, outside the suite, make validate-long (the long validations, label `long`) and make fuzz
# (each fuzz target for FUZZ_SECONDS, clang's libFuzzer with sanitizers, in build-fuzz/).
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release -DSNAPJUMP_WERROR=ON

.PHONY: run test validate-long fuzz deps build bench format clean
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 60

deps:
	@bash scripts/install-deps.sh

build: deps
	@cmake -S . -B $(BUILD) $(CMAKE_FLAGS) > /dev/null
	@cmake --build $(BUILD) -j $(JOBS)

run: build
	$(BUILD)/snapjump predict
	$(BUILD)/snapjump run

test: build
	cd $(BUILD) && OMP_NUM_THREADS=1 ctest -LE long --output-on-failure -j $(JOBS) --timeout 900

validate-long: build
	$(BUILD)/snapjump_long_validation

fuzz:
	@bash scripts/install-deps.sh clang libclang-rt-14-dev
	@cmake -S . -B $(FUZZ_BUILD) -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DSNAPJUMP_FUZZ=ON -DSNAPJUMP_BUILD_TESTS=OFF -DSNAPJUMP_BUILD_BENCHMARKS=OFF > /dev/null
	@cmake --build $(FUZZ_BUILD) -j $(JOBS) --target snapjump_fuzz
	@bash scripts/fuzz.sh $(FUZZ_BUILD) $(FUZZ_SECONDS)

format:
	clang-format -i $$(git ls-files '*.cpp' '*.hpp')

clean:
	rm -rf $(BUILD)
