// A depth proof where a cone's side holds the deepest point; private to the library's sources.
#pragma once

#include "../geometry/framed_body.hpp"
#include "expanding_polytope.hpp"
#include "side_chain.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// A cone (apex at z = h, base disc of radius r at z = -h) has the same support, `r/2 cos b`,
/// along every normal of its side: the directions at elevation b, `tan b = r / 2h`, where its
/// apex and its rim support it together. Write the pair's difference, turned over where the cone
/// is B, as the cone less the other body's points y (in the cone's axes); along the side's
/// normal at azimuth w, y bounds the support by `cos b (w . -y_xy) + sin b (h - y_z)`, which is
/// at least `w . P` for the point `P = -cos b y_xy + sin b (h - y_z) w_y` of the plane (w_y the
/// azimuth y was the support along; `h - y_z >= 0`). So where the cone's side holds the deepest
/// point, the least support is a point's depth in a convex set of the plane, which a chain of
/// such points closes on as the cylinder's section does (cylinder_side.hpp). Off the side's
/// normals, at elevation b + t, the apex (t > 0) or the rim point at azimuth w (t < 0) with y
/// bound the support by `cos t (w . P) + |sin t| s`, s the distance from y's foot on the side's
/// line at w to the apex or to the rim: at least the chain's distance d up to where
/// `tan(|t| / 2) = s / d`, a wedge of directions about the side's normals. Every other direction
/// crosses a face of `polytope`, as for the cylinder. `cone_is_a` names the cone; `best` is the
/// expansion's best normal, near which the chain starts; `gap` is where the chain's nearest edge
/// settles. Proves nothing where the best normal is off the side's normals, the corners along
/// the chain leave the side, or a near face leaves the wedge.
SideDepth cone_side_depth(const FramedBody& a, const FramedBody& b, bool cone_is_a,
                          const ExpandingPolytope& polytope, const Vector3& best, Scalar gap);

}  // namespace swarmcollide::detail
