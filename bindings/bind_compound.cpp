#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/typing.h>

#include <sstream>
#include <string>
#include <vector>

#include "conversions.hpp"
#include "queries.hpp"
#include "swarmcollide/geometry/compound_body.hpp"
#include "swarmcollide/queries/compound_result.hpp"
#include "swarmcollide/queries/methods.hpp"

namespace swarmcollide::bindings {

namespace {

// Parts from a sequence of polyhedra or (n, 3) array-likes.
std::vector<ConvexPolyhedron> to_parts(const py::handle& parts) {
  if (py::isinstance<py::str>(parts) || !py::isinstance<py::iterable>(parts) ||
      py::isinstance<ConvexPolyhedron>(parts)) {
    // A mesh given whole is one body; its parts come from a decomposition.
    throw py::type_error(
        "parts must be a sequence of ConvexPolyhedron or of (n, 3) point arrays (or meshes), got " +
        type_name(parts) +
        (py::hasattr(parts, "vertices") ? "; CompoundBody.from_mesh decomposes a mesh into parts"
                                        : ""));
  }
  std::vector<ConvexPolyhedron> result;
  std::size_t index = 0;
  for (const py::handle part : parts) {
    const std::string item = "parts[" + std::to_string(index++) + "]";
    result.push_back(BodyArgument(part, item.c_str()).get());
  }
  if (result.empty()) {
    throw py::value_error("parts is empty: a compound body needs at least one convex part");
  }
  return result;
}

// The parts' poses as a (count, 4, 4) array of homogeneous transforms.
py::array_t<Scalar> pose_matrices(const CompoundBody& body) {
  const std::vector<Pose> poses = body.part_poses();
  py::array_t<Scalar> out({static_cast<py::ssize_t>(poses.size()), py::ssize_t{4}, py::ssize_t{4}});
  auto m = out.mutable_unchecked<3>();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) {
        m(i, r, c) = r < 3 ? (c < 3 ? poses[i].rotation(r, c) : poses[i].translation(r))
                           : (c == 3 ? 1 : 0);
      }
    }
  }
  return out;
}

py::tuple compound_state(const py::object& self) {
  const auto& body = self.cast<const CompoundBody&>();
  py::list parts;
  for (const ConvexPolyhedron& part : body.given_parts()) parts.append(typed_body(part));
  // given_parts() is parts() itself for a body built without poses, which is rebuilt so: identity
  // poses would give the same parts, but through a copy that could turn a -0 into a 0.
  const bool posed = &body.given_parts() != &body.parts();
  return py::make_tuple(kStateVersion, parts, posed ? py::object(pose_matrices(body)) : py::none(),
                        instance_attributes(self));
}

std::pair<CompoundBody, py::dict> compound_from_state(const py::object& state) {
  PickledState items(state, "CompoundBody", 3);
  std::vector<ConvexPolyhedron> parts = items.next("parts", &to_parts);
  const auto poses = items.next("poses", [&parts](const py::handle& item) {
    return item.is_none() ? std::nullopt
                          : std::optional<std::vector<Pose>>(to_poses(item, parts.size(), "poses"));
  });
  py::dict attributes = state_attributes(items);
  return {items.build([&] {
            return poses ? CompoundBody(std::move(parts), *poses) : CompoundBody(std::move(parts));
          }),
          attributes};
}

std::string repr(const CompoundBody& body) {
  const Aabb& box = body.bounds().box;
  std::ostringstream out;
  out << "CompoundBody(" << body.size() << (body.size() == 1 ? " part, " : " parts, ")
      << body.point_count() << " points, bounds [" << box.min.x() << ", " << box.min.y() << ", "
      << box.min.z() << "] to [" << box.max.x() << ", " << box.max.y() << ", " << box.max.z()
      << "])";
  return out.str();
}

std::string stats_repr(const CompoundStats& s) {
  return "CompoundStats(part_pairs=" + std::to_string(s.part_pairs) +
         ", volume_tests=" + std::to_string(s.volume_tests) +
         ", screened=" + std::to_string(s.screened) + ", solved=" + std::to_string(s.solved) +
         ", pruned=" + std::to_string(s.pruned()) + ")";
}

std::string result_repr(const CompoundResult& r) {
  std::ostringstream out;
  out.precision(6);
  out << "CompoundResult(method='" << method_name(r.method) << "'";
  if (r.escalated_from) out << ", escalated_from='" << method_name(*r.escalated_from) << "'";
  out << ", distance=" << r.distance << ", lower_bound=" << r.lower_bound
      << ", colliding=" << (r.colliding ? "True" : "False")
      << ", certified=" << (r.certified ? "True" : "False") << ", part_a=" << r.part_a
      << ", part_b=" << r.part_b << ", solved=" << r.stats.solved << " of " << r.stats.part_pairs
      << " part pairs)";
  return out.str();
}

}  // namespace

