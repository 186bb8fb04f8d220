#pragma once

#include <string>
#include <vector>

#include "swarmcollide/queries/options.hpp"

namespace swarmcollide {

/// The queries a method can answer (bit flags).
enum Capability : unsigned {
  kDistance = 1u << 0,
  kCollide = 1u << 1,
  kSignedDistance = 1u << 2,
  /// Answers curved shapes (ConvexPolyhedron::curved: Cylinder, Cone, Ellipsoid) through their
  /// support functions; the other methods enumerate a body's points.
  kCurvedShapes = 1u << 3,
};

/// A solver parameter that a method reads from QueryOptions.
struct ParameterInfo {
  enum class Kind { integer, real, choice };
  /// The keyword (the field's name in its options struct).
  const char* name;
  Kind kind;
  /// One line for documentation.
  const char* description;
  /// Valid range, inclusive except for the minimum where `minimum_excluded` (a value that must
  /// be positive); for a choice, the index of the last choice is the maximum.
  double minimum;
  double maximum;
  bool minimum_excluded;
  /// The names of a choice's values 0, 1, ...; empty otherwise.
  std::vector<const char*> choices;
  /// The value in `options` (a choice as its index).
  double (*get)(const QueryOptions& options);
  /// Sets the value; `value` must already be valid (see `set_parameter`).
  void (*set)(QueryOptions& options, double value);
};

/// What the library knows about a method: one entry per method, read by every dispatch and by
/// the Python layer (`swarmcollide.METHODS`).
struct MethodInfo {
  Method method;
  /// The name the APIs use ("dual", "ipso", ...).
  const char* name;
  /// One line for documentation.
  const char* summary;
  /// `Capability` flags.
  unsigned capabilities;
  /// True when every verdict the method returns is proven; false for the primal swarms and the
  /// penalty method, whose verdicts are proven only when their bounds happen to be tight enough
  /// (`collide` then hands unproven verdicts to an exact method).
  bool always_certified;
  /// The parameters of QueryOptions the method reads, besides `tolerance` and `seed`.
  std::vector<ParameterInfo> parameters;
};

/// Every method, the default ("dual") first.
const std::vector<MethodInfo>& method_table();

/// The entry of `method`.
const MethodInfo& method_info(Method method);

/// The method called `name`; throws std::invalid_argument listing the valid names.
Method method_from_name(const std::string& name);

/// The name of `method`.
const char* method_name(Method method);

/// Sets parameter `name` of `options.method` to `value` (a choice by index); throws
/// std::invalid_argument when the method has no such parameter (listing its parameters), or the
/// value is not an integer where one is due, or it lies outside the parameter's range.
void set_parameter(QueryOptions& options, const std::string& name, double value);

/// The index of `choice` among the choices of parameter `name` of `options.method`; throws
/// std::invalid_argument listing the valid choices.
int choice_index(const QueryOptions& options, const std::string& name, const std::string& choice);

}  // namespace swarmcollide
