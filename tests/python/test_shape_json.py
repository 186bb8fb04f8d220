"""Shapes outside queries: JSON records (read back as the same bodies), the CLI reading and
writing them, and pictures of curved and rounded bodies (tessellated for drawing only)."""

import json
import math

import numpy as np
import pytest

import swarmcollide as sc
from shape_checks import SHAPES, at
from swarmcollide.cli import main
from swarmcollide.shape_json import body_from_json, body_to_json


@pytest.mark.parametrize("body", SHAPES, ids=lambda b: repr(b)[:20])
def test_every_shape_is_read_back_as_the_same_body(body):
    record = json.loads(json.dumps(body_to_json(body)))
    again = body_from_json(record)
    assert type(again) is type(body) and repr(again) == repr(body)
    # The same body: the same support points and the same answers.
    for d in ([1, 0, 0], [0.3, -0.5, 0.8], [0, 0, -1]):
        np.testing.assert_array_equal(again.support(d), body.support(d))
    other = sc.Box([0.5, 0.5, 0.5])
    assert (sc.distance(again, other, pose_b=at(4)).distance
            == sc.distance(body, other, pose_b=at(4)).distance)


def test_compound_bodies_are_read_back_part_by_part():
    body = sc.CompoundBody([sc.Cylinder(0.3, 1.0), sc.Box([1.0, 0.15, 0.15]), sc.Sphere(0.2)])
    record = json.loads(json.dumps(body_to_json(body)))
    assert [part["shape"] for part in record["parts"]] == ["cylinder", "polyhedron", "polyhedron"]
    again = body_from_json(record)
    assert isinstance(again, sc.CompoundBody) and len(again) == 3
    assert repr(again.parts[0]) == "Cylinder(radius=0.3, half_length=1)"
    assert again.parts[2].radius == 0.2
    cube = sc.Box([0.5, 0.5, 0.5])
    assert (sc.distance(again, cube, pose_b=at(0, 0, 3)).distance
            == pytest.approx(sc.distance(body, cube, pose_b=at(0, 0, 3)).distance, abs=1e-12))


@pytest.mark.parametrize("record, error, message", [
    ([1, 2], TypeError, r"record must be a JSON object"),
    ({"shape": "torus"}, ValueError, r"record\['shape'\] must be one of 'sphere'"),
    ({"shape": "cylinder", "radius": 1}, ValueError, r"lacks 'half_length'"),
    ({"shape": "sphere", "radius": 1, "colour": "red"}, ValueError, r"unknown keys 'colour'"),
    ({"shape": "sphere", "radius": "big"}, ValueError, r"record\['radius'\] must be a number"),
    ({"shape": "sphere", "radius": -1}, ValueError, r"record: radius must be a finite number"),
    ({"shape": "ellipsoid", "radii": [1, 2]}, ValueError, r"radii'\] must be a list of 3"),
    ({"shape": "box", "half_extents": [1, 1, 0]}, ValueError, r"record: half_extents\[2\] must"),
    ({"shape": "box", "half_extents": [1, 1, math.inf]}, ValueError,
     r"record\['half_extents'\]\[2\] must be a finite number"),
    ({"shape": "compound", "parts": []}, ValueError, r"non-empty list"),
    ({"shape": "compound", "parts": [{"shape": "cone", "radius": 1}]}, ValueError,
     r"record\['parts'\]\[0\] \(a cone\) lacks 'half_length'"),
    ({"shape": "polyhedron", "points": [[0, 0]]}, ValueError, r"points"),
])
def test_bad_records_name_the_key(record, error, message):
    with pytest.raises(error, match=message):
        body_from_json(record)


def nested_compound(depth: int) -> dict:
    record = {"shape": "sphere", "radius": 1}
    for _ in range(depth):
        record = {"shape": "compound", "parts": [record]}
    return record


def test_numbers_beyond_a_double_and_nested_compounds_name_the_field_and_the_limit():
    huge = 10 ** 400  # JSON's 400-digit integer: float() overflows on it
    for record, where in [
            ({"shape": "sphere", "radius": huge}, r"record\['radius'\]"),
            ({"shape": "sphere", "radius": math.inf}, r"record\['radius'\]"),
            ({"shape": "box", "half_extents": [1, huge, 1]}, r"record\['half_extents'\]\[1\]"),
            ({"shape": "polyhedron", "points": [[0, 0, 0], [1, 0, huge]]},
             r"record\['points'\]\[1\]\[2\]"),
            ({"shape": "compound", "parts": [{"shape": "sphere", "radius": 1}],
              "poses": [[[1, 0, 0, huge], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]]},
             r"record\['poses'\]\[0\]\[0\]\[3\]")]:
        with pytest.raises(ValueError, match=where + r" must be a finite number within a "
                           r"double's range \(magnitude at most 1\.798e\+308\), got "):
            body_from_json(record)
    with pytest.raises(ValueError, match="got an integer of 401 digits$"):
        body_from_json({"shape": "sphere", "radius": huge})
    # Refused at the first nested compound, however deep the nesting (3,000 exhausted the
    # recursion with a RecursionError).
    with pytest.raises(ValueError, match=r"^record\['parts'\]\[0\] is a compound; compounds do "
                                         r"not nest \(one level at most\)"):
        body_from_json(nested_compound(3000))


