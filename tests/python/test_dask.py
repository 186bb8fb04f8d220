"""Batches on Dask arrays: bitwise the in-memory call whatever the chunking and the scheduler (the
threaded one and a real distributed cluster of two worker processes); errors name the global
pair index; arguments are checked when the graph is built."""

import re
import subprocess
import sys
from dataclasses import fields
from pathlib import Path

import dask
import dask.array as da
import numpy as np
import pytest
import zarr
from distributed import Client, LocalCluster

import swarmcollide as sc
import swarmcollide.dask as scd

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "dask_out_of_core.py"
PAIRS = 120
# Even, irregular, single-pair, one-chunk, and As and Bs cut differently.
CHUNKINGS = [(40, 40), (7, 7), ((1, 60, 59), (1, 60, 59)), (PAIRS, PAIRS), (30, 45)]
QUERIES = [
    ("distance_many", "ipso", {"max_iterations": 15}),
    ("distance_many", "dual", {}),
    ("collide_many", "pso", {"max_iterations": 5}),
    ("signed_distance_many", "dual", {}),
]


@pytest.fixture(scope="module")
def bodies():
    rng = np.random.default_rng(17)
    As = rng.normal(size=(PAIRS, 8, 3))
    Bs = rng.normal(size=(PAIRS, 5, 3)) + rng.uniform(-3, 3, size=(PAIRS, 1, 3))
    return As, Bs


@pytest.fixture(scope="module")
def client():
    """A real cluster: a scheduler and two worker processes on the loopback interface, used
    where a test asks for it (it is not made every computation's default)."""
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address="127.0.0.1:0") as cluster, \
            Client(cluster, set_as_default=False) as client:
        yield client


def chunked(As, Bs, chunks_a, chunks_b):
    return (da.from_array(As, chunks=(chunks_a, -1, -1)),
            da.from_array(Bs, chunks=(chunks_b, -1, -1)))


def assert_bitwise(lazy, eager, scheduler="threads"):
    computed = lazy.compute(scheduler=scheduler)
    for field in fields(computed):
        got, expected = getattr(computed, field.name), getattr(eager, field.name)
        assert got.dtype == expected.dtype and got.shape == expected.shape, field.name
        assert got.tobytes() == expected.tobytes(), field.name


@pytest.mark.parametrize(("query", "method", "parameters"), QUERIES)
@pytest.mark.parametrize(("chunks_a", "chunks_b"), CHUNKINGS)
def test_threaded_scheduler_gives_the_in_memory_answers_bitwise(
        bodies, query, method, parameters, chunks_a, chunks_b):
    As, Bs = bodies
    eager = getattr(sc, query)(As, Bs, method=method, seed=3, **parameters)
    lazy = getattr(scd, query)(*chunked(As, Bs, chunks_a, chunks_b), method=method, seed=3,
                               **parameters)
    with dask.config.set(num_workers=3):
        assert_bitwise(lazy, eager)


@pytest.mark.parametrize(("query", "method", "parameters"), QUERIES)
def test_a_cluster_of_two_processes_gives_the_in_memory_answers_bitwise(
        client, bodies, query, method, parameters):
    As, Bs = bodies
    eager = getattr(sc, query)(As, Bs, method=method, seed=3, **parameters)
    for chunks_a, chunks_b in CHUNKINGS[2:]:
        lazy = getattr(scd, query)(*chunked(As, Bs, chunks_a, chunks_b), method=method, seed=3,
                                   **parameters)
        assert_bitwise(lazy, eager, client)


@pytest.mark.parametrize("where", ["threads", "cluster", "dask.get"])
def test_persisted_answers_are_the_in_memory_answers_bitwise(request, bodies, where):
    """persist keeps one piece per chunk with every field, which compute, store and each field
    read. dask.get is neither a local scheduler nor a cluster: its chunks come back together."""
    scheduler = {"cluster": request.getfixturevalue("client") if where == "cluster" else None,
                 "dask.get": dask.get, "threads": "threads"}[where]
    As, Bs = bodies
    eager = sc.signed_distance_many(As, Bs, seed=5)
    lazy = scd.signed_distance_many(*chunked(As, Bs, (1, 60, 59), 30), seed=5)
    kept = lazy.persist(scheduler=scheduler)
    assert repr(kept) == "BatchArrays(120 pairs in 6 chunks, lazy)"
    assert_bitwise(kept, eager, scheduler)
    assert_bitwise(lazy, eager, scheduler)
    for field in ("distance", "point_b", "iterations"):
        got = getattr(kept, field).compute(scheduler=scheduler)
        assert got.tobytes() == getattr(eager, field).tobytes(), field
    if where != "cluster":  # a NumPy target sent to another process is a copy
        distance = np.empty(PAIRS)
        kept.store({"distance": distance}, scheduler=scheduler)
        assert distance.tobytes() == eager.distance.tobytes()


