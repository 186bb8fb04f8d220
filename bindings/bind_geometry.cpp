#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <sstream>

#include "conversions.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"

namespace swarmcollide::bindings {

namespace {

std::string repr(const ConvexPolyhedron& body) {
  const Aabb box = body.aabb();
  std::ostringstream out;
  out << "ConvexPolyhedron(" << body.size() << (body.size() == 1 ? " point" : " points")
      << ", bounds [" << box.min.x() << ", " << box.min.y() << ", " << box.min.z() << "] to ["
      << box.max.x() << ", " << box.max.y() << ", " << box.max.z() << "])";
  return out.str();
}

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
      .def("__repr__", [](const Hull& h) {
        return "Hull(dimension=" + std::to_string(h.dimension) + ", " +
               std::to_string(h.vertex_indices.size()) + " vertices, " +
               std::to_string(h.faces.rows()) + " faces)";
      });

  py::class_<Aabb>(m, "Aabb", "An axis-aligned bounding box with corners ``min`` and ``max``.")
      .def_readonly("min", &Aabb::min)
      .def_readonly("max", &Aabb::max)
      .def("__repr__", [](const Aabb& box) {
        std::ostringstream out;
        out << "Aabb(min=[" << box.min.x() << ", " << box.min.y() << ", " << box.min.z()
            << "], max=[" << box.max.x() << ", " << box.max.y() << ", " << box.max.z() << "])";
        return out.str();
      });

  py::class_<ConvexPolyhedron>(m, "ConvexPolyhedron", R"doc(
A convex polyhedron: the convex hull of a finite set of points (the paper's Definition 3).

Parameters
----------
points : array_like, shape (n, 3)
    At least one finite point. The points are kept as given: they are the vertices ``x_i`` of
    model (2). Flat, collinear and single-point sets are valid bodies.

Examples
--------
>>> import swarmcollide as sc
>>> tetra = sc.ConvexPolyhedron([[0, 1, 0], [1, 0, 0], [0, 0, 1], [0, 0, 0]])
>>> tetra.support([1, 0, 0]).tolist()
[1.0, 0.0, 0.0]
>>> tetra.hull().dimension
3
)doc")
      .def(py::init([](const py::object& points) {
             // A body given for its points is the same body: copies share the hull.
             if (py::isinstance<ConvexPolyhedron>(points)) return points.cast<ConvexPolyhedron>();
             return ConvexPolyhedron(to_vertex_matrix(points, "points"));
           }),
           py::arg("points"))
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
            return body.support_index(finite_vector3(direction, "direction"));
          },
          py::arg("direction"), "Index of the point farthest along ``direction`` (first on ties).")
      .def("aabb", &ConvexPolyhedron::aabb, "Smallest axis-aligned box containing the body.")
      .def_property_readonly(
          "radius", [](const ConvexPolyhedron& body) { return body.bounds().radius; },
          "Half the diagonal of the bounding box: every point lies within it of the box's centre.")
      .def("centroid", &ConvexPolyhedron::centroid,
           "Centre of mass of the solid (of the polygon, segment or point for lower-dimensional "
           "bodies).")
      .def("hull", &ConvexPolyhedron::hull, py::return_value_policy::copy,
           "Convex hull through Qhull (an exact planar hull for flat bodies).")
      .def("__repr__", &repr);

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
}

}  // namespace swarmcollide::bindings
