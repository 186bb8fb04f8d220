// The solver behind each method; private to the library's sources.
#pragma once

#include "../geometry/framed_body.hpp"
#include "../solvers/answer.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/options.hpp"

namespace swarmcollide::detail {

/// A method's solver: answers `goal` for a framed pair (the options are validated).
using Solver = Answer (*)(const FramedPair& pair, const QueryOptions& options, Goal goal);

/// The solver of `method`, from the method table (methods.cpp).
Solver solver_for(Method method);

/// Throws std::invalid_argument when `method` cannot answer `query` (which has `capability`),
/// naming the methods that can.
void require(Method method, Capability capability, const char* query);

}  // namespace swarmcollide::detail