def test_store_on_a_cluster_writes_zarr_targets_each_chunk_once(client, bodies, tmp_path):
    As, Bs = bodies
    eager = sc.distance_many(As, Bs)
    lazy = scd.distance_many(*chunked(As, Bs, 40, 40))
    targets = {name: zarr.open_array(str(tmp_path / f"{name}.zarr"), mode="w",
                                     shape=getattr(eager, name).shape, chunks=(40, 3)[:getattr(
                                         eager, name).ndim], dtype=getattr(eager, name).dtype)
               for name in ("distance", "point_a", "colliding")}
    lazy.store(targets, lock=False, scheduler=client)
    for name, target in targets.items():
        assert target[:].tobytes() == getattr(eager, name).tobytes(), name


def test_answers_do_not_depend_on_threads_per_chunk(bodies):
    As, Bs = bodies
    eager = sc.distance_many(As, Bs, method="ipso", max_iterations=10)
    assert_bitwise(scd.distance_many(*chunked(As, Bs, 50, 50), method="ipso", threads=None,
                                     max_iterations=10), eager)
    assert_bitwise(scd.distance_many(*chunked(As, Bs, 50, 50), method="ipso", threads=2,
                                     max_iterations=10), eager)


def test_collide_many_passes_escalate(bodies):
    As, Bs = bodies
    for escalate in (True, False):
        eager = sc.collide_many(As, Bs, method="ipso", max_iterations=0, escalate=escalate)
        lazy = scd.collide_many(*chunked(As, Bs, 25, 25), method="ipso", max_iterations=0,
                                escalate=escalate)
        assert_bitwise(lazy, eager)
    assert eager.escalated.sum() == 0 and lazy.escalated.sum().compute(scheduler="sync") == 0


def test_bodies_chunked_along_their_points_too_and_integer_coordinates(bodies):
    As, Bs = bodies
    As = np.round(As * 10).astype(np.int32)
    lazy = scd.distance_many(da.from_array(As, chunks=(35, 3, 2)), da.from_array(Bs, chunks=50))
    assert_bitwise(lazy, sc.distance_many(As, Bs))


def test_each_chunk_is_answered_once_for_all_fields(bodies, monkeypatch):
    As, Bs = bodies
    answered = []
    answer = scd._answer

    def counting(where, *args, **kwargs):
        answered.append(where[0].start)
        return answer(where, *args, **kwargs)

    monkeypatch.setattr(scd, "_answer", counting)
    lazy = scd.distance_many(*chunked(As, Bs, 40, 40))
    lazy.compute(scheduler="threads")
    assert sorted(answered) == [0, 40, 80]
    dask.compute(lazy.distance, lazy.point_a, lazy.colliding, scheduler="threads")
    assert sorted(answered) == [0, 0, 40, 40, 80, 80]


def test_store_writes_the_fields_into_numpy_and_zarr_targets(bodies, tmp_path):
    As, Bs = bodies
    eager = sc.signed_distance_many(As, Bs)
    lazy = scd.signed_distance_many(*chunked(As, Bs, 30, 30))
    distance = np.empty(PAIRS)
    point_a = zarr.open_array(str(tmp_path / "point_a.zarr"), mode="w", shape=(PAIRS, 3),
                              chunks=(30, 3), dtype="f8")
    lazy.store({"distance": distance, "point_a": point_a}, scheduler="threads")
    assert distance.tobytes() == eager.distance.tobytes()
    assert point_a[:].tobytes() == eager.point_a.tobytes()
    with pytest.raises(ValueError, match="targets has no field named 'points'"):
        lazy.store({"points": distance})


@pytest.mark.parametrize(("field", "shape"), [
    ("distance", (PAIRS - 1,)), ("distance", (PAIRS + 1,)), ("distance", (PAIRS, 5)),
    ("point_a", (PAIRS,)), ("point_a", (PAIRS, 4))])
def test_store_refuses_a_target_of_another_shape_before_computing(bodies, monkeypatch, field,
                                                                   shape):
    # A short target failed in a chunk's write with NumPy's broadcasting message, naming no
    # target; a long one was written in part, its tail left as it was.
    monkeypatch.setattr(scd, "_answer", None)  # nothing is answered: the check comes first
    lazy = scd.distance_many(*chunked(*bodies, 40, 40))
    target = np.full(shape, -1.0)
    expected = (PAIRS, 3) if field == "point_a" else (PAIRS,)
    with pytest.raises(ValueError, match=rf"^targets\['{field}'\] has shape "
                                         rf"{re.escape(str(shape))}, where the field '{field}' has "
                                         rf"shape {re.escape(str(expected))}"):
        lazy.store({"colliding": np.empty(PAIRS, bool), field: target}, scheduler="sync")
    assert (target == -1).all()
    with pytest.raises(TypeError, match=r"^targets\['distance'\] must be an array with a shape, "
                                        r".*got list"):
        lazy.store({"distance": [0.0] * PAIRS})


def test_empty_batch():
    empty = da.zeros((0, 4, 3), chunks=(10, -1, -1))
    r = scd.distance_many(empty, empty).compute(scheduler="threads")
    assert len(r) == 0 and r.point_a.shape == (0, 3) and r.iterations.dtype == np.int32


