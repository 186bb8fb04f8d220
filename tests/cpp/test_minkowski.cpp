// The enclosure test behind every intersection proof and every expanding polytope's start: the
// origin inside a tetrahedron of Minkowski points, beyond rounding.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "shapes.hpp"
#include "solvers/minkowski.hpp"
#include "swarmcollide/geometry/shapes.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"

namespace swarmcollide::testing {
namespace {

using detail::encloses_origin;

TEST(EnclosesOrigin, ATetrahedronAroundTheOriginEnclosesItWithItsBarycentricWeights) {
  Random rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    const Matrix3 r = rng.rotation();
    const std::array<Vector3, 4> points = {
        Vector3(r * Vector3(1, 1, 1)), Vector3(r * Vector3(1, -1, -1)),
        Vector3(r * Vector3(-1, 1, -1)), Vector3(r * Vector3(-1, -1, 1))};
    std::array<Scalar, 4> weights{};
    ASSERT_TRUE(encloses_origin(points, weights));
    for (Scalar w : weights) EXPECT_NEAR(w, 0.25, 1e-14);
  }
}

// Four points on a circle are coplanar: whatever side rounding puts the fourth point on, a point
// off their plane is not inside (the enclosure test once took the rounding's sign as the fourth
// point's side, and a cone's rim points then "enclosed" a point 0.06 off their plane).
TEST(EnclosesOrigin, AFlatTetrahedronEnclosesNothingOffItsPlane) {
  const std::array<Vector3, 4> rim = {
      Vector3(-0.26564707001448495, 0.32420028557772568, 0.68602072581512497),
      Vector3(0.038031181537268061, 0.60117418821289847, 0.32383838818035016),
      Vector3(-0.29806270602406559, -0.33154327383587789, 0.15737049484204796),
      Vector3(0.14656536463047082, 0.46458087836140832, -0.019041044586027067)};
  EXPECT_FALSE(encloses_origin(rim));
  Random rng(9);
  for (int trial = 0; trial < 2000; ++trial) {
    const Matrix3 r = rng.rotation();
    const Vector3 centre = rng.vector(0.5);
    const Scalar height = rng.uniform(0.01, 0.5) * (trial % 2 ? 1 : -1);
    std::array<Vector3, 4> points;
    for (int k = 0; k < 4; ++k) {
      const Scalar angle = rng.uniform(0, 2 * M_PI);
      points[k] = r * (centre + Vector3(std::cos(angle), std::sin(angle), height));
    }
    EXPECT_FALSE(encloses_origin(points)) << trial;
  }
}

// The test without weights decides the enclosure from the four faces' sides of the origin alone
// (their sum is the fourth point's side): on tetrahedra nearly flat, or with the origin nearly on a
// face, an enclosure it reports must hold in extended precision, by more than the points'
// rounding, and wherever the test with weights (which also checks each fourth point's side)
// finds one, it must too.
TEST(EnclosesOrigin, WithoutWeightsItProvesWhatExtendedPrecisionConfirms) {
  using Extended = long double;
  constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  Random rng(24);
  int enclosed = 0;
  for (int trial = 0; trial < 30000; ++trial) {
    std::array<Vector3, 4> points;
    for (Vector3& p : points) p = rng.vector(1);
    const Scalar closeness = std::pow(10.0, -rng.uniform(2, 15));
    if (trial % 3 == 1) {
      // Nearly flat: every point within `closeness` of a plane through the origin's neighbourhood.
      const Vector3 normal = rng.vector(1).normalized();
      const Scalar offset = rng.uniform(-0.1, 0.1);
      for (Vector3& p : points) p -= (p.dot(normal) - offset - rng.uniform(-1, 1) * closeness) * normal;
    } else if (trial % 3 == 2) {
      // The origin within `closeness` of a face's plane.
      const Vector3 normal = (points[2] - points[1]).cross(points[3] - points[1]).normalized();
      const Vector3 shift = (points[1].dot(normal) + rng.uniform(-1, 1) * closeness) * normal;
      for (Vector3& p : points) p -= shift;
    }
    std::array<Scalar, 4> weights{};
    const bool with_weights = encloses_origin(points, weights);
    const bool without = encloses_origin(points);
    if (with_weights) EXPECT_TRUE(without) << trial;
    if (!without) continue;
    ++enclosed;
    int sign = 0;
    for (const auto& face : kFaces) {
      Eigen::Matrix<Extended, 3, 1> p = points[face[0]].cast<Extended>();
      const Eigen::Matrix<Extended, 3, 1> normal =
          (points[face[1]].cast<Extended>() - p).cross(points[face[2]].cast<Extended>() - p);
      const Extended side = -p.dot(normal) / normal.norm();
      const int face_sign = side > 0 ? 1 : -1;
      if (sign == 0) sign = face_sign;
      EXPECT_EQ(face_sign, sign) << trial;
      EXPECT_GT(std::abs(side), 2 * detail::kFrameRounding) << trial;
    }
  }
  EXPECT_GT(enclosed, 1000);
}

// The pair whose exact signed distance the flat tetrahedron left unproven: a ball's centre 0.019
// inside a cone's slanted side (the expanding polytope could not start from it).
TEST(EnclosesOrigin, ABallInsideAConesSideGetsAProvenSignedDistance) {
  Matrix3 ra;
  ra << -0.15414121542884041, -0.53386065283718531, 0.83140440764911383, 0.55715135333450294,
      -0.74188385708553939, -0.37308271478777277, 0.81597969042351259, 0.4057106677770958,
      0.4117960646584804;
  Matrix3 rb;
  rb << -0.37250199720062116, -0.33449129116846787, -0.86565457210945296, 0.89942821969575693,
      -0.3599232933707362, -0.24795987680284948, -0.22862882516531036, -0.8709596999985787,
      0.43492305213901428;
  const Pose pa = at(Vector3::Zero(), ra);
  const Pose pb = at(Vector3(0.11790765748165244, -0.20585454074875598, -0.55160308419370629), rb);
  const Cone cone(1.0053022056970209, 0.17094432708988852);
  const Sphere ball(1.0687101846787841);
  // The centre's depth below the slanted side (the line from the base's rim (R, -h) to the apex
  // (0, h) in the plane of the axis), less than below the base.
  const Vector3 c = ra.transpose() * pb.translation;
  const Scalar radius = 1.0053022056970209;
  const Scalar h = 0.17094432708988852;
  const Scalar rho = std::hypot(c.x(), c.y());
  const Scalar depth = -((rho - radius) * 2 * h + (c.z() + h) * radius) /
                       std::hypot(2 * h, radius);
  ASSERT_GT(depth, 0.01);
  ASSERT_LT(depth, c.z() + h);
  for (Method method : {Method::exact, Method::dual}) {
    QueryOptions options;
    options.method = method;
    const DistanceResult s = Query(options).signed_distance(cone, pa, ball, pb);
    EXPECT_TRUE(s.certified) << method_name(method);
    EXPECT_NEAR(s.distance, -(ball.radius() + depth), 1e-9) << method_name(method);
  }
}

}  // namespace
}  // namespace swarmcollide::testing
