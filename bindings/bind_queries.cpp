#include "conversions.hpp"
#include "swarmcollide/queries/distance.hpp"

namespace swarmcollide::bindings {

void bind_queries(py::module_& m) {
  py::class_<DistanceOptions>(m, "DistanceOptions", "A method and the parameters of its solver.")
      .def(py::init<>())
      .def_property(
          "method", [](const DistanceOptions& o) { return method_name(o.method); },
          [](DistanceOptions& o, const std::string& name) { o.method = method_from_name(name); })
      .def_readwrite("swarm", &DistanceOptions::swarm);

  m.def(
      "distance",
      [](const py::object& a, const py::object& b, const DistanceOptions& options) {
        const ConvexPolyhedron body_a = to_polyhedron(a, "a");
        const ConvexPolyhedron body_b = to_polyhedron(b, "b");
        py::gil_scoped_release release;
        return distance(body_a, body_b, options);
      },
      py::arg("a"), py::arg("b"), py::arg("options"));
}

}  // namespace swarmcollide::bindings