void bind_compound(py::module_& m) {
  py::class_<PartNode>(m, "PartNode", R"doc(
A node of a compound body's bounding-volume tree, in the body's own frame.

Attributes
----------
box : Aabb
    The smallest axis-aligned box holding the parts below the node.
centre, radius : numpy.ndarray, float
    A ball holding the parts below the node.
left, right : int
    Indices of the children in ``CompoundBody.tree``; -1 for a leaf.
part : int
    The part a leaf holds; -1 for an inner node.
)doc")
      .def_readonly("box", &PartNode::box)
      .def_readonly("centre", &PartNode::centre)
      .def_readonly("radius", &PartNode::radius)
      .def_readonly("left", &PartNode::left)
      .def_readonly("right", &PartNode::right)
      .def_readonly("part", &PartNode::part)
      .def_property_readonly("leaf", &PartNode::leaf)
      .def(pickle_fields<PartNode>(
          "PartNode", any_values, field("box", &PartNode::box), field("centre", &PartNode::centre),
          field("radius", &PartNode::radius), field("left", &PartNode::left),
          field("right", &PartNode::right), field("part", &PartNode::part)))
      .def("__repr__", [](const PartNode& n) {
        std::ostringstream out;
        out << "PartNode("
            << (n.leaf() ? "part=" + std::to_string(n.part)
                         : "left=" + std::to_string(n.left) + ", right=" + std::to_string(n.right))
            << ", radius=" << n.radius << ")";
        return out.str();
      });

  py::class_<CompoundBody>(m, "CompoundBody", R"doc(
A body that is the union of convex parts, each a ConvexPolyhedron in the body's own frame.

The body keeps a bounding-volume tree over its parts whose every node holds a box, a ball and the
convex hull of the parts below it, the paper's "convex Bounding Volume Hierarchies": queries between compound bodies (``distance``, ``collide``,
``signed_distance``, the batches, scenes) open only the part pairs whose volumes' certified lower
bounds cannot rule them out, and name the parts that realise the answer. Answers are certified
for the union of the convex parts. ``CompoundBody.from_mesh`` builds one from a triangle mesh by
convex decomposition.

Parameters
----------
parts : sequence of ConvexPolyhedron or array_like of shape (n, 3)
    At least one convex part (or the points whose hull it is).
poses : array_like of shape (len(parts), 4, 4), optional
    Where each part sits in the body's frame (as ``Scene`` takes poses: also ``(n, 3, 4)``, a
    pair ``(rotations, translations)`` or a list of poses such as ``(Rotation, translation)``
    pairs): part ``i``'s points ``x`` are at ``R_i x + t_i``. None
    (default): every part is given in the body's frame. A curved part (Cylinder, Cone, Ellipsoid)
    keeps its exact support function under its pose; a polyhedron's points are moved.

