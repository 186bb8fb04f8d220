#include "swarmcollide/queries/signed_distance.hpp"

#include <stdexcept>

#include "swarmcollide/solvers/dual.hpp"
#include "swarmcollide/solvers/fcl_distance.hpp"
#include "swarmcollide/solvers/libccd_penetration.hpp"

namespace swarmcollide {

DistanceResult signed_distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                               const DistanceOptions& options) {
  switch (options.method) {
    case Method::fcl:
      return fcl_signed_distance(a, b, FclGjk::libccd, options.exact);
    case Method::fcl_indep:
      return fcl_signed_distance(a, b, FclGjk::indep, options.exact);
    case Method::libccd:
      return libccd_signed_distance(a, b, options.exact);
    case Method::dual:
      return dual_signed_distance(a, b, options.dual);
    default:
      throw std::invalid_argument(
          "signed_distance needs an exact method ('fcl', 'fcl-indep' or "
          "'libccd') or 'dual'; method '" +
          method_name(options.method) + "' does not measure penetration depth");
  }
}

}  // namespace swarmcollide
