# make demo: set up everything and reproduce the paper's tables.
# make test: set up everything and run the C++ (ctest) and Python (pytest) suites.
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
CPP_BUILD := build/cpp
JOBS ?= 2

PACKAGE_SOURCES := CMakeLists.txt pyproject.toml $(shell find cpp bindings python -type f -not -name '*.pyc' 2>/dev/null)
# pybind11 is pinned because the checked-in stubs (python/swarmcollide/_core.pyi) follow its output.
BUILD_REQUIREMENTS := "scikit-build-core>=0.10" "pybind11==3.1.0"

.PHONY: demo test test-cpp test-python system-packages install stubs bench clean

demo: install
	$(PY) -m swarmcollide paper

test: test-cpp test-python

system-packages:
	@./scripts/install-system-packages.sh

$(PY): | system-packages
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip

$(VENV)/.installed: $(PACKAGE_SOURCES) | system-packages $(PY)
	$(PY) -m pip install --quiet $(BUILD_REQUIREMENTS)
	$(PY) -m pip install --quiet --no-build-isolation ".[test,dask]"
	touch $@

install: $(VENV)/.installed

test-cpp: system-packages
	cmake -S . -B $(CPP_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release \
	  -DSWARMCOLLIDE_BUILD_TESTS=ON -DSWARMCOLLIDE_BUILD_PYTHON=OFF
	cmake --build $(CPP_BUILD) -j $(JOBS)
	ctest --test-dir $(CPP_BUILD) --output-on-failure -j $(JOBS)

# make bench: the benchmark binary, the Python comparisons, bench/RESULTS.md and its plots.
# BENCH_ARGS=--quick runs a reduced set (both the binary and the Python scripts take it).
BENCH_BUILD := build/bench
BENCH_ARGS ?=

$(VENV)/.bench-installed: $(VENV)/.installed
	$(PY) -m pip install --quiet --no-build-isolation ".[test,dask,bench]"
	touch $@

bench: install $(VENV)/.bench-installed
	cmake -S . -B $(BENCH_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release \
	  -DSWARMCOLLIDE_BUILD_BENCH=ON -DSWARMCOLLIDE_BUILD_PYTHON=OFF
	cmake --build $(BENCH_BUILD) -j $(JOBS) --target swarmcollide-bench swarmcollide-batch-loop \
	  swarmcollide-swarm-speed swarmcollide-swarm-targets
	mkdir -p bench/results bench/plots
	$(BENCH_BUILD)/bench/swarmcollide-bench $(BENCH_ARGS) --json bench/results/cpp.json \
	  > $(BENCH_BUILD)/console.txt
	$(PY) bench/compare_python.py $(BENCH_ARGS) --json bench/results/python_comparison.json
	$(PY) bench/convergence.py $(BENCH_ARGS) --json bench/results/convergence.json --plots bench/plots
	$(PY) bench/batch.py $(BENCH_ARGS) --json bench/results/batch.json \
	  --loop-binary $(BENCH_BUILD)/bench/swarmcollide-batch-loop
	$(BENCH_BUILD)/bench/swarmcollide-swarm-speed > bench/results/swarm_speed.txt
	$(PY) bench/swarm_targets.py $(BENCH_ARGS) --json bench/results/swarm_targets.json \
	  --binary $(BENCH_BUILD)/bench/swarmcollide-swarm-targets \
	  --sweep bench/results/velocity_sweep.txt --choices bench/results/choices.txt
	$(PY) bench/kernel_code.py > bench/results/kernel_code.txt \
	  --object $(BENCH_BUILD)/cpp/CMakeFiles/swarmcollide.dir/src/solvers/swarm_kernels.cpp.o
	$(PY) bench/report.py --results bench/results --plots bench/plots --out bench/RESULTS.md
	$(PY) bench/dask_batch.py $(BENCH_ARGS) --json bench/results/dask_batch.json \
	  --results-md bench/RESULTS.md

stubs: install
	$(PY) -m pybind11_stubgen swarmcollide._core -o python --numpy-array-use-type-var

test-python: install
	$(PY) -m pytest

clean:
	rm -rf build $(VENV)
