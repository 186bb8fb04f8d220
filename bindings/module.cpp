#include <pybind11/pybind11.h>

#include "queries.hpp"

namespace py = pybind11;

namespace swarmcollide::bindings {
void bind_geometry(py::module_& m);
void bind_compound(py::module_& m);
void bind_problem(py::module_& m);
void bind_solvers(py::module_& m);
void bind_batch(py::module_& m, py::class_<Query>& query);
void bind_scene(py::module_& m);
void bind_robot(py::module_& m);
void bind_motion(py::module_& m);
}  // namespace swarmcollide::bindings

PYBIND11_MODULE(_core, m) {
  m.doc() =
      "swarmcollide's C++ core: convex polyhedra and compound bodies, model (2), its solvers, "
      "queries and scenes.";
  using namespace swarmcollide::bindings;
  bind_geometry(m);
  bind_problem(m);
  bind_solvers(m);
  bind_distance_result(m);
  bind_compound(m);
  py::class_<swarmcollide::Query> query = bind_queries(m);
  bind_batch(m, query);
  bind_scene(m);
  bind_robot(m);
  bind_motion(m);
}
