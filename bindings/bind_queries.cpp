#include "conversions.hpp"
#include "swarmcollide/queries/collide.hpp"
#include "swarmcollide/queries/distance.hpp"
#include "swarmcollide/queries/signed_distance.hpp"

namespace swarmcollide::bindings {

namespace {

// Converts both bodies while holding the GIL, then runs the query without it.
template <typename... Extra, typename Result>
auto on_bodies(Result (*query)(const ConvexPolyhedron&, const ConvexPolyhedron&,
                               const DistanceOptions&, Extra...)) {
  return [query](const py::object& a, const py::object& b, const DistanceOptions& options,
                 Extra... extra) {
    const ConvexPolyhedron body_a = to_polyhedron(a, "a");
    const ConvexPolyhedron body_b = to_polyhedron(b, "b");
    py::gil_scoped_release release;
    return query(body_a, body_b, options, extra...);
  };
}

}  // namespace

void bind_queries(py::module_& m) {
  py::class_<DistanceOptions>(m, "DistanceOptions", "A method and the parameters of its solver.")
      .def(py::init<>())
      .def_property(
          "method", [](const DistanceOptions& o) { return method_name(o.method); },
          [](DistanceOptions& o, const std::string& name) { o.method = method_from_name(name); })
      .def_readwrite("swarm", &DistanceOptions::swarm)
      .def_readwrite("penalty", &DistanceOptions::penalty)
      .def_readwrite("exact", &DistanceOptions::exact)
      .def_readwrite("dual", &DistanceOptions::dual);

  m.def("distance", on_bodies(&distance), py::arg("a"), py::arg("b"), py::arg("options"));
  m.def("signed_distance", on_bodies(&signed_distance), py::arg("a"), py::arg("b"),
        py::arg("options"));
  m.def("collision", on_bodies(&collision), py::arg("a"), py::arg("b"), py::arg("options"),
        py::arg("escalate"));
  m.def("collide", on_bodies(&collide), py::arg("a"), py::arg("b"), py::arg("options"),
        py::arg("escalate"));
}

}  // namespace swarmcollide::bindings