def test_the_cli_names_a_shape_file_too_deep_or_too_large_to_read(tmp_path, capsys):
    deep = tmp_path / "deep.json"
    # Written by hand: json.dumps recurses as deep as json.load.
    deep.write_text('{"shape": "compound", "parts": [' * 3000 + '{"shape": "sphere", "radius": 1}'
                    + "]}" * 3000)
    plain = tmp_path / "ball.json"
    plain.write_text(json.dumps({"shape": "sphere", "radius": 1}))
    assert main(["distance", str(deep), str(plain)]) == 1
    assert f"shape file '{deep}' nests deeper than Python's JSON reader follows" in (
        capsys.readouterr().err)
    large = tmp_path / "large.json"
    large.write_text('{"shape": "sphere", "radius": 1' + "0" * 400 + "}")
    assert main(["distance", str(large), str(plain)]) == 1
    assert f"{large}['radius'] must be a finite number" in capsys.readouterr().err


def test_the_cli_reads_and_writes_shape_files(tmp_path, capsys):
    a = tmp_path / "can.json"
    b = tmp_path / "plus.json"
    a.write_text(json.dumps({"shape": "cylinder", "radius": 0.5, "half_length": 1.0}))
    b.write_text(json.dumps({"shape": "compound", "parts": [
        {"shape": "ellipsoid", "radii": [0.2, 0.2, 0.6]},
        {"shape": "box", "half_extents": [0.6, 0.1, 0.1]}]}))
    assert main(["distance", str(a), str(b), "--pose-b", "2 0 0", "--json"]) == 0
    answer = json.loads(capsys.readouterr().out)
    # The bar reaches x = 1.4, the can's mantle x = 0.5.
    assert answer["distance"] == pytest.approx(0.9, abs=1e-9) and answer["certified"]
    assert answer["part_b"] == 1
    assert answer["a"]["shape"] == {"shape": "compound", "parts": [
        {"shape": "cylinder", "radius": 0.5, "half_length": 1.0}]}
    assert answer["b"]["shape"]["parts"][0] == {"shape": "ellipsoid", "radii": [0.2, 0.2, 0.6]}
    for method in ("fcl", "exact"):
        assert main(["distance", str(a), str(b), "--pose-b", "2 0 0", "--json",
                     "--method", method]) == 0
        assert json.loads(capsys.readouterr().out)["distance"] == pytest.approx(0.9, abs=1e-9)
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"shape": "cone", "radius": 0}))
    assert main(["distance", str(bad), str(a)]) == 1
    assert "lacks 'half_length'" in capsys.readouterr().err
    bad.write_text("{not json")
    assert main(["distance", str(bad), str(a)]) == 1
    assert "is not JSON" in capsys.readouterr().err


@pytest.mark.parametrize("body, inside", [
    (sc.Cylinder(0.5, 1.0), lambda p: (np.hypot(p[:, 0], p[:, 1]) <= 0.5 + 1e-12)
     & (np.abs(p[:, 2]) <= 1.0 + 1e-12)),
    (sc.Sphere(0.7), lambda p: np.linalg.norm(p, axis=1) <= 0.7 + 1e-12),
    (sc.Ellipsoid([0.3, 0.6, 0.9]),
     lambda p: ((p / [0.3, 0.6, 0.9]) ** 2).sum(axis=1) <= 1 + 1e-12),
    (sc.Capsule(0.2, 0.5), lambda p: np.hypot(np.hypot(p[:, 0], p[:, 1]),
                                              np.maximum(np.abs(p[:, 2]) - 0.5, 0)) <= 0.2 + 1e-12),
], ids=["cylinder", "sphere", "ellipsoid", "capsule"])
def test_curved_and_rounded_bodies_are_drawn_as_their_surfaces(body, inside):
    pytest.importorskip("matplotlib")
    from swarmcollide.plot import _surface, plot_body, plot_pair

    points, faces = _surface(body)
    # Points of the body, reaching its box: the drawing is the shape, not its few vertices.
    assert inside(points).all()
    np.testing.assert_allclose(points.min(axis=0), body.aabb().min, atol=0.01)
    np.testing.assert_allclose(points.max(axis=0), body.aabb().max, atol=0.01)
    assert len(faces) > 100 and faces.max() < len(points)
    figure = plot_body(body)
    assert len(figure.axes[0].collections) == 1
    figure = plot_pair(body, sc.CompoundBody([body, sc.Box([0.1, 0.1, 0.1])]), pose_b=at(3))
    assert figure.axes[0].get_title().endswith("(certified), parts 0 and 0")
