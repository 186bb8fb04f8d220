"""ConvexPolyhedron: construction from (n, 3) points, queries, hulls and bad input."""

import numpy as np
import pytest

import swarmcollide as sc

CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)


def test_keeps_the_points_as_given_and_read_only():
    body = sc.ConvexPolyhedron(CUBE)
    np.testing.assert_array_equal(body.vertices, CUBE)
    assert len(body) == 8
    with pytest.raises(ValueError):
        body.vertices[0, 0] = 5.0


@pytest.mark.parametrize("points", [CUBE.tolist(), CUBE.astype(np.float32), CUBE.astype(int)])
def test_accepts_array_likes_of_any_real_dtype(points):
    np.testing.assert_array_equal(sc.ConvexPolyhedron(points).vertices, CUBE)


def test_accepts_non_contiguous_arrays():
    wide = np.zeros((8, 6))
    wide[:, ::2] = CUBE
    np.testing.assert_array_equal(sc.ConvexPolyhedron(wide[:, ::2]).vertices, CUBE)


@pytest.mark.parametrize(
    ("points", "error", "message"),
    [
        ([], ValueError, "shape"),
        (np.zeros((0, 3)), ValueError, "empty"),
        ([[1, 2]], ValueError, r"points must be an \(n, 3\) array of numbers, got shape \(1, 2\)"),
        ([1, 2, 3], ValueError, "shape"),
        (np.zeros((2, 3, 1)), ValueError, "shape"),
        ([[1, 2, 3], [4, 5]], ValueError, "array of numbers"),
        ([[np.nan, 0, 0]], ValueError, "NaN or infinite"),
        ([[0, 0, 0], [0, np.inf, 0]], ValueError, "row 1"),
        ("cube", TypeError, "got str"),
        ([[None, 0, 0]], TypeError, "real numbers"),
        ([[1j, 0, 0]], TypeError, "real numbers"),
        (np.ones((2, 3), dtype=bool), TypeError, "real numbers"),
    ],
)
def test_bad_points_raise_a_clear_error(points, error, message):
    with pytest.raises(error, match=message):
        sc.ConvexPolyhedron(points)


def test_support_aabb_centroid():
    body = sc.ConvexPolyhedron(np.vstack([CUBE, [[0.2, 0.2, 0.2]]]))
    np.testing.assert_array_equal(body.support([1, -1, 1]), [1, 0, 1])
    assert body.support_index([-1, -1, -1]) == 0
    box = body.aabb()
    np.testing.assert_array_equal(box.min, [0, 0, 0])
    np.testing.assert_array_equal(box.max, [1, 1, 1])
    np.testing.assert_allclose(body.centroid(), [0.5, 0.5, 0.5], atol=1e-14)
    with pytest.raises(ValueError, match="direction"):
        body.support([np.nan, 0, 0])


@pytest.mark.parametrize("count", [8, 32, 33, 40, 64, 300])
@pytest.mark.parametrize("inner", [False, True])
def test_support_is_the_highest_point_of_every_body(count, inner):
    # Points on a sphere are every one a vertex; beyond the columns of small bodies (32 points)
    # support() scanned nothing and returned a wrong point for 96-100% of directions.
    rng = np.random.default_rng(count)
    points = rng.normal(size=(count, 3))
    points /= np.linalg.norm(points, axis=1)[:, None]
    if inner:
        points = np.vstack([points, rng.normal(size=(count, 3)) * 0.1])
    body = sc.ConvexPolyhedron(points, radius=0.1)
    for d in rng.normal(size=(50, 3)):
        assert body.support(d) @ d == pytest.approx(np.max(points @ d), abs=1e-12)
        assert points[body.support_index(d)] @ d == pytest.approx(np.max(points @ d), abs=1e-12)


def test_hull_of_a_cube_with_an_inner_point():
    body = sc.ConvexPolyhedron(np.vstack([CUBE, [[0.5, 0.5, 0.5]]]))
    hull = body.hull()
    assert hull.dimension == 3
    np.testing.assert_array_equal(hull.vertex_indices, np.arange(8))
    assert hull.faces.shape == (12, 3)
    # Outward: every hull vertex lies behind every face.
    v = body.vertices
    for face in hull.faces:
        normal = np.cross(v[face[1]] - v[face[0]], v[face[2]] - v[face[0]])
        assert np.all((v[:8] - v[face[0]]) @ normal <= 1e-12)
    assert "dimension=3" in repr(hull) and "12 faces" in repr(hull)


@pytest.mark.parametrize(
    ("points", "dimension", "vertices", "faces"),
    [
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [0.5, 0.5, 0]], 2, 4, 4),
        ([[0, 0, 0], [1, 1, 1], [0.5, 0.5, 0.5]], 1, 2, 0),
        ([[2, 2, 2], [2, 2, 2]], 0, 1, 0),
    ],
)
def test_degenerate_bodies_have_exact_lower_dimensional_hulls(points, dimension, vertices, faces):
    hull = sc.ConvexPolyhedron(points).hull()
    assert hull.dimension == dimension
    assert len(hull.vertex_indices) == vertices
    assert hull.faces.shape == (faces, 3)


