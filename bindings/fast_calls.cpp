#include "fast_calls.hpp"

#include "swarmcollide/geometry/shapes.hpp"

namespace swarmcollide::bindings {

const ConvexPolyhedron* body_instance(PyObject* object) {
  if (const auto* body = exact_instance<ConvexPolyhedron>(object)) return body;
  if (const auto* body = exact_instance<Box>(object)) return body;
  if (const auto* body = exact_instance<Sphere>(object)) return body;
  if (const auto* body = exact_instance<Capsule>(object)) return body;
  if (const auto* body = exact_instance<Cylinder>(object)) return body;
  if (const auto* body = exact_instance<Cone>(object)) return body;
  return exact_instance<Ellipsoid>(object);
}

py::object fast_function(FastCall entry, const py::function& python_path,
                         const std::string& text_signature) {
  // A function's name and documentation must outlive it, and the module keeps its functions:
  // they are made once per import and never freed.
  const auto name = python_path.attr("__name__").cast<std::string>();
  const std::string docstring = py::str(python_path.attr("__doc__"));
  const auto* const documentation = new std::string(name + text_signature + "\n--\n\n" + docstring);
  const auto* const function_name = new std::string(name);
  auto* const definition = new PyMethodDef{
      function_name->c_str(), reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(entry)),
      METH_FASTCALL | METH_KEYWORDS, documentation->c_str()};
  const py::object module = python_path.attr("__module__");
  PyObject* const function = PyCFunction_NewEx(definition, nullptr, module.ptr());
  if (function == nullptr) throw py::error_already_set();
  return py::reinterpret_steal<py::object>(function);
}

}  // namespace swarmcollide::bindings
