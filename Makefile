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
	$(PY) -m pip install --quiet --no-build-isolation ".[test]"
	touch $@

install: $(VENV)/.installed

test-cpp: system-packages
	cmake -S . -B $(CPP_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release \
	  -DSWARMCOLLIDE_BUILD_TESTS=ON -DSWARMCOLLIDE_BUILD_PYTHON=OFF
	cmake --build $(CPP_BUILD) -j $(JOBS)
	ctest --test-dir $(CPP_BUILD) --output-on-failure -j $(JOBS)

stubs: install
	$(PY) -m pybind11_stubgen swarmcollide._core -o python --numpy-array-use-type-var

test-python: install
	$(PY) -m pytest

clean:
	rm -rf build $(VENV)
