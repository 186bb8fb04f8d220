#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "conversions.hpp"
#include "queries.hpp"
#include "swarmcollide/queries/batch.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/scene/scene.hpp"

namespace swarmcollide::bindings {

namespace {

using IdArray = py::array_t<std::int64_t>;

IdArray id_array(const std::vector<BodyId>& ids) {
  IdArray out(static_cast<py::ssize_t>(ids.size()));
  auto view = out.mutable_unchecked<1>();
  for (std::size_t i = 0; i < ids.size(); ++i) view(static_cast<py::ssize_t>(i)) = ids[i];
  return out;
}

// One id or a 1-D array-like of ids.
std::vector<BodyId> to_ids(const py::handle& ids, const char* name) {
  const py::array array = py::module_::import("numpy").attr("asarray")(ids);
  const char kind = array.dtype().kind();
  // An empty list is an array of floats to NumPy, and names no body.
  if (array.ndim() == 1 && array.size() == 0) return {};
  if ((kind != 'i' && kind != 'u') || array.ndim() > 1) {
    throw py::type_error(std::string(name) + " must be an id or a 1-D array of integer ids, got " +
                         type_name(ids));
  }
  const auto integers =
      py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(array);
  std::vector<BodyId> result(static_cast<std::size_t>(integers.size()));
  for (py::ssize_t i = 0; i < integers.size(); ++i) {
    const std::int64_t id = integers.data()[i];
    if (id < 0 || id > std::numeric_limits<BodyId>::max()) {
      throw py::value_error("no body with id " + std::to_string(id) + " in the scene");
    }
    result[static_cast<std::size_t>(i)] = static_cast<BodyId>(id);
  }
  return result;
}

// `value` as one id would be read: itself unless it is an array; the item of an integer array
// holding one (as `add` returns the id of one body); nothing (a null object) for another array.
py::object id_item(const py::handle& value) {
  if (!is_array(value)) return py::reinterpret_borrow<py::object>(value);
  const auto array = py::reinterpret_borrow<py::array>(value);
  const char kind = array.dtype().kind();
  if ((kind == 'i' || kind == 'u') && array.size() == 1) return array.attr("item")();
  return py::object();
}

// One id as `name`: an integer (Python's or NumPy's), or an integer array holding one, as `add`
// returns the id of one body; TypeError for another array or type, ValueError for a negative id.
BodyId to_id(const py::handle& value, const char* name) {
  if (const py::object item = id_item(value)) return to_count(item, name, 0);
  const auto array = py::reinterpret_borrow<py::array>(value);
  throw py::type_error(std::string(name) + " must be one id (an integer, or an array of one id as "
                       "add returns for one body), got an array of " +
                       std::to_string(array.size()) + " " +
                       std::string(py::str(array.dtype())) + " values; pass one of its items");
}

// Pairs of ids: one pair (a, b) or an (m, 2) array-like.
std::vector<std::pair<BodyId, BodyId>> to_id_pairs(const py::handle& pairs, const char* name) {
  const py::array array = py::module_::import("numpy").attr("asarray")(pairs);
  const bool one = array.ndim() == 1 && array.shape(0) == 2;
  if (!one && !(array.ndim() == 2 && array.shape(1) == 2)) {
    throw py::value_error(std::string(name) + " must be a pair of ids or an (m, 2) array of them");
  }
  const std::vector<BodyId> flat = to_ids(array.attr("reshape")(-1), name);
  std::vector<std::pair<BodyId, BodyId>> result;
  for (std::size_t k = 0; k + 1 < flat.size(); k += 2) result.emplace_back(flat[k], flat[k + 1]);
  return result;
}

// One body (a polyhedron, (n, 3) points or a mesh such as a trimesh.Trimesh: its vertices) or
// many (a sequence of them, or an (m, n, 3) array).
std::vector<ConvexPolyhedron> to_bodies(const py::handle& given) {
  const py::object bodies = points_of(given);
  std::vector<ConvexPolyhedron> result;
  if (py::isinstance<ConvexPolyhedron>(bodies)) {
    result.push_back(bodies.cast<ConvexPolyhedron>());
    return result;
  }
  if (py::isinstance<py::str>(bodies) || !py::isinstance<py::iterable>(bodies)) {
    throw py::type_error(
        "bodies must be a polyhedron, (n, 3) points, a sequence of them or an "
        "(m, n, 3) array, got " +
        type_name(bodies));
  }
  refuse_masked(bodies, "bodies");
  py::object array;
  try {
    array = py::module_::import("numpy").attr("asarray")(bodies);
  } catch (py::error_already_set&) {
    array = py::none();  // ragged: a sequence of bodies
  }
  if (!array.is_none()) {
    const py::array a = array.cast<py::array>();
    const char kind = a.dtype().kind();
    const bool real = kind == 'f' || kind == 'i' || kind == 'u';
    if (real && a.ndim() == 2) {
      result.push_back(BodyArgument(bodies, "bodies").get());
      return result;
    }
    if (real && a.ndim() == 3) {
      if (a.shape(2) != 3 || a.shape(1) == 0) {
        throw py::value_error("bodies must have shape (m, n, 3) with n >= 1");
      }
      const auto stack = py::array_t<Scalar, py::array::c_style | py::array::forcecast>::ensure(a);
      for (py::ssize_t i = 0; i < stack.shape(0); ++i) {
        try {
          result.emplace_back(Eigen::Map<const VertexMatrix>(stack.data() + i * stack.shape(1) * 3,
                                                             stack.shape(1), 3));
        } catch (const std::invalid_argument& error) {
          throw py::value_error("bodies[" + std::to_string(i) + "]: " + error.what());
        }
      }
      return result;
    }
  }
  std::size_t index = 0;
  for (const py::handle body : bodies) {
    const std::string item = "bodies[" + std::to_string(index++) + "]";
    result.push_back(BodyArgument(body, item.c_str()).get());
  }
  return result;
}

std::uint32_t to_bits(const py::handle& value, const char* name) {
  if (is_array(value)) {
    throw py::type_error(std::string(name) +
                         " must be one integer bit mask (it applies to every body of the call), "
                         "got an array of shape " +
                         std::string(py::str(value.attr("shape"))));
  }
  if (PyBool_Check(value.ptr()) || !PyIndex_Check(value.ptr())) {
    throw py::type_error(std::string(name) + " must be an integer bit mask, got " +
                         type_name(value));
  }
  const py::int_ bits = py::reinterpret_steal<py::int_>(PyNumber_Index(value.ptr()));
  if (bits < py::int_(0) || bits > py::int_(0xFFFFFFFFu)) {
    throw py::value_error(std::string(name) + " must be a 32-bit mask in [0, 2**32), got " +
                          std::string(py::str(bits)));
  }
  return bits.cast<std::uint32_t>();
}

std::string result_repr(const char* type, const SceneResult& r) {
  std::ostringstream out;
  out.precision(6);
  const Eigen::Index m = r.size();
  out << type << "(" << m << (m == 1 ? " pair" : " pairs");
  if (m > 0) {
    out << ", " << r.certified.count() << " certified, distances " << r.distance.minCoeff()
        << " to " << r.distance.maxCoeff();
  }
  return out.str();
}

// Poses as an (m, 4, 4) array of transforms.
py::array_t<Scalar> transforms(const std::vector<Pose>& poses) {
  py::array_t<Scalar> out({static_cast<py::ssize_t>(poses.size()), py::ssize_t{4}, py::ssize_t{4}});
  auto view = out.mutable_unchecked<3>();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const auto k = static_cast<py::ssize_t>(i);
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) {
        view(k, r, c) = r == 3 ? (c == 3 ? 1.0 : 0.0)
                               : (c == 3 ? poses[i].translation(r) : poses[i].rotation(r, c));
      }
    }
  }
  return out;
}

