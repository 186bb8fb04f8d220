#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <sstream>
#include <string>

#include "conversions.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/placed_shape.hpp"
#include "swarmcollide/geometry/shapes.hpp"

namespace swarmcollide::bindings {

namespace {

std::string repr(const ConvexPolyhedron& body) {
  const Aabb box = body.aabb();
  std::ostringstream out;
  out << "ConvexPolyhedron(" << body.size() << (body.size() == 1 ? " point" : " points")
      << ", bounds [" << box.min.x() << ", " << box.min.y() << ", " << box.min.z() << "] to ["
      << box.max.x() << ", " << box.max.y() << ", " << box.max.z() << "]";
  if (body.radius() > 0) out << ", radius=" << body.radius();
  out << ")";
  return out.str();
}

std::string sphere_repr(const Sphere& s) {
  std::ostringstream out;
  out << "Sphere(radius=" << s.radius() << ")";
  return out.str();
}

std::string capsule_repr(const Capsule& c) {
  std::ostringstream out;
  out << "Capsule(radius=" << c.radius() << ", half_length=" << c.half_length() << ")";
  return out.str();
}

std::string box_repr(const Box& b) {
  std::ostringstream out;
  const Vector3& h = b.half_extents();
  out << "Box(half_extents=[" << h.x() << ", " << h.y() << ", " << h.z() << "]";
  if (b.radius() > 0) out << ", radius=" << b.radius();
  out << ")";
  return out.str();
}

std::string cylinder_repr(const Cylinder& c) {
  std::ostringstream out;
  out << "Cylinder(radius=" << c.cylinder_radius() << ", half_length=" << c.half_length() << ")";
  return out.str();
}

std::string cone_repr(const Cone& c) {
  std::ostringstream out;
  out << "Cone(radius=" << c.base_radius() << ", half_length=" << c.half_length() << ")";
  return out.str();
}

std::string ellipsoid_repr(const Ellipsoid& e) {
  std::ostringstream out;
  const Vector3& r = e.radii();
  out << "Ellipsoid(radii=[" << r.x() << ", " << r.y() << ", " << r.z() << "])";
  return out.str();
}

// A shape pickled as `parameters(shape)` (a tuple of `count` items) and its instance's attributes
// (a Python subclass's), rebuilt by `make(state)` from the parameters it reads back.
template <typename Shape, typename Parameters, typename Make>
auto pickle_shape(const char* type, std::size_t count, Parameters parameters, Make make) {
  return py::pickle(
      [parameters](const py::object& self) {
        return py::tuple(py::make_tuple(kStateVersion) + parameters(self.cast<const Shape&>()) +
                         py::make_tuple(instance_attributes(self)));
      },
      [type, count, make](const py::object& state) {
        PickledState items(state, type, count + 1);
        Shape shape = make(items);
        return std::make_pair(std::move(shape), state_attributes(items));
      });
}

// A ConvexPolyhedron's shape as pickled: None for the hull of its points, else its curved shape
// in its own frame and the pose placing it (None in its own frame).
py::object curved_state(const ConvexPolyhedron& body) {
  if (!body.curved()) return py::none();
  const CurvedShapeParameters shape = body.curved()->parameters();
  return py::make_tuple(unplaced_shape(shape),
                        shape.placed ? py::object(homogeneous(shape.pose)) : py::none());
}

// The curved body of `shape` placed by `pose` (none: in its own frame), as placed_shape.hpp
// places a compound body's parts.
ConvexPolyhedron curved_body(const ConvexPolyhedron& shape, const std::optional<Pose>& pose) {
  return pose ? placed(shape, *pose) : shape;
}

// The curved body a ConvexPolyhedron's state names by its (shape, pose) item.
ConvexPolyhedron curved_from_state(const py::handle& item) {
  if (PyTuple_Check(item.ptr()) && PyTuple_Size(item.ptr()) == 2) {
    const py::tuple pair = py::reinterpret_borrow<py::tuple>(item);
    if (py::isinstance<Cylinder>(pair[0]) || py::isinstance<Cone>(pair[0]) ||
        py::isinstance<Ellipsoid>(pair[0])) {
      std::optional<Pose> pose;
      if (!pair[1].is_none()) pose = to_pose(pair[1], "pose");
      return curved_body(pair[0].cast<const ConvexPolyhedron&>(), pose);
    }
  }
  throw py::type_error("must be None or a pair (Cylinder, Cone or Ellipsoid; pose or None), got " +
                       std::string(py::repr(item)));
}

bool same_points(const VertexMatrix& a, const VertexMatrix& b) {
  return a.rows() == b.rows() && (a.array() == b.array()).all();
}

py::tuple polyhedron_state(const py::object& self) {
  const auto& body = self.cast<const ConvexPolyhedron&>();
  const py::object shape = curved_state(body);
  // A part placed by a pose and placed again keeps only the last pose in its parameters: rebuilt
  // from them it would be another body.
  if (!shape.is_none() && !same_points(curved_from_state(shape).vertices(), body.vertices())) {
    throw py::type_error(
        "cannot pickle this ConvexPolyhedron: it is a curved shape placed by two poses in turn (a "
        "compound body's placed part placed again), which its parameters do not rebuild; pickle "
        "the shape itself and the product of the poses");
  }
  return py::make_tuple(kStateVersion, body.vertices(), body.radius(), shape,
                        instance_attributes(self));
}

std::pair<ConvexPolyhedron, py::dict> polyhedron_from_state(const py::object& state) {
  PickledState items(state, "ConvexPolyhedron", 4);
  VertexMatrix points =
      items.next("points", [](const py::handle& item) { return to_vertex_matrix(item, "points"); });
  const auto radius = items.next<Scalar>("radius");
  const auto shape = items.next("shape", [](const py::handle& item) {
    return item.is_none() ? std::nullopt : std::optional<ConvexPolyhedron>(curved_from_state(item));
  });
  py::dict attributes = state_attributes(items);
  if (!shape) {
    return {items.build([&] { return ConvexPolyhedron(std::move(points), radius); }), attributes};
  }
  if (!same_points(shape->vertices(), points) || radius != 0) {
    throw items.error("points and radius are not those of its curved shape");
  }
  return {*shape, attributes};
}

// Every curved shape is answered the same way; each one's docstring says so.
#define SWARMCOLLIDE_CURVED_NOTE                                                                   \
  "A curved shape, defined by its support function: methods ``'dual'`` (the default) and "         \
  "``'exact'`` answer it, exactly to their tolerance and certified, against any other body; "      \
  "``'fcl'`` runs FCL's GJK on FCL's own primitive and ``'libccd'`` libccd on its support "        \
  "function, both checked by the certificate as for polyhedra; the methods that read a body's "    \
  "points (``'ipso'``, ``'pso'``, ``'penalty'``) raise ValueError. Its ``vertices`` are a few "    \
  "points on its surface (an inner polytope with the shape's bounding box), not the body; "        \
  "results carry no weights (empty), and witnesses are points of the shape."

// Every query answers rounded bodies the same way; each shape's docstring says so.
#define SWARMCOLLIDE_ROUNDED_NOTE                                                              \
  "Queries answer rounded bodies on their cores (the points' hull) and subtract the radii: the " \
  "signed distance of two rounded convex bodies is exactly that of their cores less both "       \
  "radii, so bounds, certificates and verdicts keep their meaning, relative to the size of the " \
  "rounded bodies. Methods ``'ipso'``, ``'pso'`` and ``'penalty'`` (model (2)) weigh the "       \
  "core's points; ``'fcl'`` and ``'libccd'`` also answer on the cores (not on FCL's own sphere " \
  "and capsule primitives). Support points, hulls, centroids and weights are the core's."

}  // namespace

void bind_geometry(py::module_& m) {
  py::class_<Hull>(m, "Hull", R"doc(
Convex hull of a polyhedron's points, as indices into those points.

Attributes
----------
dimension : int
    Affine dimension of the points: 0 (a point), 1 (a segment), 2 (a flat polygon) or 3 (a solid).
vertex_indices : numpy.ndarray
    Indices of the points that are hull vertices, ascending.
faces : numpy.ndarray
    ``(m, 3)`` triangles indexing the polyhedron's points, outward by the right-hand rule. A flat
    polygon is listed once facing each side; segments and points have no faces.
)doc")
      .def_readonly("dimension", &Hull::dimension)
      .def_property_readonly("vertex_indices",
                             [](const Hull& h) {
                               return py::array_t<int>(
                                   static_cast<py::ssize_t>(h.vertex_indices.size()),
                                   h.vertex_indices.data());
                             })
      .def_readonly("faces", &Hull::faces)
      .def(pickle_fields<Hull>(
          "Hull", any_values, field("dimension", &Hull::dimension),
          field("vertex_indices", &Hull::vertex_indices), field("faces", &Hull::faces)))
      .def("__repr__", [](const Hull& h) {
        return "Hull(dimension=" + std::to_string(h.dimension) + ", " +
               std::to_string(h.vertex_indices.size()) + " vertices, " +
               std::to_string(h.faces.rows()) + " faces)";
      });

  py::class_<Aabb>(m, "Aabb", "An axis-aligned bounding box with corners ``min`` and ``max``.")
      .def_readonly("min", &Aabb::min)
      .def_readonly("max", &Aabb::max)
      .def(pickle_fields<Aabb>(
          "Aabb", any_values, field("min", &Aabb::min), field("max", &Aabb::max)))
      .def("__repr__", [](const Aabb& box) {
        std::ostringstream out;
        out << "Aabb(min=[" << box.min.x() << ", " << box.min.y() << ", " << box.min.z()
            << "], max=[" << box.max.x() << ", " << box.max.y() << ", " << box.max.z() << "])";
        return out.str();
      });

  py::class_<ConvexPolyhedron>(m, "ConvexPolyhedron", R"doc(
A convex polyhedron: the convex hull of a finite set of points (the paper's Definition 3),
rounded by ``radius``: the set of points within ``radius`` of that hull (a sphere is one point
rounded, a capsule a segment; see ``Sphere``, ``Capsule`` and ``Box``).

)doc" SWARMCOLLIDE_ROUNDED_NOTE R"doc(

Parameters
----------
points : array_like, shape (n, 3)
    At least one finite point. The points are kept as given: they are the vertices ``x_i`` of
    model (2). Flat, collinear and single-point sets are valid bodies. A ConvexPolyhedron is
    taken as it is (with its radius unless ``radius`` is given).
radius : float, optional
    The rounding radius, finite and ``>= 0``; 0 (the default) for a plain polyhedron.

Examples
--------
>>> import swarmcollide as sc
>>> tetra = sc.ConvexPolyhedron([[0, 1, 0], [1, 0, 0], [0, 0, 1], [0, 0, 0]])
>>> tetra.support([1, 0, 0]).tolist()
[1.0, 0.0, 0.0]
>>> tetra.hull().dimension
3
>>> sc.distance(sc.ConvexPolyhedron([[0, 0, 0]], radius=1), [[3, 0, 0]]).distance
2.0
)doc")
      .def(py::init([](const py::object& points, std::optional<Scalar> radius) {
             // A body given for its points is the same body: copies share the hull.
             if (py::isinstance<ConvexPolyhedron>(points)) {
               ConvexPolyhedron body = points.cast<ConvexPolyhedron>();
               if (!radius || *radius == body.radius()) return body;
               if (const SupportFunction* shape = body.curved()) {
                 throw py::value_error(std::string("radius: a ") + shape->name() +
                                       " is a curved shape and cannot be rounded; its vertices "
                                       "are only a few points on its surface");
               }
               return ConvexPolyhedron(body.vertices(), *radius);
             }
             return ConvexPolyhedron(to_vertex_matrix(points, "points"), radius.value_or(0));
           }),
           py::arg("points"), py::arg("radius") = py::none())
      .def_property_readonly("vertices", &ConvexPolyhedron::vertices,
                             py::return_value_policy::reference_internal,
                             "The ``(n, 3)`` points the body was built from (read-only).")
      .def("__len__", &ConvexPolyhedron::size)
      .def(
          "support",
          [](const ConvexPolyhedron& body, const py::object& direction) {
            return Vector3(body.support(finite_vector3(direction, "direction")));
          },
          py::arg("direction"),
          "A point of the body farthest along ``direction`` (3 real numbers).")
      .def(
          "support_index",
          [](const ConvexPolyhedron& body, const py::object& direction) {
            if (const SupportFunction* shape = body.curved()) {
              throw py::value_error(std::string("a ") + shape->name() +
                                    " is a curved shape: its support points are not among its "
                                    "vertices; use support(direction)");
            }
            return body.support_index(finite_vector3(direction, "direction"));
          },
          py::arg("direction"),
          "Index of the point farthest along ``direction`` (first on ties); ValueError for a "
          "curved shape, whose support points are not among its vertices.")
      .def("aabb", &ConvexPolyhedron::aabb,
           "Smallest axis-aligned box containing the body (its rounding included).")
      .def_property_readonly("radius", &ConvexPolyhedron::radius,
                             "The rounding radius (0 for a plain polyhedron).")
      .def_property_readonly(
          "rounding_radius", &ConvexPolyhedron::radius,
          "The rounding radius of every kind of body: a ConvexPolyhedron's or Box's ``radius``, a "
          "Sphere's or Capsule's radius, 0 for a Cylinder, Cone or Ellipsoid, whose ``radius`` "
          "(where they have one) is their own dimension. Code that handles any body reads this.")
      .def_property_readonly(
          "bounding_radius", [](const ConvexPolyhedron& body) { return body.bounds().radius; },
          "Half the diagonal of the points' bounding box plus the rounding radius: every point of "
          "the body lies within it of the box's centre.")
      .def_property_readonly(
          "curved", [](const ConvexPolyhedron& body) { return body.curved() != nullptr; },
          "True for a curved shape (Cylinder, Cone, Ellipsoid), defined by its support function "
          "rather than by the hull of its vertices.")
      .def("centroid", &ConvexPolyhedron::centroid,
           "Centre of mass of the solid (of the polygon, segment or point for lower-dimensional "
           "bodies).")
      .def("hull", &ConvexPolyhedron::hull, py::return_value_policy::copy,
           "Convex hull through Qhull (an exact planar hull for flat bodies).")
      .def(py::pickle(&polyhedron_state, &polyhedron_from_state))
      .def("__repr__", &repr);

  py::class_<Sphere, ConvexPolyhedron>(m, "Sphere", R"doc(
A ball of radius ``radius`` centred on the origin of its frame (URDF's ``<sphere radius>``;
MJCF's sphere geom, size = radius): the one point ``(0, 0, 0)`` rounded by ``radius``.

)doc" SWARMCOLLIDE_ROUNDED_NOTE R"doc(

Parameters
----------
radius : float
    Finite and ``> 0``.

Examples
--------
>>> import swarmcollide as sc
>>> a, b = sc.Sphere(1.0), sc.Sphere(0.5)
>>> sc.distance(a, b, pose_b=([[1, 0, 0], [0, 1, 0], [0, 0, 1]], [3, 0, 0])).distance
1.5
>>> sc.signed_distance(a, b).distance
-1.5
)doc")
      .def(py::init([](const Given<Scalar>& radius) {
             return Sphere(to_real(radius.value, "radius"));
           }),
           py::arg("radius"))
      .def(pickle_shape<Sphere>(
          "Sphere", 1, [](const Sphere& s) { return py::make_tuple(s.radius()); },
          [](PickledState& items) {
            const auto radius = items.next<Scalar>("radius");
            return items.build([&] { return Sphere(radius); });
          }))
      .def("__repr__", &sphere_repr);

  py::class_<Capsule, ConvexPolyhedron>(m, "Capsule", R"doc(
A capsule along the z axis of its frame, centred on its origin (MJCF's capsule geom, size =
(radius, half_length)): the segment from ``(0, 0, -half_length)`` to ``(0, 0, half_length)``
rounded by ``radius``, ``2 (half_length + radius)`` long in all.

)doc" SWARMCOLLIDE_ROUNDED_NOTE R"doc(

Parameters
----------
radius : float
    Finite and ``> 0``.
half_length : float
    Half the length of the core segment (of the cylinder part), finite and ``> 0``.

Examples
--------
>>> import swarmcollide as sc
>>> upright = sc.Capsule(0.5, 1.0)
>>> identity = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
>>> sc.distance(upright, upright, pose_b=(identity, [2, 0, 0.5])).distance
1.0
)doc")
      .def(py::init([](const Given<Scalar>& radius, const Given<Scalar>& half_length) {
             return Capsule(to_real(radius.value, "radius"),
                            to_real(half_length.value, "half_length"));
           }),
           py::arg("radius"), py::arg("half_length"))
      .def_property_readonly("half_length", &Capsule::half_length,
                             "Half the length of the core segment.")
      .def(pickle_shape<Capsule>(
          "Capsule", 2,
          [](const Capsule& c) { return py::make_tuple(c.radius(), c.half_length()); },
          [](PickledState& items) {
            const auto radius = items.next<Scalar>("radius");
            const auto half_length = items.next<Scalar>("half_length");
            return items.build([&] { return Capsule(radius, half_length); });
          }))
      .def("__repr__", &capsule_repr);

  py::class_<Box, ConvexPolyhedron>(m, "Box", R"doc(
An axis-aligned box centred on the origin of its frame, ``2 half_extents`` across (URDF's
``<box size>`` is ``2 half_extents``; MJCF's box geom size is ``half_extents``): the hull of its
8 corners, rounded by ``radius`` (a rounded box then spans ``half_extents + radius``).

)doc" SWARMCOLLIDE_ROUNDED_NOTE R"doc(

Parameters
----------
half_extents : array_like, shape (3,)
    Half the box's size along x, y and z, each finite and ``> 0``.
radius : float, optional
    The rounding radius, finite and ``>= 0`` (0, the default, for a sharp box).

Examples
--------
>>> import swarmcollide as sc
>>> box = sc.Box([1, 2, 3])
>>> identity = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
>>> sc.distance(box, sc.Sphere(1), pose_b=(identity, [3, 0, 0])).distance
1.0
)doc")
      .def(py::init([](const py::object& half_extents, const Given<Scalar>& radius) {
             return Box(finite_vector3(half_extents, "half_extents"),
                        to_real(radius.value, "radius"));
           }),
           py::arg("half_extents"), py::arg("radius") = 0.0)
      .def_property_readonly("half_extents", &Box::half_extents,
                             "Half the box's size along x, y and z.")
      .def(pickle_shape<Box>(
          "Box", 2, [](const Box& b) { return py::make_tuple(b.half_extents(), b.radius()); },
          [](PickledState& items) {
            const auto half_extents = items.next<Vector3>("half_extents");
            const auto radius = items.next<Scalar>("radius");
            return items.build([&] { return Box(half_extents, radius); });
          }))
      .def("__repr__", &box_repr);

  py::class_<Cylinder, ConvexPolyhedron>(m, "Cylinder", R"doc(
A solid circular cylinder along the z axis of its frame, centred on its origin: radius
``radius``, from ``z = -half_length`` to ``z = half_length`` (FCL's and coal's convention; URDF's
``<cylinder radius length>`` has ``length = 2 half_length``; MJCF's cylinder geom has size =
(radius, half_length)).

)doc" SWARMCOLLIDE_CURVED_NOTE R"doc(

Parameters
----------
radius : float
    The radius of the circular section, finite and ``> 0``.
half_length : float
    Half the cylinder's length along z, finite and ``> 0``.

Examples
--------
>>> import swarmcollide as sc
>>> can = sc.Cylinder(0.5, 1.0)
>>> identity = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
>>> round(sc.distance(can, sc.Sphere(0.25), pose_b=(identity, [2, 0, 0])).distance, 9)
1.25
>>> round(sc.signed_distance(can, can, pose_b=(identity, [0, 0, 1.5])).distance, 9)
-0.5
)doc")
      .def(py::init([](const Given<Scalar>& radius, const Given<Scalar>& half_length) {
             return Cylinder(to_real(radius.value, "radius"),
                             to_real(half_length.value, "half_length"));
           }),
           py::arg("radius"), py::arg("half_length"))
      .def_property_readonly("radius", &Cylinder::cylinder_radius,
                             "The radius of the circular section (a cylinder is not rounded: its "
                             "rounding radius is 0).")
      .def_property_readonly("half_length", &Cylinder::half_length,
                             "Half the cylinder's length along z.")
      .def(pickle_shape<Cylinder>(
          "Cylinder", 2,
          [](const Cylinder& c) { return py::make_tuple(c.cylinder_radius(), c.half_length()); },
          [](PickledState& items) {
            const auto radius = items.next<Scalar>("radius");
            const auto half_length = items.next<Scalar>("half_length");
            return items.build([&] { return Cylinder(radius, half_length); });
          }))
      .def("__repr__", &cylinder_repr);

  py::class_<Cone, ConvexPolyhedron>(m, "Cone", R"doc(
A solid right circular cone along the z axis of its frame, centred on its axis' midpoint (FCL's
and coal's convention): its base, a disk of radius ``radius``, at ``z = -half_length``, its apex
at ``(0, 0, half_length)``; its centre of mass is at ``z = -half_length / 2``.

)doc" SWARMCOLLIDE_CURVED_NOTE R"doc(

Parameters
----------
radius : float
    The radius of the base disk, finite and ``> 0``.
half_length : float
    Half the cone's height, finite and ``> 0``.

Examples
--------
>>> import swarmcollide as sc
>>> cone = sc.Cone(1.0, 1.0)
>>> identity = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
>>> round(sc.distance(cone, sc.Sphere(0.5), pose_b=(identity, [0, 0, 3])).distance, 9)
1.5
)doc")
      .def(py::init([](const Given<Scalar>& radius, const Given<Scalar>& half_length) {
             return Cone(to_real(radius.value, "radius"),
                         to_real(half_length.value, "half_length"));
           }),
           py::arg("radius"), py::arg("half_length"))
      .def_property_readonly("radius", &Cone::base_radius,
                             "The radius of the base disk (a cone is not rounded: its rounding "
                             "radius is 0).")
      .def_property_readonly("half_length", &Cone::half_length, "Half the cone's height.")
      .def(pickle_shape<Cone>(
          "Cone", 2, [](const Cone& c) { return py::make_tuple(c.base_radius(), c.half_length()); },
          [](PickledState& items) {
            const auto radius = items.next<Scalar>("radius");
            const auto half_length = items.next<Scalar>("half_length");
            return items.build([&] { return Cone(radius, half_length); });
          }))
      .def("__repr__", &cone_repr);

  py::class_<Ellipsoid, ConvexPolyhedron>(m, "Ellipsoid", R"doc(
A solid ellipsoid centred on the origin of its frame with semi-axes ``radii`` along x, y and z:
the points with ``(x/a)^2 + (y/b)^2 + (z/c)^2 <= 1`` (MJCF's ellipsoid geom, size = radii).

)doc" SWARMCOLLIDE_CURVED_NOTE R"doc(

Parameters
----------
radii : array_like, shape (3,)
    The semi-axes along x, y and z, each finite and ``> 0``.

Examples
--------
>>> import swarmcollide as sc
>>> egg = sc.Ellipsoid([1, 2, 3])
>>> identity = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
>>> round(sc.distance(egg, sc.Sphere(1), pose_b=(identity, [0, 0, 5])).distance, 9)
1.0
)doc")
      .def(py::init([](const py::object& radii) {
             return Ellipsoid(finite_vector3(radii, "radii"));
           }),
           py::arg("radii"))
      .def_property_readonly("radii", &Ellipsoid::radii, "The semi-axes along x, y and z.")
      .def(pickle_shape<Ellipsoid>(
          "Ellipsoid", 1, [](const Ellipsoid& e) { return py::make_tuple(e.radii()); },
          [](PickledState& items) {
            const auto radii = items.next<Vector3>("radii");
            return items.build([&] { return Ellipsoid(radii); });
          }))
      .def("__repr__", &ellipsoid_repr);

  m.def(
      "as_polyhedron",
      [](const py::object& body, const py::object& name) {
        return BodyArgument(body, to_name(name, "name").c_str()).get();
      },
      py::arg("body"), py::arg("name") = "body",
      R"doc(
Return ``body`` as a ConvexPolyhedron, building one from ``(n, 3)`` points if needed.

Errors name the argument as ``name``.
)doc");

  m.def(
      "pose_matrix",
      [](const py::object& pose, const py::object& name) {
        return homogeneous(to_pose(pose, to_name(name, "name").c_str()));
      },
      py::arg("pose"), py::arg("name") = "pose",
      R"doc(
Return ``pose``, in any form the queries take (see ``swarmcollide.PoseLike``), as a ``(4, 4)``
float64 homogeneous transform, read exactly as the queries read it.

Errors name the argument as ``name``.
)doc");
}

}  // namespace swarmcollide::bindings
