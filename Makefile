# make demo: set up everything and reproduce the paper's tables.
# make test: set up everything and run the C++ (ctest) and Python (pytest) suites.
# make test-sanitize: the same under AddressSanitizer and UBSan (the C++ tests and a pytest subset).
# make census: the fuzz census (tests/fuzz/census.py): the pair queries, then the files, CLI and
# inputs corpus, scenes, curved shapes, motions and robots; CENSUS_ARGS="--count 500"
# FILES_CENSUS_ARGS="--count 100" SCENE_CENSUS_ARGS="--count 40" MOTIONS_CENSUS_ARGS="--count 300"
# ROBOTS_CENSUS_ARGS="--count 400" for a quick one.
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
CPP_BUILD := build/cpp
JOBS ?= 2

PACKAGE_SOURCES := CMakeLists.txt pyproject.toml $(shell find cpp bindings python -type f -not -name '*.pyc' 2>/dev/null)
# pybind11 is pinned because the checked-in stubs (python/swarmcollide/_core.pyi) follow its output.
BUILD_REQUIREMENTS := "scikit-build-core>=0.10" "pybind11==3.1.0"

.PHONY: demo test test-cpp test-python test-sanitize census system-packages install stubs bench \
  bench-scene bench-compound clean

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
	$(PY) -m pip install --quiet --no-build-isolation ".[test,plot,mesh,dask,robot]"
	touch $@

install: $(VENV)/.installed