using PairIds = Eigen::Matrix<std::int64_t, Eigen::Dynamic, 2, Eigen::RowMajor>;

// What is inconsistent in a SceneResult rebuilt from its state: a column of another length.
std::string scene_result_error(const SceneResult& r) {
  return unequal_lengths({{"pairs", r.pairs.rows()},
                          {"distance", r.distance.rows()},
                          {"lower_bound", r.lower_bound.rows()},
                          {"point_a", r.point_a.rows()},
                          {"point_b", r.point_b.rows()},
                          {"normal", r.normal.rows()},
                          {"certified", r.certified.rows()}});
}

// The same for a ContactResult, whose contact points are rows of their own.
std::string contact_result_error(const ContactResult& r) {
  std::string wrong = scene_result_error(r);
  if (wrong.empty()) {
    wrong = unequal_lengths(
        {{"pairs", r.pairs.rows()}, {"counts", r.counts.rows()}, {"offsets", r.offsets.rows()}});
  }
  if (wrong.empty()) {
    wrong = unequal_lengths({{"points", r.points.rows()}, {"point_pair", r.point_pair.rows()}});
  }
  return wrong;
}

py::tuple sweep_state(const SweepResult& r) {
  return py::make_tuple(kStateVersion, r.pairs, r.t_lower, r.t_upper, transforms(r.pose_a),
                        transforms(r.pose_b), r.distance, r.point_a, r.point_b, r.normal,
                        r.certified, r.iterations);
}