def test_repr(bodies):
    lazy = scd.collide_many(*chunked(*bodies, 50, 50))
    assert repr(lazy) == "BatchArrays(120 pairs in 3 chunks, lazy)"
    computed = lazy.compute(scheduler="threads")
    assert repr(computed) == (f"BatchArrays(120 pairs, {computed.colliding.sum()} colliding, "
                              f"{computed.certified.sum()} certified)")


def bad_bodies(bodies):
    As, Bs = (x.copy() for x in bodies)
    As[57, 2] = np.nan  # chunk [50, 75): As[57] cannot be built
    Bs[101], As[101] = 1.5e308, -1.5e308  # chunk [100, 120): a distance beyond the double range
    return As, Bs


@pytest.mark.parametrize("scheduler", ["threads", "cluster"])
def test_a_bad_body_in_one_chunk_raises_the_in_memory_error_with_its_global_index(
        request, bodies, scheduler):
    As, Bs = bad_bodies(bodies)
    compute = {"scheduler": request.getfixturevalue("client") if scheduler == "cluster"
               else scheduler}
    with pytest.raises(ValueError, match=r"^As\[57\]: points has a NaN"):
        sc.distance_many(As[:100], Bs[:100])
    with pytest.raises(ValueError, match=r"^As\[57\]: points has a NaN"):
        scd.distance_many(*chunked(As[:100], Bs[:100], 25, 25)).compute(**compute)
    with pytest.raises(ValueError, match=r"^pair 101: "):
        sc.collide_many(As[75:], Bs[75:], first_index=75)
    with pytest.raises(ValueError, match=r"^pair 101: "):
        scd.collide_many(*chunked(As, Bs, 25, 25)).colliding[75:].compute(**compute)


@pytest.mark.parametrize(
    ("As", "Bs", "keywords", "error", "message"),
    [
        (np.zeros((2, 4, 3)), da.zeros((2, 4, 3)), {}, TypeError,
         r"As must be a dask array of shape \(m, n, 3\), got ndarray; wrap .*from_array"),
        (da.zeros((2, 4, 3)), [[[0, 0, 0]]], {}, TypeError, "Bs must be a dask array"),
        (da.zeros((2, 4, 2)), da.zeros((2, 4, 3)), {}, ValueError,
         r"As must have shape \(m, n, 3\) with n >= 1, got \(2, 4, 2\)"),
        (da.zeros((2, 4, 3)), da.zeros((2, 0, 3)), {}, ValueError, r"Bs must have shape"),
        (da.zeros((2, 12)), da.zeros((2, 4, 3)), {}, ValueError, r"As must have shape"),
        (da.zeros((2, 4, 3), dtype=bool), da.zeros((2, 4, 3)), {}, TypeError,
         "As must hold real numbers, got an array of dtype bool"),
        (da.zeros((2, 4, 3)), da.zeros((2, 4, 3), dtype=complex), {}, TypeError, "Bs must hold"),
        (da.zeros((2, 4, 3)), da.zeros((3, 4, 3)), {}, ValueError,
         "As and Bs must hold the same number of pairs, got 2 and 3"),
        (da.zeros((2, 4, 3))[da.ones(2, dtype=bool)], da.zeros((2, 4, 3)), {}, ValueError,
         r"As has chunks of unknown size; call As.compute_chunk_sizes\(\) first"),
        (da.zeros((2, 4, 3)), da.zeros((2, 4, 3)), {"method": "libccd"}, ValueError,
         r"distance is not available with method 'libccd'; use one of \['dual'"),
        (da.zeros((2, 4, 3)), da.zeros((2, 4, 3)), {"method": "gjk"}, ValueError, "gjk"),
        (da.zeros((2, 4, 3)), da.zeros((2, 4, 3)), {"swarm_size": 0}, ValueError, "swarm_size"),
        (da.zeros((2, 4, 3)), da.zeros((2, 4, 3)), {"seed": -1}, ValueError, "seed must lie"),
        (da.zeros((2, 4, 3)), da.zeros((2, 4, 3)), {"threads": 0}, ValueError,
         r"threads must be in \[1, 1024\]"),
        (da.zeros((2, 4, 3)), da.zeros((2, 4, 3)), {"threads": 1.5}, TypeError,
         "threads must be an integer or None"),
    ],
)
def test_bad_arguments_raise_when_the_graph_is_built(As, Bs, keywords, error, message):
    with pytest.raises(error, match=message):
        scd.distance_many(As, Bs, **keywords)


def test_signed_distance_needs_a_method_that_measures_penetration():
    bodies = da.zeros((2, 4, 3))
    with pytest.raises(ValueError, match="signed_distance is not available with method 'ipso'"):
        scd.signed_distance_many(bodies, bodies, method="ipso")


@pytest.mark.parametrize("store", ["npy", "zarr"])
def test_out_of_core_example_runs_and_checks_itself(tmp_path, store):
    done = subprocess.run(
        [sys.executable, str(EXAMPLE), "--pairs", "300", "--chunk", "70", "--store", store,
         "--dir", str(tmp_path), "--check"],
        capture_output=True, text=True, timeout=120,
    )
    assert done.returncode == 0, done.stderr
    assert "300 pairs" in done.stdout and "bitwise equal to the in-memory call" in done.stdout