# ctest runs every C++ test in a process of its own, and then each suite runs whole, in three
# shuffled orders (seeds 1-3): a query's state left on its thread for the next (a cache, a pool,
# a thread_local) shows in one way or the other. Session 67's resumed expansion failed only in a
# fresh process; state that leaks from one query into the next fails only in a shared one.
test-cpp: system-packages
	cmake -S . -B $(CPP_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release \
	  -DSWARMCOLLIDE_BUILD_TESTS=ON -DSWARMCOLLIDE_BUILD_PYTHON=OFF
	cmake --build $(CPP_BUILD) -j $(JOBS)
	ctest --test-dir $(CPP_BUILD) --output-on-failure -j $(JOBS)
	for suite in swarmcollide_tests swarmcollide_allocation_tests; do \
	  $(CPP_BUILD)/tests/cpp/$$suite --gtest_shuffle --gtest_random_seed=1 --gtest_repeat=3 \
	    --gtest_brief=1 || exit 1; \
	done

# make bench: every bench (bench/README.md), each writing bench/results/NAME.json in one format
# (bench/record.py), then bench/RESULTS.md and its plots from them (bench/report.py only renders).
# BENCH_ARGS=--quick runs a reduced set (both the binaries and the Python scripts take it).
BENCH_BUILD := build/bench
BENCH_ARGS ?=

$(VENV)/.bench-installed: $(VENV)/.installed
	$(PY) -m pip install --quiet --no-build-isolation ".[test,plot,mesh,dask,robot,bench]"
	touch $@

# make bench-scene: only the scene section (C++ against FCL's manager, Python against python-fcl
# and trimesh), then bench/RESULTS.md again from every recorded result.
bench-scene: install $(VENV)/.bench-installed
	cmake -S . -B $(BENCH_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release \
	  -DSWARMCOLLIDE_BUILD_BENCH=ON -DSWARMCOLLIDE_BUILD_PYTHON=OFF
	cmake --build $(BENCH_BUILD) -j $(JOBS) --target swarmcollide-scene-bench
	mkdir -p bench/results bench/plots
	$(PY) bench/record.py --bench scene --json bench/results/scene.json -- \
	  $(BENCH_BUILD)/bench/swarmcollide-scene-bench $(BENCH_ARGS)
	$(PY) bench/scene.py $(BENCH_ARGS) --json bench/results/scene_python.json
	$(PY) bench/report.py --results bench/results --plots bench/plots --out bench/RESULTS.md

# make bench-compound: only the compound section (two decomposed meshes against python-fcl's mesh
# distance), then bench/RESULTS.md again from every recorded result.
bench-compound: install $(VENV)/.bench-installed
	mkdir -p bench/results
	$(PY) bench/compound.py $(BENCH_ARGS) --json bench/results/compound.json
	$(PY) bench/report.py --results bench/results --plots bench/plots --out bench/RESULTS.md

# coal's C++ library comes with its pip wheel (the bench extra), under site-packages/cmeel.prefix.
COAL_PREFIX = $$($(PY) -c "import sysconfig; print(sysconfig.get_paths()['purelib'])")/cmeel.prefix

bench: install $(VENV)/.bench-installed bench-scene bench-compound
	cmake -S . -B $(BENCH_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release \
	  -DSWARMCOLLIDE_BUILD_BENCH=ON -DSWARMCOLLIDE_BUILD_PYTHON=OFF \
	  -DSWARMCOLLIDE_COAL_PREFIX="$(COAL_PREFIX)"
	cmake --build $(BENCH_BUILD) -j $(JOBS) --target swarmcollide-bench swarmcollide-fcl-ratio \
	  swarmcollide-batch-loop swarmcollide-swarm-speed swarmcollide-swarm-targets \
	  swarmcollide-narrowphase-coal swarmcollide-penetration-coal
	mkdir -p bench/results bench/plots
	$(PY) bench/record.py --bench narrowphase_coal --json bench/results/narrowphase_coal.json -- \
	  $(BENCH_BUILD)/bench/swarmcollide-narrowphase-coal $(BENCH_ARGS)
	$(PY) bench/record.py --bench narrowphase_coal_poses \
	  --json bench/results/narrowphase_coal_poses.json -- \
	  $(BENCH_BUILD)/bench/swarmcollide-narrowphase-coal --poses 50 $(BENCH_ARGS)
	$(PY) bench/record.py --bench penetration_coal --json bench/results/penetration_coal.json -- \
	  $(BENCH_BUILD)/bench/swarmcollide-penetration-coal $(BENCH_ARGS)
	$(PY) bench/record.py --bench cpp --json bench/results/cpp.json -- \
	  $(BENCH_BUILD)/bench/swarmcollide-bench $(BENCH_ARGS) > $(BENCH_BUILD)/console.txt
	$(PY) bench/record.py --bench fcl_ratio --json bench/results/fcl_ratio.json -- \
	  $(BENCH_BUILD)/bench/swarmcollide-fcl-ratio $(BENCH_ARGS)
	$(PY) bench/compare_python.py $(BENCH_ARGS) --json bench/results/python_comparison.json
	$(PY) bench/per_call.py $(BENCH_ARGS) --json bench/results/per_call.json
	$(PY) bench/hull_points.py $(BENCH_ARGS) --json bench/results/hull_points.json
	$(PY) bench/convergence.py $(BENCH_ARGS) --json bench/results/convergence.json --plots bench/plots
	$(PY) bench/batch.py $(BENCH_ARGS) --json bench/results/batch.json \
	  --loop-binary $(BENCH_BUILD)/bench/swarmcollide-batch-loop
	$(PY) bench/batch.py $(BENCH_ARGS) --poses --json bench/results/pose_batch.json
	$(PY) bench/record.py --bench swarm_speed --json bench/results/swarm_speed.json -- \
	  $(BENCH_BUILD)/bench/swarmcollide-swarm-speed
	$(PY) bench/swarm_targets.py $(BENCH_ARGS) --json bench/results/swarm_targets.json \
	  --binary $(BENCH_BUILD)/bench/swarmcollide-swarm-targets --sweep --choices
	$(PY) bench/kernel_code.py --json bench/results/kernel_code.json \
	  --object $(BENCH_BUILD)/cpp/CMakeFiles/swarmcollide.dir/src/solvers/swarm_kernels.cpp.o
	$(PY) bench/dask_batch.py $(BENCH_ARGS) --json bench/results/dask_batch.json
	$(PY) bench/contacts.py $(BENCH_ARGS) --json bench/results/contacts.json
	$(PY) bench/contacts.py $(BENCH_ARGS) --scene pile --json bench/results/contacts_pile.json
	$(PY) bench/curved_coal.py $(BENCH_ARGS) --json bench/results/curved_coal.json
	$(PY) bench/curved_scene.py $(BENCH_ARGS) --json bench/results/curved_scene.json
	$(PY) bench/robot.py $(BENCH_ARGS) --json bench/results/robot.json
	$(PY) bench/robot_motion.py $(BENCH_ARGS) --json bench/results/robot_motion.json
	$(PY) bench/report.py --results bench/results --plots bench/plots --out bench/RESULTS.md

# The core, the C++ tests and the extension, built with ASan and UBSan (SWARMCOLLIDE_SANITIZE) in
# their own directory, at -O1 with assertions on (Eigen's index checks included). The build is most
# of this target's time, so it keeps line tables only (-g1: the reports' stacks still name
# functions, files and lines; full -g took a quarter longer: ball_screen.cpp 339 s -> 261 s,
# test_batch.cpp 175 s -> 123 s on a loaded host) and leaves out GCC's points-to analysis, which
# took 78% of ball_screen.cpp's instrumented build (19 times its release build, where other files
# take 3; 19 s of CPU without it instead of 95): the whole instrumented build took 1,221 s of CPU
# instead of 2,082. Python itself is not instrumented, so the ASan and UBSan runtimes are preloaded
# into it, and pytest imports the instrumented extension through PYTHONPATH (the .venv supplies
# NumPy, SciPy, pytest and the package's metadata). CPython never frees some of its own memory at
# exit, so leak detection, which would report that, is on for ctest only. PYTHONMALLOC=malloc
# routes Python's small objects through ASan's malloc too. A report from a call in a sandboxed
# child (tests/python/sandbox.py) appears in that test's failure message. The C++ suite also runs
# whole in one shuffled order, as test-cpp's do.
SAN_BUILD := build/sanitize
SAN_SITE := $(SAN_BUILD)/site
SAN_PYTESTS ?= tests/python/test_trust.py tests/python/test_contract.py tests/python/test_batch.py \
  tests/python/test_geometry.py tests/python/test_dual.py tests/python/test_problem.py \
  tests/python/test_motion.py tests/python/test_robot.py tests/python/test_curved_shapes.py \
  tests/python/test_robot_motion.py tests/python/test_scene_sweep.py tests/python/test_compound_poses.py
SAN_RUNTIMES = $$(gcc -print-file-name=libasan.so) $$(gcc -print-file-name=libubsan.so)

test-sanitize: install
	cmake -S . -B $(SAN_BUILD) -G Ninja -DSWARMCOLLIDE_SANITIZE=ON \
	  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -fno-tree-pta" \
	  -DCMAKE_INTERPROCEDURAL_OPTIMIZATION=OFF \
	  -DSWARMCOLLIDE_BUILD_TESTS=ON -DSWARMCOLLIDE_BUILD_PYTHON=ON \
	  -DPython_EXECUTABLE=$(abspath $(PY)) -Dpybind11_DIR="$$($(PY) -m pybind11 --cmakedir)"
	cmake --build $(SAN_BUILD) -j $(JOBS)
	rm -rf $(SAN_SITE)
	mkdir -p $(SAN_SITE)/swarmcollide
	cp python/swarmcollide/*.py python/swarmcollide/py.typed $(SAN_BUILD)/bindings/_core*.so \
	  $(SAN_SITE)/swarmcollide/
	status=0; \
	UBSAN_OPTIONS=print_stacktrace=1 ctest --test-dir $(SAN_BUILD) --output-on-failure -j $(JOBS) \
	  || status=1; \
	UBSAN_OPTIONS=print_stacktrace=1 $(SAN_BUILD)/tests/cpp/swarmcollide_tests --gtest_shuffle \
	  --gtest_random_seed=1 --gtest_brief=1 || status=1; \
	ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1 PYTHONMALLOC=malloc \
	  SWARMCOLLIDE_SANITIZED=1 \
	  LD_PRELOAD="$(SAN_RUNTIMES)" PYTHONPATH=$(SAN_SITE) \
	  $(PY) -m pytest -p no:cacheprovider -n $(JOBS) $(SAN_PYTESTS) || status=1; \
	exit $$status

CENSUS_ARGS ?=
FILES_CENSUS_ARGS ?=
# The scene corpus: long seeded motions through every broadphase, every method's certified rows,
# far bodies and bad arguments (tests/python/scene_cases.py).
SCENE_CENSUS_ARGS ?= --count 200
# The curved shapes against coal's primitives (needs the bench extra): every pair of shape kinds.
CURVED_CENSUS_ARGS ?= --pairs 200
# The same at extreme sizes (wires, plates, needles; sizes over six decades) and offsets.
CURVED_EXTREME_CENSUS_ARGS ?= --pairs 100

census: install $(VENV)/.bench-installed
	$(PY) tests/fuzz/census.py --json build/fuzz/census.jsonl $(CENSUS_ARGS)
	$(PY) tests/fuzz/census.py --corpus files --count 1000 --timeout 30 \
	  --json build/fuzz/files.jsonl $(FILES_CENSUS_ARGS)
	$(PY) tests/fuzz/census.py --corpus scene --json build/fuzz/scene.jsonl $(SCENE_CENSUS_ARGS)
	$(PY) tests/fuzz/curved_census.py --json build/fuzz/curved.jsonl $(CURVED_CENSUS_ARGS)
	$(PY) tests/fuzz/curved_census.py --extreme --json build/fuzz/curved_extreme.jsonl \
	  $(CURVED_EXTREME_CENSUS_ARGS)
	# At the library's default tolerance, where every unproven answer is a finding (at 1e-12 some
	# are rounding's floor): two seeds that held one before session 65's fixes (tests/fuzz/AFTER.md).
	$(PY) tests/fuzz/curved_census.py --tolerance 1e-9 --seed 32 --pairs 300 \
	  --json build/fuzz/curved_default.jsonl
	$(PY) tests/fuzz/curved_census.py --extreme --tolerance 1e-9 --seed 67 --pairs 300 \
	  --json build/fuzz/curved_extreme_default.jsonl
	$(PY) tests/fuzz/census.py --corpus motions --count 3000 --json build/fuzz/motions.jsonl \
	  $(MOTIONS_CENSUS_ARGS)
	$(PY) tests/fuzz/census.py --corpus robots --count 4000 --json build/fuzz/robots.jsonl \
	  $(ROBOTS_CENSUS_ARGS)

stubs: install
	$(PY) -m pybind11_stubgen swarmcollide._core -o python --numpy-array-use-type-var

# The suites run on $(JOBS) worker processes (pytest-xdist): a serial run left a core idle.
test-python: install
	$(PY) -m pytest -n $(JOBS)

clean:
	rm -rf build $(VENV)