SweepResult sweep_from_state(const py::object& state) {
  PickledState items(state, "SweepResult", 11);
  SweepResult r;
  r.pairs = items.next<PairIds>("pairs");
  const auto rows = static_cast<std::size_t>(r.pairs.rows());
  const auto poses = [rows](const char* name) {
    return [rows, name](const py::handle& item) { return to_poses(item, rows, name); };
  };
  r.t_lower = items.next<VectorX>("t_lower");
  r.t_upper = items.next<VectorX>("t_upper");
  r.pose_a = items.next("pose_a", poses("pose_a"));
  r.pose_b = items.next("pose_b", poses("pose_b"));
  r.distance = items.next<VectorX>("distance");
  r.point_a = items.next<VertexMatrix>("point_a");
  r.point_b = items.next<VertexMatrix>("point_b");
  r.normal = items.next<VertexMatrix>("normal");
  r.certified = items.next<Eigen::Array<bool, Eigen::Dynamic, 1>>("certified");
  r.iterations = items.next<Eigen::Array<int, Eigen::Dynamic, 1>>("iterations");
  const std::string wrong = unequal_lengths(
      {{"pairs", r.pairs.rows()}, {"t_lower", r.t_lower.rows()}, {"t_upper", r.t_upper.rows()},
       {"distance", r.distance.rows()}, {"point_a", r.point_a.rows()},
       {"point_b", r.point_b.rows()}, {"normal", r.normal.rows()},
       {"certified", r.certified.rows()}, {"iterations", r.iterations.rows()}});
  if (!wrong.empty()) throw items.error(wrong);
  return r;
}

// A scene as pickled: its options, then its bodies by column (ids, bodies in their own frames,
// poses, groups, masks), the excluded pairs and the next id. The proofs cached for warm starts are
// left out: answers do not depend on them beyond the tolerance (docs/scene.md).
py::tuple scene_state(const Scene& scene) {
  const SceneOptions& options = scene.options();
  const std::vector<BodyId> ids = scene.ids();
  py::list bodies, groups, masks;
  std::vector<Pose> poses;
  for (BodyId id : ids) {
    const CompoundBody* compound = scene.compound(id);
    bodies.append(compound ? py::cast(*compound) : typed_body(scene.body(id)));
    poses.push_back(scene.pose(id));
    groups.append(scene.filter(id).group);
    masks.append(scene.filter(id).mask);
  }
  std::vector<std::pair<BodyId, BodyId>> excluded = scene.excluded();
  PairIds excluded_pairs(static_cast<Eigen::Index>(excluded.size()), 2);
  for (std::size_t k = 0; k < excluded.size(); ++k) {
    excluded_pairs.row(static_cast<Eigen::Index>(k)) << excluded[k].first, excluded[k].second;
  }
  return py::tuple(py::make_tuple(kStateVersion) + options_state(options.query) +
                   py::make_tuple(broadphase_name(options.broadphase), options.threads,
                                  options.warm_start, options.escalate, id_array(ids), bodies,
                                  transforms(poses), groups, masks, excluded_pairs,
                                  scene.next_id()));
}

Scene scene_from_state(const py::object& state) {
  PickledState items(state, "Scene", 15);
  SceneOptions options;
  options.query = options_from_state(items);
  options.broadphase = items.next("broadphase", [](const py::handle& item) {
    return broadphase_from_name(to_name(item, "broadphase"));
  });
  options.threads = items.next<int>("threads");
  options.warm_start = items.next<bool>("warm_start");
  options.escalate = items.next<bool>("escalate");
  const std::vector<BodyId> ids =
      items.next("ids", [](const py::handle& item) { return to_ids(item, "ids"); });
  const py::list bodies = items.next("bodies", [](const py::handle& item) {
    return py::list(py::reinterpret_borrow<py::object>(item));
  });
  const std::vector<Pose> poses = items.next("poses", [&ids](const py::handle& item) {
    return to_poses(item, ids.size(), "poses");
  });
  const auto groups = items.next<std::vector<std::uint32_t>>("groups");
  const auto masks = items.next<std::vector<std::uint32_t>>("masks");
  const auto excluded =
      items.next("excluded", [](const py::handle& item) { return to_id_pairs(item, "excluded"); });
  const auto next_id = items.next<BodyId>("next_id");
  const std::string wrong = unequal_lengths(
      {{"ids", static_cast<Eigen::Index>(ids.size())},
       {"bodies", static_cast<Eigen::Index>(bodies.size())},
       {"poses", static_cast<Eigen::Index>(poses.size())},
       {"groups", static_cast<Eigen::Index>(groups.size())},
       {"masks", static_cast<Eigen::Index>(masks.size())}});
  if (!wrong.empty()) throw items.error(wrong);
  return items.build([&] {
    Scene scene(options);
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const std::string item = "bodies[" + std::to_string(i) + "]";
      const BodyFilter filter{groups[i], masks[i]};
      scene.skip_ids(ids[i]);
      if (is_compound(bodies[i])) {
        scene.add(bodies[i].cast<const CompoundBody&>(), poses[i], filter);
      } else {
        scene.add(BodyArgument(bodies[i], item.c_str()).get(), poses[i], filter);
      }
    }
    scene.exclude(excluded);
    scene.skip_ids(next_id);
    return scene;
  });
}

std::string sweep_repr(const SweepResult& r) {
  std::ostringstream out;
  out.precision(6);
  const Eigen::Index m = r.size();
  out << "SweepResult(" << m << (m == 1 ? " pair" : " pairs");
  if (m > 0) {
    out << ", " << r.certified.count() << " certified, first contact at t in [" << r.t_lower.minCoeff()
        << ", " << r.t_upper.minCoeff() << "]";
  }
  return out.str() + ")";
}

