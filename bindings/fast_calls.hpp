// Module functions answered in C++ before pybind11's dispatch: the usual calls of the small
// queries, whose argument matching costs as much as the query itself.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "swarmcollide/geometry/convex_polyhedron.hpp"

namespace swarmcollide::bindings {

namespace py = pybind11;

/// The C++ object of `object` when its Python type is exactly T's bound class (the usual argument:
/// a ConvexPolyhedron, a Query), read from the instance with the type's record found once: a cast
/// looks the record up by the C++ type's name on every call. Null for anything else (a subclass,
/// another type), which the callers then convert as pybind11 does, or for an instance whose
/// __init__ has not run (the cast then says so).
template <typename T>
const T* exact_instance(PyObject* object) {
  static PyTypeObject* const type = reinterpret_cast<PyTypeObject*>(py::type::of<T>().ptr());
  static py::detail::type_info* const record = py::detail::get_type_info(typeid(T));
  if (Py_TYPE(object) != type) return nullptr;
  auto* instance = reinterpret_cast<py::detail::instance*>(object);
  return static_cast<const T*>(instance->get_value_and_holder(record, false).value_ptr());
}

/// The body of `object` when its Python type is exactly ConvexPolyhedron or one of the shapes bound
/// as its subclasses (Sphere, Capsule, Box, Cylinder, Cone, Ellipsoid); null for anything else,
/// including a subclass written in Python, which the callers convert as pybind11 does. The generic
/// isinstance and cast cost about a microsecond per curved argument, more than many queries.
const ConvexPolyhedron* body_instance(PyObject* object);

/// METH_FASTCALL | METH_KEYWORDS's calling convention (named so from Python 3.13 only).
using FastCall = PyObject* (*)(PyObject*, PyObject* const*, Py_ssize_t, PyObject*);

/// `entry` as a module function standing for `python_path`, its Python definition: with its name,
/// module and documentation, headed by `text_signature` (without annotations). `entry` answers
/// the calls it reads and hands every other one to the Python definition.
py::object fast_function(FastCall entry, const py::function& python_path,
                         const std::string& text_signature);

}  // namespace swarmcollide::bindings
