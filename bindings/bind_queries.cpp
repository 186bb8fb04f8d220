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

  m.def("distance", &distance, py::arg("a"), py::arg("b"), py::arg("options"),
        py::call_guard<py::gil_scoped_release>());
  m.def("collide", &collide, py::arg("a"), py::arg("b"), py::arg("options"),
        py::call_guard<py::gil_scoped_release>());
}

}  // namespace swarmcollide::bindings