std::string stats_repr(const SceneStats& s) {
  std::ostringstream out;
  out << "SceneStats(candidates=" << s.candidates << ", screened=" << s.screened
      << ", warm_bounded=" << s.warm_bounded << ", warm_rejected=" << s.warm_rejected
      << ", warm_proven=" << s.warm_proven << ", solved=" << s.solved
      << ", escalations=" << s.escalations << ", certified=" << s.certified
      << ", cached_pairs=" << s.cached_pairs << ", cache_bytes=" << s.cache_bytes << ")";
  return out.str();
}

constexpr const char* kSceneDoc = R"doc(
Many convex bodies, each defined once in its own frame and placed by a pose, and the queries
about all their pairs.

FCL's broadphase manager, given tight boxes from the bodies' support functions, collects the
candidate pairs; the narrowphase (``method``, certified as ``Query.collision`` is) answers them
in C++ threads without the GIL. With ``warm_start``, each candidate pair keeps what the last
query proved (a separating direction and its support points in the bodies' own frames, or a
simplex enclosing the origin) and the next query tries it first; a pair's proof is dropped when
the broadphase stops returning it. Without, every answer is computed from scratch and depends only
on the bodies, their poses and ``seed``.

Parameters
----------
method : str
    The narrowphase's method (see ``METHODS``); ``"dual"`` by default.
broadphase : str
    FCL's manager: ``"dynamic_aabb_tree"`` (default), ``"sap"``, ``"ssap"``,
    ``"interval_tree"``, ``"spatial_hashing"`` or ``"brute_force"`` (``BROADPHASES``). Answers do
    not depend on it.
threads : int, optional
    Narrowphase threads, the caller's included; None uses one per hardware thread. The others
    are woken once a query's candidates left would take the caller over about 200 us alone.
tolerance : float
    Precision and contact threshold, relative to each pair's size (at most 0.1).
seed : int
    Pair ``(i, j)`` is seeded with ``pair_seed(seed, (i << 32) | j)``.
warm_start : bool
    Start each query from what the last one proved.
escalate : bool
    Hand verdicts the method cannot prove to the exact method.
**parameters
    Solver parameters of ``method``.

