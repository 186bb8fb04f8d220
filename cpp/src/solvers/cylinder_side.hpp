// A depth proof where a cylinder's side holds the deepest point; private to the library's
// sources.
#pragma once

#include "../geometry/framed_body.hpp"
#include "expanding_polytope.hpp"
#include "side_chain.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// A cylinder is a disc plus a segment along its axis z, so `A - B` is `E + [-h, h] z` for the
/// convex set E that the other body minus the cylinder's disc makes. Along a direction u at
/// elevation t from the plane normal to z, at azimuth w in that plane, a point e of E lifted to
/// either end of the segment shows `h_{A-B}(u) >= cos t (w . e) + |sin t| (h - |e . z|)`. Where
/// the deepest point lies on the cylinder's side, the least support is in the plane (t = 0),
/// where it is a point's depth in E's projection along z: a convex set of the plane, closed on
/// by a chain of support points (a polygon of a dozen or two corners) where the expanding
/// polytope needs thirty steps along the curved side of a rim against the flat side of the
/// cylinder. For every azimuth between the chain's edge normals its corners give
/// `cos t d + |sin t| (h - H)` (d the least of the chain's edge distances, H the most of its
/// corners' heights), at least d up to the elevation where it falls back to d (everywhere if
/// `h - H >= d`): a wedge of directions about the plane. Every other direction crosses a face of
/// `polytope` (the expansion's surface so far, closed around the origin), which bounds the depth
/// along it by its plane's distance over the cosine to its normal; the bound holds where, for
/// every face nearer than it, the directions that face bounds by less lie in the wedge.
/// `cylinder_is_a` names the cylinder; `best` is the expansion's best normal, near which the
/// chain starts; `gap` is where the chain's nearest edge settles. Proves nothing where the best
/// normal is off the plane, the corners along the chain leave the side, or a near face leaves
/// the wedge.
SideDepth cylinder_side_depth(const FramedBody& a, const FramedBody& b, bool cylinder_is_a,
                              const ExpandingPolytope& polytope, const Vector3& best, Scalar gap);

}  // namespace swarmcollide::detail