def test_a_polyhedron_is_accepted_where_points_are():
    body = sc.ConvexPolyhedron(CUBE)
    np.testing.assert_array_equal(sc.ConvexPolyhedron(body).vertices, CUBE)
    assert body.bounding_radius == pytest.approx(np.sqrt(3) / 2)
    assert body.radius == 0


def test_repr_tells_what_it_holds():
    text = repr(sc.ConvexPolyhedron(CUBE))
    assert text.startswith("ConvexPolyhedron(8 points")
    assert "[0, 0, 0] to [1, 1, 1]" in text


@pytest.mark.parametrize("count", [4, 5, 8, 12, 16, 17, 40])
def test_hulls_match_an_independent_qhull(count):
    from scipy.spatial import ConvexHull

    rng = np.random.default_rng(count)
    for trial in range(10):
        points = rng.normal(size=(count, 3))
        if trial % 2:  # points on a grid: coplanar faces, collinear edges, repeated points
            points = np.round(points)
        try:
            reference = ConvexHull(points)
        except Exception:
            continue  # flat grids: covered by the degenerate tests
        hull = sc.ConvexPolyhedron(points).hull()
        assert hull.dimension == 3
        assert {tuple(p) for p in points[hull.vertex_indices]} == {
            tuple(p) for p in points[reference.vertices]
        }
        corners = points[hull.faces]
        volume = np.einsum("ij,ij->i", corners[:, 0], np.cross(corners[:, 1], corners[:, 2])).sum() / 6
        assert volume == pytest.approx(reference.volume, rel=1e-12)


def _sphere_among_inside_points(inside: int, seed: int):
    """45 points of a Fibonacci lattice on the unit sphere (every one a hull vertex) shuffled among
    points strictly inside their hull; returns the points and the rows of the 45."""
    i = np.arange(45)
    z = 1 - 2 * (i + 0.5) / 45
    angle = np.pi * (3 - np.sqrt(5)) * i
    sphere = np.column_stack([np.sqrt(1 - z * z) * np.cos(angle),
                              np.sqrt(1 - z * z) * np.sin(angle), z])
    rng = np.random.default_rng(seed)
    weights = rng.uniform(size=(inside, 4))
    weights /= weights.sum(axis=1, keepdims=True)
    interior = 0.98 * np.einsum("ik,ikj->ij", weights, sphere[rng.integers(45, size=(inside, 4))])
    order = rng.permutation(45 + inside)
    points = np.vstack([sphere, interior])[order]
    return points, np.sort(np.argsort(order)[:45])


# Budgets that keep the paper's methods quick on 345 points: they are not asked to converge,
# only to keep their contract over every given point.
_SHORT_BUDGETS = {"ipso": {"max_iterations": 20}, "pso": {"max_iterations": 20},
                  "penalty": {"outer_iterations": 2}}


@pytest.mark.parametrize("method", sorted(sc.METHODS))
def test_answers_over_the_hull_points_report_weights_over_every_given_point(method):
    points, hull_rows = _sphere_among_inside_points(300, seed=4)
    body = sc.ConvexPolyhedron(points)
    hull = sc.ConvexPolyhedron(points[hull_rows])
    other = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float) + 1.2
    info = sc.METHODS[method]
    query = getattr(sc, "distance" if "distance" in info.queries else "signed_distance")
    r = query(body, other, method=method, **_SHORT_BUDGETS.get(method, {}))
    assert r.weights_a.shape == (len(points),)
    np.testing.assert_allclose(r.weights_a @ points, r.point_a, atol=1e-12)
    if info.always_certified:
        off_hull = np.setdiff1d(np.arange(len(points)), hull_rows)
        assert not r.weights_a[off_hull].any()
        assert r.distance == pytest.approx(query(hull, other, method=method).distance, abs=1e-9)


@pytest.mark.parametrize("method", ["dual", "exact", "fcl"])
def test_compound_parts_read_their_hull_points_and_report_weights_over_their_given_points(method):
    points, hull_rows = _sphere_among_inside_points(300, seed=5)
    box = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float) + 3
    compound = sc.CompoundBody([points, box])
    other = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float) * 0.5
    other += [1.3, 0.2, -0.1]
    r = sc.distance(compound, other, method=method)
    assert r.part_a == 0 and r.certified
    assert r.weights_a.shape == (len(points),)
    assert not r.weights_a[np.setdiff1d(np.arange(len(points)), hull_rows)].any()
    expected = sc.distance(points[hull_rows], other, method=method).distance
    assert r.distance == pytest.approx(expected, abs=1e-9)
