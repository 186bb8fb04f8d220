#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace swarmcollide::bindings {
void bind_geometry(py::module_& m);
void bind_problem(py::module_& m);
void bind_solvers(py::module_& m);
void bind_queries(py::module_& m);
void bind_batch(py::module_& m);
}  // namespace swarmcollide::bindings

PYBIND11_MODULE(_core, m) {
  m.doc() = "swarmcollide's C++ core: convex polyhedra, model (2) and its solvers.";
  using namespace swarmcollide::bindings;
  bind_geometry(m);
  bind_problem(m);
  bind_solvers(m);
  bind_queries(m);
  bind_batch(m);
}
