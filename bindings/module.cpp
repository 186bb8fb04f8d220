#include <pybind11/pybind11.h>

#include <algorithm>

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

namespace {

// pickle's protocols 0 and 1 reduce an object through copyreg's _reduce_ex, which makes the copy
// by calling the object's nearest built-in base type with it: pybind11's base refuses, and its
// exception there aborted the interpreter (pickle.dumps(sc.Sphere(1.0), protocol=0)). Every class
// that pickles (a __setstate__, py::pickle's) reduces in every protocol as it does in protocol 2:
// its class made anew (copyreg.__newobj__) and its __getstate__'s state, which protocols 0 and 1
// write as they write any other call.
void reduce_as_protocol_two(py::module_& m) {
  const py::object object_reduce_ex =
      py::module_::import("builtins").attr("object").attr("__reduce_ex__");
  for (const auto item : m.attr("__dict__").cast<py::dict>()) {
    const py::handle type = item.second;
    if (!PyType_Check(type.ptr()) || !py::hasattr(type, "__setstate__")) continue;
    // The protocol as Python passes it (an object: typed as int, the stubs' signature would
    // contradict object.__reduce_ex__'s).
    type.attr("__reduce_ex__") = py::cpp_function(
        [object_reduce_ex](const py::object& self, const py::object& protocol) {
          return object_reduce_ex(self, std::max(protocol.cast<int>(), 2));
        },
        py::name("__reduce_ex__"), py::is_method(type), py::arg("protocol"),
        "Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and "
        "__getstate__).");
  }
}

}  // namespace

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
  reduce_as_protocol_two(m);
}