Examples
--------
>>> import swarmcollide as sc
>>> cube = [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
>>> ell = sc.CompoundBody([cube, [[x + 1, y, z] for x, y, z in cube],
...                        [[x, y + 1, z] for x, y, z in cube]])
>>> ell
CompoundBody(3 parts, 24 points, bounds [0, 0, 0] to [2, 2, 1])
>>> r = sc.distance(ell, [[x + 1.6, y + 1.5, z] for x, y, z in cube])
>>> round(r.distance, 9), r.part_a, r.certified  # the corner of the L is empty
(0.5, 1, True)
>>> import numpy as np
>>> lying = np.array([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 2], [0, 0, 0, 1]])  # axis along y
>>> bar = sc.CompoundBody([sc.Box([1, 1, 0.1]), sc.Cylinder(0.1, 1)], poses=[np.eye(4), lying])
>>> r = sc.distance(bar, sc.Sphere(0.5), pose_b=(np.eye(3), [0, 0, 3]))
>>> round(r.distance, 9), r.part_a, r.certified  # the cylinder's side: 3 - 2 - 0.1 - 0.5
(0.4, 1, True)
)doc")
      .def(py::init([](const py::object& parts, const py::object& poses) {
             if (py::isinstance<CompoundBody>(parts)) {
               if (!poses.is_none()) {
                 throw py::type_error(
                     "poses must be None when parts is a CompoundBody (whose parts have their "
                     "poses already); pass its given_parts with the poses instead");
               }
               return parts.cast<CompoundBody>();
             }
             std::vector<ConvexPolyhedron> given = to_parts(parts);
             if (poses.is_none()) return CompoundBody(std::move(given));
             const std::vector<Pose> placed = to_poses(poses, given.size(), "poses");
             return CompoundBody(std::move(given), placed);
           }),
           py::arg("parts"), py::kw_only(), py::arg("poses") = py::none())
      .def_property_readonly(
          "parts",
          [](const CompoundBody& body) {
            py::typing::List<ConvexPolyhedron> parts;
            for (const ConvexPolyhedron& part : body.parts()) parts.append(typed_body(part));
            return parts;
          },
          "The convex parts in the body's frame, placed by their poses (copies that share the "
          "parts' hulls; a curved part as its own Cylinder, Cone or Ellipsoid, or, placed by a "
          "pose, as a ConvexPolyhedron with its support function).")
      .def_property_readonly(
          "given_parts",
          [](const CompoundBody& body) {
            py::typing::List<ConvexPolyhedron> parts;
            for (const ConvexPolyhedron& part : body.given_parts()) parts.append(typed_body(part));
            return parts;
          },
          "The parts as given, each in its own frame (``parts`` for a body built without poses).")
      .def_property_readonly("part_poses", &pose_matrices,
                             "Where each part sits in the body's frame: a (len(parts), 4, 4) "
                             "array of homogeneous transforms (identities without poses).")
      .def("__len__", &CompoundBody::size)
      .def_property_readonly("tree", &CompoundBody::tree,
                             "The bounding-volume tree: a list of PartNode, the root first.")
      .def_property_readonly(
          "envelope", &CompoundBody::envelope,
          "The convex hull of every part's points (a ConvexPolyhedron holding the body).")
      .def_property_readonly("node_envelopes", &CompoundBody::node_envelopes,
                             "The convex hull of the parts below each node of ``tree``.")
      .def_property_readonly("point_count", &CompoundBody::point_count,
                             "Total number of points of the parts.")
      .def(
          "aabb", [](const CompoundBody& b) { return b.bounds().box; },
          "Smallest axis-aligned box containing the body.")
      .def_property_readonly(
          "radius", [](const CompoundBody& b) { return b.bounds().radius; },
          "Half the diagonal of the bounding box.")
      .def_property_readonly(
          "bounding_radius", [](const CompoundBody& b) { return b.bounds().radius; },
          "Half the diagonal of the bounding box (as ConvexPolyhedron.bounding_radius).")
      .def(py::pickle(&compound_state, &compound_from_state))
      .def("__repr__", &repr);

  py::class_<CompoundStats>(m, "CompoundStats", R"doc(
What a query between compound bodies did with their part pairs.

Attributes
----------
part_pairs : int
    Parts of A times parts of B.
volume_tests : int
    Pairs of tree nodes whose bounding volumes were compared.
screened : int
    Part pairs settled by the separation along their centres' line, with no solver.
solved : int
    Part pairs handed to the method's solver.
pruned : int
    Part pairs never looked at: ruled out by the tree's certified lower bounds.
)doc")
      .def_readonly("part_pairs", &CompoundStats::part_pairs)
      .def_readonly("volume_tests", &CompoundStats::volume_tests)
      .def_readonly("screened", &CompoundStats::screened)
      .def_readonly("solved", &CompoundStats::solved)
      .def_property_readonly("pruned", &CompoundStats::pruned)
      .def(pickle_fields<CompoundStats>(
          "CompoundStats", any_values, field("part_pairs", &CompoundStats::part_pairs),
          field("volume_tests", &CompoundStats::volume_tests),
          field("screened", &CompoundStats::screened), field("solved", &CompoundStats::solved)))
      .def("__repr__", &stats_repr);

  py::class_<CompoundResult, DistanceResult>(m, "CompoundResult", R"doc(
The answer of a query between compound bodies: a DistanceResult for the union of the convex parts,
with the pair of parts that realises it.

``lower_bound <= true value <= distance`` holds for the union of the parts (certified for the
parts, not for the mesh they approximate). The witnesses lie on parts ``part_a`` and ``part_b``;
``weights_a`` and ``weights_b`` are over those parts' points. For signed distances the value is
the smallest signed distance over part pairs: minus the deepest part-pair penetration, which is
not in general the penetration depth of the non-convex union.
)doc")
      .def_readonly("part_a", &CompoundResult::part_a,
                    "Index of A's part that realises the answer.")
      .def_readonly("part_b", &CompoundResult::part_b,
                    "Index of B's part that realises the answer.")
      .def_readonly("stats", &CompoundResult::stats, "What the search did (a CompoundStats).")
      .def(py::pickle(
          [](const CompoundResult& r) {
            return py::make_tuple(kStateVersion, distance_result_state(r), r.part_a, r.part_b,
                                  r.stats);
          },
          [](const py::object& state) {
            PickledState items(state, "CompoundResult", 4);
            CompoundResult r;
            static_cast<DistanceResult&>(r) = items.next("result", &distance_result_from_state);
            r.part_a = items.next<int>("part_a");
            r.part_b = items.next<int>("part_b");
            r.stats = items.next<CompoundStats>("stats");
            return r;
          }))
      .def("__repr__", &result_repr);
}

}  // namespace swarmcollide::bindings
