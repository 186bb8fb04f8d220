// A body as FCL sees it (method "fcl"); private to the library's sources.
#pragma once

#include <fcl/geometry/shape/shape_base.h>

#include "../geometry/framed_body.hpp"

namespace swarmcollide::detail {

/// `body` as an FCL shape in the frame's units (divided by 2^exponent), in the body's own frame
/// centred on its box, as FramedBody places it before its rotation: a curved shape as FCL's own
/// primitive (`fcl::Cylinderd`, `fcl::Coned`, `fcl::Ellipsoidd`), any other body as its hull
/// points in an `fcl::Convexd` (a rounded body's core: the radii are taken off its answer after,
/// queries/rounded.hpp). Made on first use for the body and exponent and kept with the body
/// (ConvexPolyhedron::derived); the body must be framed from a ConvexPolyhedron.
const fcl::ShapeBased& fcl_shape(const FramedBody& body);

}  // namespace swarmcollide::detail