Examples
--------
>>> import numpy as np, swarmcollide as sc
>>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
>>> scene = sc.Scene()
>>> scene.add(np.stack([cube, cube, cube]), poses=np.stack([np.eye(4)] * 3)).tolist()
[0, 1, 2]
>>> moved = np.eye(4)
>>> moved[:3, 3] = [0.5, 0, 0]
>>> scene.set_poses(1, moved)
>>> moved[:3, 3] = [3, 0, 0]
>>> scene.set_poses(2, moved)
>>> scene.colliding_pairs().pairs.tolist()
[[0, 1]]
>>> r = scene.pairs_within(1.6)
>>> r.pairs.tolist(), r.distance.round(9).tolist()
([[0, 1], [1, 2]], [0.0, 1.5])
>>> c = scene.contacts()
>>> c.normal.round(9).tolist(), c.counts.tolist()
([[1.0, 0.0, 0.0]], [4])
)doc";

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<SceneResult>(m, "SceneResult", R"doc(
Pairs a Scene query found, one row per pair, as NumPy arrays.

Row k is the pair ``(A, B) = pairs[k]``; vectors point from A to B, and
``lower_bound[k] <= distance between A and B <= distance[k]``.

Attributes
----------
pairs : numpy.ndarray of int64, shape (m, 2)
    Ids of A and B.
distance, lower_bound : numpy.ndarray, shape (m,)
    Upper bound (achieved by the witnesses) and certified lower bound on the distance.
point_a, point_b : numpy.ndarray, shape (m, 3)
    Witness points on A and B.
normal : numpy.ndarray, shape (m, 3)
    Unit direction from A to B certifying ``lower_bound`` (zero where overlap was proven by a
    common point; ``contacts`` gives those their contact normals).
certified : numpy.ndarray of bool, shape (m,)
    The pair's membership (and value, for distances and contacts) is proven.
)doc")
      .def_readonly("pairs", &SceneResult::pairs)
      .def_readonly("distance", &SceneResult::distance)
      .def_readonly("lower_bound", &SceneResult::lower_bound)
      .def_readonly("point_a", &SceneResult::point_a)
      .def_readonly("point_b", &SceneResult::point_b)
      .def_readonly("normal", &SceneResult::normal)
      .def_readonly("certified", &SceneResult::certified)
      .def("__len__", &SceneResult::size)
      .def(pickle_fields<SceneResult>(
          "SceneResult", &scene_result_error, field("pairs", &SceneResult::pairs),
          field("distance", &SceneResult::distance),
          field("lower_bound", &SceneResult::lower_bound), field("point_a", &SceneResult::point_a),
          field("point_b", &SceneResult::point_b), field("normal", &SceneResult::normal),
          field("certified", &SceneResult::certified)))
      .def("__repr__", [](const SceneResult& r) { return result_repr("SceneResult", r) + ")"; });

  py::class_<ContactResult, SceneResult>(m, "ContactResult", R"doc(
The contacts of every pair in contact: a SceneResult whose ``distance`` is the certified signed
distance (negative: the penetration depth) and ``normal`` the contact normal from A to B, with
each pair's contact points.

Attributes
----------
counts : numpy.ndarray of int, shape (m,)
    Contact points of each pair (1 to ``max_points``).
points : numpy.ndarray, shape (p, 3)
    All contact points, pair by pair, halfway between the two supporting planes.
point_pair : numpy.ndarray of int64, shape (p,)
    Row in ``pairs`` of each contact point.
offsets : numpy.ndarray of int64, shape (m,)
    Index in ``points`` of each pair's first contact point.
)doc")
      .def_readonly("counts", &ContactResult::counts)
      .def_readonly("points", &ContactResult::points)
      .def_readonly("point_pair", &ContactResult::point_pair)
      .def_readonly("offsets", &ContactResult::offsets)
      .def(pickle_fields<ContactResult>(
          "ContactResult", &contact_result_error, field("pairs", &SceneResult::pairs),
          field("distance", &SceneResult::distance),
          field("lower_bound", &SceneResult::lower_bound), field("point_a", &SceneResult::point_a),
          field("point_b", &SceneResult::point_b), field("normal", &SceneResult::normal),
          field("certified", &SceneResult::certified), field("counts", &ContactResult::counts),
          field("points", &ContactResult::points), field("point_pair", &ContactResult::point_pair),
          field("offsets", &ContactResult::offsets)))
      .def("__repr__", [](const ContactResult& r) {
        return result_repr("ContactResult", r) + ", " + std::to_string(r.points.rows()) +
               " contact points)";
      });

  py::class_<SweepResult>(m, "SweepResult", R"doc(
The pairs that touch during ``Scene.sweep``, one row per pair in increasing id order, as NumPy
arrays: row k is ``time_of_impact`` of bodies ``(A, B) = pairs[k]`` over the sweep's motions
(time 0 at the poses before the sweep, 1 at the given ones).

Attributes
----------
pairs : numpy.ndarray of int64, shape (m, 2)
    Ids of A and B, the smaller first.
t_lower, t_upper : numpy.ndarray, shape (m,)
    The first contact's bracket: the pair is proven apart before ``t_lower`` and within
    ``tolerance x size`` at ``t_upper`` (``t_upper - t_lower <= time_tolerance``).
pose_a, pose_b : numpy.ndarray, shape (m, 4, 4)
    The bodies' poses at ``t_upper``.
distance : numpy.ndarray, shape (m,)
    Signed distance at ``t_upper`` (its upper bound).
point_a, point_b, normal : numpy.ndarray, shape (m, 3)
    Witness points on A and B and the unit contact normal from A to B at ``t_upper``.
certified : numpy.ndarray of bool, shape (m,)
    The bracket is proven; uncertified rows err on the side of contact.
iterations : numpy.ndarray of int, shape (m,)
    Distance queries each pair ran.
)doc")
      .def_readonly("pairs", &SweepResult::pairs)
      .def_readonly("t_lower", &SweepResult::t_lower)
      .def_readonly("t_upper", &SweepResult::t_upper)
      .def_property_readonly("pose_a", [](const SweepResult& r) { return transforms(r.pose_a); })
      .def_property_readonly("pose_b", [](const SweepResult& r) { return transforms(r.pose_b); })
      .def_readonly("distance", &SweepResult::distance)
      .def_readonly("point_a", &SweepResult::point_a)
      .def_readonly("point_b", &SweepResult::point_b)
      .def_readonly("normal", &SweepResult::normal)
      .def_readonly("certified", &SweepResult::certified)
      .def_readonly("iterations", &SweepResult::iterations)
      .def("__len__", &SweepResult::size)
      .def(py::pickle(&sweep_state, &sweep_from_state))
      .def("__repr__", &sweep_repr);

  py::class_<SceneStats>(m, "SceneStats", R"doc(
What the last Scene query did with its candidate pairs.

Attributes
----------
candidates : int
    Pairs that passed the filters whose boxes, padded for the query, overlap.
screened : int
    Found apart along the line between their centres, before any solver.
warm_bounded : int
    Found apart by a cached lower bound on their distance less how far the bodies have moved
    since: no support evaluated.
warm_rejected, warm_proven : int
    Settled by re-evaluating a cached separating direction or enclosing simplex (or one that
    Wolfe's algorithm found from it in a step or two).
solved : int
    Handed to the method's solver.
escalations : int
    Verdicts the method could not prove, handed to the exact method.
certified : int
    Candidates whose answer is proven.
cached_pairs, cache_bytes : int
    Pairs with a cached proof after the query, and the bytes their storage takes: a 64-byte
    record for every pair whose broadphase boxes (padded boxes with margins for motion)
    overlap, and for a pair in contact the last expanding polytope's surface (at most 16
    corners). cache_bytes is summed when ``scene.stats`` is read (the storage then), not by
    every query: the sum reads every pair's record.
)doc")
      .def_readonly("candidates", &SceneStats::candidates)
      .def_readonly("screened", &SceneStats::screened)
      .def_readonly("warm_bounded", &SceneStats::warm_bounded)
      .def_readonly("warm_rejected", &SceneStats::warm_rejected)
      .def_readonly("warm_proven", &SceneStats::warm_proven)
      .def_readonly("solved", &SceneStats::solved)
      .def_readonly("escalations", &SceneStats::escalations)
      .def_readonly("certified", &SceneStats::certified)
      .def_readonly("cached_pairs", &SceneStats::cached_pairs)
      .def_readonly("cache_bytes", &SceneStats::cache_bytes)
      .def(pickle_fields<SceneStats>(
          "SceneStats", any_values, field("candidates", &SceneStats::candidates),
          field("screened", &SceneStats::screened),
          field("warm_bounded", &SceneStats::warm_bounded),
          field("warm_rejected", &SceneStats::warm_rejected),
          field("warm_proven", &SceneStats::warm_proven), field("solved", &SceneStats::solved),
          field("escalations", &SceneStats::escalations),
          field("certified", &SceneStats::certified),
          field("cached_pairs", &SceneStats::cached_pairs),
          field("cache_bytes", &SceneStats::cache_bytes)))
      .def("__repr__", &stats_repr);

  m.def("broadphases", &broadphase_names, "The names of the broadphase managers a Scene can use.");

  py::class_<Scene>(m, "Scene", kSceneDoc)
      .def(py::init([](const py::object& method, const py::object& broadphase,
                       const py::object& threads, const py::object& tolerance,
                       const py::object& seed, const Given<bool>& warm_start,
                       const Given<bool>& escalate, const py::kwargs& parameters) {
             SceneOptions options;
             options.query = make_options(method, tolerance, seed, parameters);
             options.broadphase = broadphase_from_name(to_name(broadphase, "broadphase"));
             if (!threads.is_none()) options.threads = thread_count(threads);
             options.warm_start = to_bool(warm_start.value, "warm_start");
             options.escalate = to_bool(escalate.value, "escalate");
             return Scene(options);
           }),
           py::arg("method") = "dual", py::arg("broadphase") = "dynamic_aabb_tree",
           py::arg("threads") = py::none(), py::arg("tolerance") = kDefaultTolerance,
           py::arg("seed") = 0, py::arg("warm_start") = true, py::arg("escalate") = true)
      .def(
          "add",
          [](Scene& scene, const py::handle& bodies, const py::handle& poses,
             const py::handle& group, const py::handle& mask) {
            const BodyFilter filter{to_bits(group, "group"), to_bits(mask, "mask")};
            if (is_compound(bodies) || holds_compound(bodies)) {
              // Each in turn, convex or compound, so that ids follow the given order.
              const py::sequence list = is_compound(bodies)
                                            ? py::sequence(py::make_tuple(bodies))
                                            : py::reinterpret_borrow<py::sequence>(bodies);
              const std::vector<Pose> placed = to_poses(poses, list.size(), "poses");
              std::vector<BodyId> ids;
              for (std::size_t i = 0; i < list.size(); ++i) {
                const Pose pose = placed.empty() ? Pose{} : placed[i];
                if (is_compound(list[i])) {
                  const CompoundBody body = list[i].cast<CompoundBody>();
                  py::gil_scoped_release release;
                  ids.push_back(scene.add(body, pose, filter));
                } else {
                  const std::string item = "bodies[" + std::to_string(i) + "]";
                  const ConvexPolyhedron body = BodyArgument(list[i], item.c_str()).get();
                  py::gil_scoped_release release;
                  ids.push_back(scene.add(body, pose, filter));
                }
              }
              return id_array(ids);
            }
            std::vector<ConvexPolyhedron> list = to_bodies(bodies);
            const std::vector<Pose> placed = to_poses(poses, list.size(), "poses");
            std::vector<BodyId> ids;
            {
              py::gil_scoped_release release;
              ids = scene.add(std::move(list), placed, filter);
            }
            return id_array(ids);
          },
          py::arg("bodies"), py::arg("poses") = py::none(), py::arg("group") = 1,
          py::arg("mask") = 0xFFFFFFFFu, R"doc(
Add one body (a ConvexPolyhedron, ``(n, 3)`` points or a CompoundBody) or many (a sequence of
them or an ``(m, n, 3)`` array) at ``poses``; return their ids (never reused).

A compound body is boxed and first screened by its envelope (the hull of its parts); pairs the
envelopes do not settle are answered by the compound queries (branch and bound over the parts,
certified for them), and its contacts are found between the deepest pair of parts.

``poses`` is None (the identity), an ``(m, 4, 4)`` array of rigid transforms, a pair
``(rotations (m, 3, 3), translations (m, 3))`` or a list of m poses (each as ``distance`` takes
it); one body also takes a single ``(4, 4)`` transform.
Bodies A and B are paired when ``A.group & B.mask`` and ``B.group & A.mask`` are both nonzero.
)doc")
      .def(
          "set_poses",
          [](Scene& scene, const py::handle& ids, const py::handle& poses) {
            const std::vector<BodyId> which = to_ids(ids, "ids");
            // No ids and no poses (None or empty) move nothing.
            if (which.empty() &&
                (poses.is_none() ||
                 py::module_::import("numpy").attr("size")(poses).cast<py::ssize_t>() == 0)) {
              return;
            }
            const std::vector<Pose> placed = to_poses(poses, which.size(), "poses");
            if (placed.empty()) {
              throw py::value_error("poses must hold one pose per id (got None for " +
                                    std::to_string(which.size()) + " ids)");
            }
            py::gil_scoped_release release;
            scene.set_poses(which, placed);
          },
          py::arg("ids"), py::arg("poses"),
          "Move bodies (one id or an array of ids, each at most once) to ``poses`` (as for "
          "``add``); their hulls are never recomputed.")
      .def(
          "sweep",
          [](Scene& scene, const py::handle& ids, const py::handle& poses, const py::handle& motion,
             const py::handle& time_tolerance, const py::handle& max_iterations) {
            const std::vector<BodyId> which = to_ids(ids, "ids");
            SweepOptions options;
            options.motion = to_motion_kind(motion);
            options.time_tolerance = to_real(time_tolerance, "time_tolerance");
            options.max_iterations = to_count(max_iterations, "max_iterations", 1);
            std::vector<Pose> placed;
            if (!which.empty() ||
                !(poses.is_none() ||
                  py::module_::import("numpy").attr("size")(poses).cast<py::ssize_t>() == 0)) {
              placed = to_poses(poses, which.size(), "poses");
              if (placed.empty()) {
                throw py::value_error("poses must hold one pose per id (got None for " +
                                      std::to_string(which.size()) + " ids)");
              }
            }
            py::gil_scoped_release release;
            return scene.sweep(which, placed, options);
          },
          py::arg("ids"), py::arg("poses"), py::kw_only(), py::arg("motion") = "linear",
          py::arg("time_tolerance") = kDefaultTimeTolerance,
          py::arg("max_iterations") = kDefaultMotionIterations, R"doc(
Move bodies from their poses to ``poses``, reporting every pair that touches on the way.

Parameters
----------
ids : int or array_like of int
    The bodies that move; the others stay still.
poses : array_like
    Their end poses, as ``set_poses`` takes them.
motion : str
    ``"linear"`` (default): each origin moves on the straight segment while the body turns at a
    constant rate about a fixed axis through it; ``"screw"``: the pose follows
    ``G(t) = G0 exp(t xi)``, xi the twist of ``G0^-1 G1`` (see ``time_of_impact``).
time_tolerance : float
    Largest width of a first contact's bracket, as a fraction of the motion, in (0, 1].
max_iterations : int
    Distance queries at most per pair; past them the pair is reported uncertified.

Returns
-------
SweepResult
    Every pair with at least one moving body that comes within the tolerance of each other
    during the motion, with its first contact bracketed (``time_of_impact`` on the pair, seeded
    as the scene seeds its queries). Candidates are the pairs the scene's filters and exclusions
    allow whose swept boxes (proven to hold each body over its whole motion) overlap. Pairs of
    two still bodies are not reported: ``colliding_pairs`` answers them.

The bodies are left at ``poses`` whatever is found (``set_poses`` puts them back at the poses a
row gives). Raises ValueError, moving nothing, for an unknown or repeated id, a pose that is not
rigid or holds a NaN, lengths that differ, a ``time_tolerance`` outside (0, 1] or a method without
signed distances.

Examples
--------
>>> import numpy as np, swarmcollide as sc
>>> scene = sc.Scene(method="exact")
>>> cube, plate = scene.add([sc.Box([0.5, 0.5, 0.5]), sc.Box([5e-4, 5, 5])])
>>> start, end = np.eye(4), np.eye(4)
>>> start[0, 3], end[0, 3] = -10, 10
>>> scene.set_poses(cube, start)
>>> r = scene.sweep(cube, end)               # through the plate in one step
>>> r.pairs.tolist(), r.certified.tolist(), (r.t_upper * 20 - 10).round(6).tolist()
([[0, 1]], [True], [-0.5005])
>>> float(scene.pose(cube)[0, 3])
10.0
)doc")
      .def(
          "remove", [](Scene& scene, const py::handle& ids) { scene.remove(to_ids(ids, "ids")); },
          py::arg("ids"), "Remove bodies, with every cached proof and exclusion concerning them.")
      .def(
          "set_filter",
          [](Scene& scene, const py::handle& ids, const py::handle& group, const py::handle& mask) {
            scene.set_filter(to_ids(ids, "ids"), {to_bits(group, "group"), to_bits(mask, "mask")});
          },
          py::arg("ids"), py::arg("group") = 1, py::arg("mask") = 0xFFFFFFFFu,
          "Set the group and mask of bodies (see ``add``).")
      .def(
          "exclude",
          [](Scene& scene, const py::handle& pairs) { scene.exclude(to_id_pairs(pairs, "pairs")); },
          py::arg("pairs"), "Never pair the bodies of each pair (one pair or an (m, 2) array).")
      .def(
          "include",
          [](Scene& scene, const py::handle& pairs) { scene.include(to_id_pairs(pairs, "pairs")); },
          py::arg("pairs"), "Pair again the bodies of excluded pairs.")
      .def("colliding_pairs", &Scene::colliding_pairs, py::call_guard<py::gil_scoped_release>(),
           "Every pair in contact (within the tolerance of each other), certified.")
      .def(
          "pairs_within",
          [](Scene& scene, const py::handle& distance) {
            const Scalar threshold = to_real(distance, "distance");
            py::gil_scoped_release release;
            return scene.pairs_within(threshold);
          },
          py::arg("distance"),
          "Every pair whose distance is at most ``distance`` (up to the tolerance), with its "
           "distance to the tolerance.")
      .def("min_distance", &Scene::min_distance, py::call_guard<py::gil_scoped_release>(),
           "The pair at the smallest distance (one row; none for fewer than two pairable bodies).")
      .def(
          "nearest",
          [](Scene& scene, const py::handle& ids, const py::handle& k) {
            const std::vector<BodyId> which = to_ids(ids, "ids");
            const int count = to_count(k, "k", 1);
            py::gil_scoped_release release;
            return scene.nearest(which, count);
          },
          py::arg("ids"), py::arg("k") = 1,
          "For each of ``ids``, its ``k`` nearest bodies, nearest first: rows ``(id, other)``.")
      .def(
          "contacts",
          [](Scene& scene, const py::handle& max_points) {
            const int most = to_count(max_points, "max_points", 1);
            py::gil_scoped_release release;
            return scene.contacts(most);
          },
          py::arg("max_points") = 4, R"doc(
Every pair in contact with its certified signed distance, contact normal (from A to B) and up to
``max_points`` contact points, from clipping the two supporting features along the normal
against each other: a box resting on a face gives its four corners.
)doc")
      .def_property_readonly("stats", &Scene::stats, "What the last query did (a SceneStats).")
      .def_property_readonly(
          "ids", [](const Scene& s) { return id_array(s.ids()); }, "The bodies' ids, ascending.")
      .def("__len__", &Scene::size)
      .def("__contains__",
           [](const Scene& s, const py::object& given) {
             // An id as body and pose take it (an array of one id too); anything else, an
             // array of several ids included, is no body of the scene.
             const py::object id = id_item(given);
             if (!id) return false;
             return PyIndex_Check(id.ptr()) && !PyBool_Check(id.ptr()) &&
                    py::int_(id) >= py::int_(0) &&
                    py::int_(id) <= py::int_(std::numeric_limits<BodyId>::max()) &&
                    s.contains(py::int_(id).cast<BodyId>());
           })
      .def(
          "body",
          [](const Scene& s, const Given<BodyId>& given) -> py::object {
            const BodyId id = to_id(given.value, "id");
            if (const CompoundBody* compound = s.compound(id)) return py::cast(*compound);
            return added_body(s.body(id));
          },
          py::arg("id"),
          "The body with this id (an integer or the array of one id ``add`` returns for one "
          "body), in its own frame: a ConvexPolyhedron (a Sphere, Capsule, Box, "
          "Cylinder, Cone or Ellipsoid as its own class) or a CompoundBody (the core's, without a "
          "decomposition record).")
      .def(
          "pose",
          [](const Scene& s, const Given<BodyId>& id) {
            return homogeneous(s.pose(to_id(id.value, "id")));
          },
          py::arg("id"),
          "The body's pose as a (4, 4) homogeneous transform; ``id`` an integer or the array "
          "of one id ``add`` returns for one body.")
      .def_property_readonly("method",
                             [](const Scene& s) { return method_name(s.options().query.method); })
      .def_property_readonly("broadphase",
                             [](const Scene& s) { return broadphase_name(s.options().broadphase); })
      .def_property_readonly("tolerance",
                             [](const Scene& s) { return s.options().query.tolerance; })
      .def_property_readonly("seed", [](const Scene& s) { return s.options().query.seed; })
      .def_property_readonly("warm_start", [](const Scene& s) { return s.options().warm_start; })
      .def(py::pickle(&scene_state, &scene_from_state))
      .def("__repr__", [](const Scene& s) {
        const std::size_t n = s.size();
        return "Scene(" + std::to_string(n) + (n == 1 ? " body" : " bodies") + ", method='" +
               method_name(s.options().query.method) + "', broadphase='" +
               broadphase_name(s.options().broadphase) +
               "', warm_start=" + (s.options().warm_start ? "True" : "False") + ")";
      });
}

}  // namespace swarmcollide::bindings
