# The two commands of README.md:
#   make run    installs what is missing, builds (Release) and runs the main job
#   make test   installs what is missing, builds (Release) and runs the test suite (one OpenMP
#               thread per test, as many tests at a time as there are cores)
# and, outside the suite, make validate-long (the long validations, label `long`).
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release -DSNAPJUMP_WERROR=ON

.PHONY: run test validate-long deps build bench format clean

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

format:
	clang-format -i $$(git ls-files '*.cpp' '*.hpp')

clean:
	rm -rf $(BUILD)
