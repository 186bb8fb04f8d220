#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace swarmcollide {

/// The one floating-point type used throughout the library.
using Scalar = double;
/// A point or direction in 3-D space.
using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
/// A 3 x 3 matrix (rotations).
using Matrix3 = Eigen::Matrix<Scalar, 3, 3>;
/// A dynamically sized vector, used for convex-combination weights.
using VectorX = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
/// Points stored one per row (row-major), so `(n, 3)` NumPy arrays map onto it without copies.
using VertexMatrix = Eigen::Matrix<Scalar, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// Triangles as rows of three point indices.
using FaceMatrix = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// A read-only view of weights, accepting vectors and vector expressions without copies.
using WeightsRef = Eigen::Ref<const VectorX>;

}  // namespace swarmcollide
