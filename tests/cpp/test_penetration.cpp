#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "penetration_oracle.hpp"
#include "geometry/framed_body.hpp"
#include "geometry/normalise.hpp"
#include "solvers/expanding_polytope.hpp"
#include "solvers/minkowski.hpp"
#include "solvers/penetration.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/hull.hpp"
#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/geometry/shapes.hpp"

namespace swarmcollide {
namespace {

using detail::penetration;
using detail::PenetrationBounds;
using testing::oracle_signed_distance;

// The oracle's own rounding (Qhull's facets of the differences) and the solver's margins are
// far below this.
constexpr Scalar kOracleSlack = 1e-12;
constexpr Scalar kTolerance = 1e-9;
constexpr int kIterations = 1000;

VertexMatrix rows(std::initializer_list<Vector3> list) {
  VertexMatrix v(static_cast<Eigen::Index>(list.size()), 3);
  Eigen::Index i = 0;
  for (const Vector3& p : list) v.row(i++) = p.transpose();
  return v;
}

VertexMatrix box(const Vector3& lo, const Vector3& hi) {
  VertexMatrix v(8, 3);
  for (int k = 0; k < 8; ++k) {
    v.row(k) << (k & 1 ? hi.x() : lo.x()), (k & 2 ? hi.y() : lo.y()), (k & 4 ? hi.z() : lo.z());
  }
  return v;
}

VertexMatrix transformed(const VertexMatrix& v, const Eigen::Matrix3d& rotation,
                         const Vector3& offset) {
  VertexMatrix out = v * rotation.transpose();
  out.rowwise() += offset.transpose();
  return out;
}

Eigen::Matrix3d rotation(Scalar x, Scalar y, Scalar z) {
  return (Eigen::AngleAxisd(z, Vector3::UnitZ()) * Eigen::AngleAxisd(y, Vector3::UnitY()) *
          Eigen::AngleAxisd(x, Vector3::UnitX()))
      .toRotationMatrix();
}

VertexMatrix random_points(std::mt19937_64& rng, int n, const Vector3& centre, Scalar radius) {
  std::normal_distribution<Scalar> g;
  VertexMatrix v(n, 3);
  for (int i = 0; i < n; ++i) v.row(i) << g(rng), g(rng), g(rng);
  v *= radius / 2;
  v.rowwise() += centre.transpose();
  return v;
}

// Bodies of random points about the origin, A's in a ball of radius 1 and B's of radius 0.6 (in
// that order from `rng`): the pairs the tests below pose through each other.
std::pair<ConvexPolyhedron, ConvexPolyhedron> random_bodies(std::mt19937_64& rng, int na, int nb) {
  return {ConvexPolyhedron(random_points(rng, na, Vector3::Zero(), 1)),
          ConvexPolyhedron(random_points(rng, nb, Vector3::Zero(), 0.6))};
}

// The contract of every answer: proven bounds around the oracle, a unit normal whose computed
// separation is the lower bound up to its margin, and witnesses that are convex combinations of
// the bodies' points on their supporting features along the normal.
void check_contract(const VertexMatrix& a, const VertexMatrix& b, const PenetrationBounds& r,
                    Scalar exact, Scalar tolerance, bool expect_proven) {
  EXPECT_LE(r.lower, exact + kOracleSlack);
  EXPECT_GE(r.upper, exact - kOracleSlack);
  if (expect_proven) {
    EXPECT_TRUE(r.proven) << "gap " << r.upper - r.lower;
  }
  EXPECT_EQ(r.proven, r.upper - r.lower <= tolerance);
  EXPECT_NEAR(r.normal.norm(), 1, 1e-15);
  const VectorX ha = a * r.normal;
  const VectorX hb = b * r.normal;
  EXPECT_NEAR(r.separation, hb.minCoeff() - ha.maxCoeff(), 1e-15);
  EXPECT_EQ(r.lower, r.separation - r.margin);
  EXPECT_LE(r.margin, 1e-13);
  const VectorX weights_a = r.weights_a.dense();
  const VectorX weights_b = r.weights_b.dense();
  EXPECT_GE(weights_a.minCoeff(), 0);
  EXPECT_GE(weights_b.minCoeff(), 0);
  EXPECT_NEAR(weights_a.sum(), 1, 1e-14);
  EXPECT_NEAR(weights_b.sum(), 1, 1e-14);
  EXPECT_LE((a.transpose() * weights_a - r.point_a).norm(), 1e-14);
  EXPECT_LE((b.transpose() * weights_b - r.point_b).norm(), 1e-14);
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    if (weights_a(i) > 0) EXPECT_GE(ha(i), ha.maxCoeff() - r.feature_slack - 1e-15);
  }
  for (Eigen::Index j = 0; j < b.rows(); ++j) {
    if (weights_b(j) > 0) EXPECT_LE(hb(j), hb.minCoeff() + r.feature_slack + 1e-15);
  }
  if (r.proven) {
    EXPECT_LE((r.point_b - r.point_a - r.separation * r.normal).norm(), 1e-9);
  }
}

// Checks the solver as it runs, and again with one iteration allowed, which stops Wolfe and the
// polytope at once and leaves the proof to the candidate axes; they prove overlaps (touching and
// separated pairs need Wolfe's nearest point, which one iteration does not give).
PenetrationBounds check(const VertexMatrix& a, const VertexMatrix& b, const std::string& name,
                        const Vector3& hint = Vector3::Zero(), Scalar tolerance = kTolerance,
                        bool expect_proven = true) {
  SCOPED_TRACE(name);
  const Hull hull_a = compute_hull(a);
  const Hull hull_b = compute_hull(b);
  const Scalar exact = oracle_signed_distance(a, b);
  const PenetrationBounds r = penetration(a, hull_a, b, hull_b, hint, tolerance, kIterations);
  check_contract(a, b, r, exact, tolerance, expect_proven);
  {
    SCOPED_TRACE("one iteration");
    const PenetrationBounds axes = penetration(a, hull_a, b, hull_b, hint, tolerance, 1);
    check_contract(a, b, axes, exact, tolerance, expect_proven && exact < -1e-12);
    if (expect_proven && exact < -1e-12) {
      EXPECT_EQ(axes.proof, detail::PenetrationProof::candidate_axes);
    }
  }
  return r;
}

TEST(Penetration, IssueCubesOverlappingByHalf) {
  const VertexMatrix c = box({0, 0, 0}, {1, 1, 1});
  const VertexMatrix b = transformed(c, Eigen::Matrix3d::Identity(), {0.5, 0.25, 0.1});
  const PenetrationBounds r = check(c, b, "cubes");
  EXPECT_NEAR(r.lower, -0.5, 1e-12);
  EXPECT_NEAR(r.upper, -0.5, 1e-12);
  EXPECT_NEAR(std::abs(r.normal.x()), 1, 1e-12);
  // The same pair at tolerance 0: the bounds hold and differ only by the rounding margins.
  const PenetrationBounds exact = check(c, b, "cubes, tolerance 0", Vector3::Zero(), 0, false);
  EXPECT_LE(exact.upper - exact.lower, 1e-13);
}

TEST(Penetration, MarginsFollowTheLargestCoordinate) {
  // The issue's cubes at other scales and far from the origin: the margins are multiples of the
  // largest coordinate, so the bounds stay proven at a tolerance scaled alike.
  const VertexMatrix c = box({0, 0, 0}, {1, 1, 1});
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  for (const Scalar scale : {1e-5, 1e-4, 1e4}) {
    for (const Scalar offset : {0.0, 1e3}) {
      const VertexMatrix a = transformed(c * scale, I, Vector3::Constant(offset * scale));
      const VertexMatrix b = transformed(
          c * scale, I, Vector3(0.5, 0.25, 0.1) * scale + Vector3::Constant(offset * scale));
      const Hull ha = compute_hull(a);
      const Hull hb = compute_hull(b);
      const PenetrationBounds r =
          penetration(a, ha, b, hb, Vector3::Zero(), 1e-9 * scale * (1 + offset), kIterations);
      // The rounded coordinates move the depth off 0.5 scale; along x it is the difference of
      // two nearby doubles, which is exact (Sterbenz).
      const Scalar exact = b.col(0).minCoeff() - a.col(0).maxCoeff();
      EXPECT_NEAR(exact, -0.5 * scale, 1e-12 * scale * (1 + offset));
      EXPECT_TRUE(r.proven) << scale << " " << offset;
      EXPECT_LE(r.lower, exact);
      EXPECT_GE(r.upper, exact);
      EXPECT_NEAR(std::abs(r.normal.x()), 1, 1e-12);
    }
  }
}

TEST(Penetration, UnnormalisedExtremesGetInfiniteBoundsNotWrongOnes) {
  // Products of such coordinates overflow or underflow; the solver declines rather than guess.
  // (The hull is the unit cube's: its indices do not depend on the scale.)
  const VertexMatrix c = box({0, 0, 0}, {1, 1, 1});
  const Hull hull = compute_hull(c);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  for (const Scalar scale : {1e-200, 1e200}) {
    const VertexMatrix a = c * scale;
    const VertexMatrix b = transformed(c * scale, I, Vector3(2, 0, 0) * scale);
    const PenetrationBounds r =
        penetration(a, hull, b, hull, Vector3::Zero(), kTolerance, kIterations);
    EXPECT_FALSE(r.proven);
    EXPECT_EQ(r.lower, -std::numeric_limits<Scalar>::infinity());
    EXPECT_EQ(r.upper, std::numeric_limits<Scalar>::infinity());
    EXPECT_TRUE(r.point_a.allFinite() && r.point_b.allFinite());
  }
  // All points at the origin: the frame is degenerate but exact, and sd = 0 is proven.
  const VertexMatrix origin = VertexMatrix::Zero(3, 3);
  const PenetrationBounds r = penetration(origin, compute_hull(origin), origin,
                                          compute_hull(origin), Vector3::Zero(), 0, kIterations);
  EXPECT_TRUE(r.proven);
  EXPECT_EQ(r.lower, 0);
  EXPECT_EQ(r.upper, 0);
}

TEST(Penetration, RandomOverlapsAtVariousDepthsMatchTheOracle) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  for (int trial = 0; trial < 120; ++trial) {
    const int na = 4 + trial % 61;
    const int nb = 4 + (trial * 7) % 61;
    const VertexMatrix a = random_points(rng, na, Vector3::Zero(), 1);
    const Vector3 offset = Vector3(unit(rng), unit(rng), unit(rng)) * (0.2 + trial % 5 * 0.2);
    const VertexMatrix b = random_points(rng, nb, offset, 0.3 + trial % 3 * 0.4);
    check(a, b, "trial " + std::to_string(trial));
  }
}

// A pair's kept surface (KeptSurface) starts the expansion at the next poses: the answers keep
// the contract frame after frame as the bodies turn and slide through each other, and a surface
// spoiled on purpose (corners swapped, an index out of range, a face or edge named that is not
// there, an adjacency broken) is either refused or still proves only true bounds.
TEST(Penetration, KeptSurfacesStartLaterExpansionsAndProveOnlyTrueBounds) {
  std::mt19937_64 rng(24);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  int started_kept = 0;
  for (int trial = 0; trial < 40; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const auto [a, b] = random_bodies(rng, 8 + trial % 50, 8 + (trial * 7) % 50);
    const Vector3 start(unit(rng), unit(rng), unit(rng));
    const Vector3 velocity = Vector3(unit(rng), unit(rng), unit(rng)) * 0.01;
    const Vector3 spin = Vector3(unit(rng), unit(rng), unit(rng)) * 0.02;
    detail::KeptSurface surface;
    for (int frame = 0; frame < 8; ++frame) {
      SCOPED_TRACE("frame " + std::to_string(frame));
      Pose pose_b;
      pose_b.rotation = rotation(frame * spin.x(), frame * spin.y(), frame * spin.z());
      pose_b.translation = start * 0.6 + frame * velocity;
      const detail::FramedPair pair = detail::frame_validated_pair(a, Pose(), b, pose_b, 1e-9);
      if (!surface.faces.empty()) {
        ++started_kept;
        // Spoiled as a stale or mistaken cache could be: a face or an edge that is not there
        // is refused; neighbours that do not name each other back are left to the final check.
        const auto faces = static_cast<std::uint8_t>(surface.faces.size());
        if (frame == 3) surface.faces.back().adj[1] = faces;
        if (frame == 4) surface.faces[1].adj_edge[2] = 3;
        if (frame == 5) std::swap(surface.corners[0], surface.corners[1]);
        if (frame == 6) surface.corners.back()[1] = static_cast<int>(b.size());
        if (frame == 7) surface.faces[0].adj[0] = surface.faces[0].adj[1];
      }
      const PenetrationBounds r = penetration(pair.a, pair.b, Vector3::Zero(), nullptr,
                                              pair.tolerance, kIterations, &surface);
      const VertexMatrix world_b = transformed(b.vertices(), pose_b.rotation, pose_b.translation);
      const Scalar exact = oracle_signed_distance(a.vertices(), world_b);
      EXPECT_LE(pair.frame.length_to_world(r.lower), exact + kOracleSlack);
      EXPECT_GE(pair.frame.length_to_world(r.upper), exact - kOracleSlack);
      if (exact < -1e-9) {
        EXPECT_TRUE(r.proven);
      }
    }
  }
  EXPECT_GT(started_kept, 40);
}

// The separation a lower bound rests on is measured between the scans' supports along the
// answer's normal: small placed polytopes, which support_index scans whole, take the expansion's
// supports along its best normal instead of scanning again, and they must be the same points.
TEST(Penetration, SmallPolytopesSeparationIsTheScansAlongTheNormal) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  int proven = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const auto [a, b] = random_bodies(rng, 4 + trial % 24, 4 + (trial * 7) % 24);
    Pose pose_b;
    pose_b.rotation = rotation(unit(rng), unit(rng), unit(rng));
    pose_b.translation = Vector3(unit(rng), unit(rng), unit(rng)) * 0.5;
    const detail::FramedPair pair = detail::frame_validated_pair(a, Pose(), b, pose_b, 1e-9);
    const PenetrationBounds r =
        penetration(pair.a, pair.b, Vector3::Zero(), nullptr, pair.tolerance, kIterations);
    const Vector3& n = r.normal;
    EXPECT_EQ(r.separation, pair.b.height(pair.b.support_index(-n), n) -
                                pair.a.height(pair.a.support_index(n), n))
        << "trial " << trial;
    proven += r.proven && r.upper < 0;
  }
  // Most pairs overlap, so the expansion ran and gave the normal.
  EXPECT_GT(proven, 30);
}

TEST(Penetration, BadHintsDoNotTrapTheSearchInALocalMaximum) {
  // s has many local maxima on the sphere: any hint, however poor, still ends at the global one.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  for (int trial = 0; trial < 60; ++trial) {
    const VertexMatrix a = random_points(rng, 8, Vector3::Zero(), 1);
    const VertexMatrix b = random_points(rng, 8, Vector3(0.3, 0.1, -0.2), 1);
    const Hull ha = compute_hull(a);
    const Hull hb = compute_hull(b);
    const PenetrationBounds good =
        penetration(a, ha, b, hb, Vector3::Zero(), kTolerance, kIterations);
    for (const Vector3& hint : {Vector3(-good.normal), Vector3(unit(rng), unit(rng), unit(rng)),
                                Vector3(good.normal.unitOrthogonal())}) {
      const PenetrationBounds r = check(a, b, "trial " + std::to_string(trial), hint);
      EXPECT_NEAR(r.lower, good.lower, 1e-12);
    }
  }
}

TEST(Penetration, BoxContacts) {
  const VertexMatrix unit = box({0, 0, 0}, {1, 1, 1});
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  // Face against face, shifted so no edges line up.
  check(unit, transformed(unit, I, {0.9, 0.3, 0.2}), "face-face");
  // Edge against edge: A turned 45 degrees about x, B about y, so A's top edge (along x) crosses
  // B's bottom edge (along y) and the axis of least overlap is their cross product, z, which is
  // no face normal of either; the pair is then turned as a whole, off the coordinate axes.
  const VertexMatrix centred = box({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5});
  const Scalar half_diagonal = std::sqrt(0.5);
  const Eigen::Matrix3d whole = rotation(0.4, -0.3, 0.7);
  const VertexMatrix ridge_a =
      transformed(centred, whole * rotation(M_PI / 4, 0, 0), Vector3::Zero());
  const VertexMatrix ridge_b = transformed(centred, whole * rotation(0, M_PI / 4, 0),
                                           whole * Vector3(0.1, -0.2, 2 * half_diagonal - 0.05));
  const PenetrationBounds crossed = check(ridge_a, ridge_b, "edge-edge");
  EXPECT_NEAR(crossed.lower, -0.05, 1e-12);
  EXPECT_NEAR(crossed.normal.dot(whole * Vector3::UnitZ()), 1, 1e-12);
  // A vertex of B pushed into a face of A.
  const VertexMatrix corner = transformed(box({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}),
                                          rotation(0.6154797, M_PI / 4, 0), Vector3::Zero());
  const Scalar reach = corner.col(2).maxCoeff();
  check(unit, transformed(corner, I, {0.5, 0.5, 1 + reach - 0.05}), "vertex-face");
  // Rotated boxes whose edges are parallel to rounding.
  const Eigen::Matrix3d turn = rotation(0.3, -0.7, 1.1);
  check(transformed(unit, turn, Vector3::Zero()),
        transformed(unit, turn, turn * Vector3(0.6, 0.2, 0.1)), "rotated parallel boxes");
}

// A tetrahedron of points of A - B (differences of the two bodies' points) around the origin,
// to start an expansion; false where none is found.
bool enclosing_start(const detail::FramedPair& pair,
                     std::array<detail::DifferencePoint, 4>& start) {
  std::vector<detail::DifferencePoint> points;
  for (int i = 0; i < pair.a.size(); ++i) {
    for (int j = 0; j < pair.b.size(); ++j) {
      points.push_back({pair.a.vertex(i) - pair.b.vertex(j), i, j});
    }
  }
  const int n = static_cast<int>(points.size());
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      for (int k = j + 1; k < n; ++k) {
        for (int l = k + 1; l < n; ++l) {
          if (detail::encloses_origin({points[i].w, points[j].w, points[k].w, points[l].w})) {
            start = {points[i], points[j], points[k], points[l]};
            return true;
          }
        }
      }
    }
  }
  return false;
}

// A box resting on a larger one, 0.01 into it: the facet of A - B along their normal is a
// rectangle that the expansion splits into several faces, and the one its best normal came from
// need not hold a given ray's crossing. The walk from it (face_crossed) must end on a face the ray
// crosses, on that facet, and the solver's witnesses (found on such a face when the best one
// does not hold the origin's foot) must satisfy the contract.
TEST(Penetration, FaceCrossedFindsTheFaceOfASplitFacetThatARayCrosses) {
  const VertexMatrix base = box({0, 0, 0}, {1, 1, 1});
  const VertexMatrix top = box({0.1, 0.2, 0.99}, {0.7, 0.7, 1.39});
  check(base, top, "resting face on face");
  const ConvexPolyhedron body_a(base);
  const ConvexPolyhedron body_b(top);
  const detail::FramedPair pair =
      detail::frame_validated_pair(body_a, Pose(), body_b, Pose(), 1e-9);
  std::array<detail::DifferencePoint, 4> start;
  ASSERT_TRUE(enclosing_start(pair, start));
  detail::ExpandingPolytope polytope;
  const detail::ExpansionResult e = polytope.run(pair.a, pair.b, start, 1e-12, kIterations);
  ASSERT_TRUE(e.verified);
  ASSERT_GE(e.best_face_index, 0);
  // The facet: A's top face less B's bottom face, at height 0.01 along z (in frame units).
  const Scalar height = detail::times_power_of_two(0.01, -pair.frame.exponent);
  std::mt19937_64 rng(30);
  std::uniform_real_distribution<Scalar> across(-0.65, 0.85);
  int crossed = 0;
  int elsewhere = 0;
  int on_facet = 0;
  for (int trial = 0; trial < 200; ++trial) {
    // A ray through the facet's interior (x in (-0.7, 0.9) and y in (-0.5, 0.8) less margins).
    const Vector3 d = Vector3(detail::times_power_of_two(across(rng), -pair.frame.exponent),
                              detail::times_power_of_two(across(rng) * 0.8, -pair.frame.exponent),
                              height)
                          .normalized();
    std::array<detail::DifferencePoint, 3> corners;
    const int f = polytope.face_crossed(e.best_face_index, d, corners);
    if (f < 0) continue;
    ++crossed;
    elsewhere += f != e.best_face_index;
    Eigen::Matrix3d m;
    for (int k = 0; k < 3; ++k) {
      const detail::DifferencePoint& c = corners[k];
      EXPECT_EQ(c.w, pair.a.vertex(c.ia) - pair.b.vertex(c.ib));
      m.col(k) = c.w;
    }
    on_facet += (m.row(2).array() - height).abs().maxCoeff() <= 1e-15;
    // d = m c with every c_k >= 0: the ray crosses the face.
    const Vector3 c = m.partialPivLu().solve(d);
    EXPECT_GE(c.minCoeff(), -1e-12) << "trial " << trial;
  }
  EXPECT_GT(crossed, 150);
  // The facet's faces are where most of these rays cross (200, 133 and 134 when written).
  EXPECT_GT(elsewhere, 0);
  EXPECT_GT(on_facet, 100);
}

// A start too flat to make a surface (four copies of one point of A - B) proves nothing and
// leaves nothing to resume, in a new polytope and in one that expanded a surface before. The
// penetration solver resumes the expansion it stopped at 2^-12 for a cylinder's or a cone's side
// (penetration.cpp): a resume after a flat start read an empty heap, or went on from the earlier
// surface's faces, and met a support along a zero normal, which the solver measured as a
// separation of 0 and certified (a cone's rim 0.05 deep in a small cylinder,
// ConeSide.ANearerRimRefusesTheSidesBound, in a new process).
TEST(Penetration, AStartTooFlatForASurfaceLeavesNothingToResume) {
  const ConvexPolyhedron body_a(box({0, 0, 0}, {1, 1, 1}));
  const ConvexPolyhedron body_b(box({0.5, 0.2, 0.4}, {1.3, 0.9, 1.2}));
  const detail::FramedPair pair =
      detail::frame_validated_pair(body_a, Pose(), body_b, Pose(), 1e-9);
  const detail::DifferencePoint point{pair.a.vertex(0) - pair.b.vertex(0), 0, 0};
  const std::array<detail::DifferencePoint, 4> flat = {point, point, point, point};
  const auto expect_nothing = [](const detail::ExpansionResult& e) {
    EXPECT_FALSE(e.verified);
    EXPECT_EQ(e.best_separation, -std::numeric_limits<Scalar>::infinity());
  };
  detail::ExpandingPolytope fresh;
  expect_nothing(fresh.run(pair.a, pair.b, flat, 1e-9, kIterations));
  expect_nothing(fresh.resume(pair.a, pair.b, 1e-9, kIterations));
  std::array<detail::DifferencePoint, 4> start;
  ASSERT_TRUE(enclosing_start(pair, start));
  detail::ExpandingPolytope used;
  ASSERT_TRUE(used.run(pair.a, pair.b, start, 1e-12, kIterations).verified);
  expect_nothing(used.run(pair.a, pair.b, flat, 1e-9, kIterations));
  expect_nothing(used.resume(pair.a, pair.b, 1e-9, kIterations));
}

// Two overlapping cylinders: the expansion converges on a patch of faces a little tilted from
// each other, often on a face other than its best normal's, which it has replaced by then. Its
// near_best_face must be a live face there, and corners_around must give that face's corners
// and its neighbours', each once, each a point of A - B; a replaced face gives none.
TEST(Penetration, CornersAroundTheBestFaceOfACurvedSurface) {
  std::mt19937_64 rng(44);
  std::uniform_real_distribution<Scalar> size(0.2, 1.0);
  std::uniform_real_distribution<Scalar> angle(-3.0, 3.0);
  std::uniform_real_distribution<Scalar> shift(-0.15, 0.15);
  const std::array<Vector3, 4> directions = {Vector3(1, 1, 1), Vector3(1, -1, -1),
                                             Vector3(-1, 1, -1), Vector3(-1, -1, 1)};
  int runs = 0;
  int replaced = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Cylinder a(size(rng), size(rng));
    const Cylinder b(size(rng), size(rng));
    Pose pose_b;
    pose_b.rotation = rotation(angle(rng), angle(rng), angle(rng));
    pose_b.translation = Vector3(shift(rng), shift(rng), shift(rng));
    const detail::FramedPair pair = detail::frame_validated_pair(a, Pose(), b, pose_b, 1e-9);
    std::array<detail::DifferencePoint, 4> start;
    for (int k = 0; k < 4; ++k) {
      const int ia = pair.a.support_index(directions[k]);
      const int ib = pair.b.support_index(-directions[k]);
      start[k] = {pair.a.vertex(ia) - pair.b.vertex(ib), ia, ib};
    }
    if (!detail::encloses_origin({start[0].w, start[1].w, start[2].w, start[3].w})) continue;
    detail::ExpandingPolytope polytope;
    const detail::ExpansionResult e = polytope.run(pair.a, pair.b, start, 1e-9, kIterations);
    ASSERT_TRUE(e.verified) << "trial " << trial;
    ASSERT_GE(e.best_face_index, 0);
    ++runs;
    std::array<detail::DifferencePoint, detail::ExpandingPolytope::kMostNearbyCorners> corners;
    const int count = polytope.corners_around(e.near_best_face, corners);
    // A face and its neighbours': at least the face's three corners and one across each edge.
    EXPECT_GE(count, 4) << "trial " << trial;
    for (int i = 0; i < count; ++i) {
      EXPECT_EQ(corners[i].w, pair.a.vertex(corners[i].ia) - pair.b.vertex(corners[i].ib));
      for (int j = 0; j < i; ++j) {
        EXPECT_FALSE(corners[i].ia == corners[j].ia && corners[i].ib == corners[j].ib);
      }
    }
    if (e.near_best_face != e.best_face_index) {
      ++replaced;
      EXPECT_EQ(polytope.corners_around(e.best_face_index, corners), 0) << "trial " << trial;
    }
  }
  EXPECT_GT(runs, 100);
  // (14 of 194 when written.)
  EXPECT_GT(replaced, 0);
}

TEST(Penetration, TouchingAndNearlyTouchingFaces) {
  const VertexMatrix unit = box({0, 0, 0}, {1, 1, 1});
  for (const Scalar gap : {0.0, 1e-16, -1e-16, 1e-12, -1e-12}) {
    const VertexMatrix b = box({1 + gap, 0.2, 0.3}, {2, 1.2, 1.3});
    const PenetrationBounds r = check(unit, b, "gap " + std::to_string(gap));
    EXPECT_NEAR(r.lower, gap, 1e-13);
  }
  // Coplanar faces: a cube whose faces are split by extra points, touching and overlapping.
  VertexMatrix split(12, 3);
  split << box({0, 0, 0}, {1, 1, 1}), 0.5, 0.5, 0, 0.5, 0.5, 1, 0, 0.5, 0.5, 1, 0.5, 0.5;
  check(split, box({0.25, 0.25, 1}, {0.75, 0.75, 2}), "coplanar, touching");
  check(split, box({0.25, 0.25, 0.99}, {0.75, 0.75, 2}), "coplanar, overlapping");
}

TEST(Penetration, FlatCollinearAndPointBodies) {
  const VertexMatrix unit = box({0, 0, 0}, {1, 1, 1});
  const VertexMatrix square =
      rows({{0.2, 0.2, 0.7}, {1.5, 0.2, 0.7}, {1.5, 1.5, 0.7}, {0.2, 1.5, 0.7}});
  const VertexMatrix segment = rows({{0.5, 0.4, -1}, {0.5, 0.4, 0.8}});
  const VertexMatrix point = rows({{0.3, 0.6, 0.9}});
  EXPECT_NEAR(check(unit, square, "square in cube").lower, -0.3, 1e-12);
  EXPECT_NEAR(check(unit, segment, "segment through cube").lower, -0.4, 1e-12);
  EXPECT_NEAR(check(unit, point, "point in cube").lower, -0.1, 1e-12);
  EXPECT_NEAR(check(square, unit, "cube and square, swapped").lower, -0.3, 1e-12);
  // Flat against flat: coplanar squares overlap by touching (the difference is flat).
  const VertexMatrix other = rows({{1, 1, 0.7}, {2, 1, 0.7}, {2, 2, 0.7}, {1, 2, 0.7}});
  EXPECT_NEAR(check(square, other, "coplanar squares").lower, 0, 1e-13);
  // Crossing squares, segments and points in every combination of dimensions.
  const VertexMatrix upright = rows({{0.5, 0.5, 0}, {0.5, 1, 0}, {0.5, 1, 1}, {0.5, 0.5, 1}});
  check(square, upright, "crossing squares");
  const VertexMatrix cross = rows({{0.5, -1, 0.7}, {0.5, 2, 0.7}});
  check(square, segment, "segment through square");
  EXPECT_NEAR(check(segment, cross, "crossing segments").lower, 0, 1e-13);
  EXPECT_NEAR(check(segment, rows({{0.5, 0.4, 0.1}}), "point on segment").lower, 0, 1e-13);
  EXPECT_NEAR(check(square, rows({{0.7, 0.9, 0.7}}), "point in square").lower, 0, 1e-13);
  EXPECT_NEAR(check(point, point, "one point twice").lower, 0, 1e-13);
  EXPECT_NEAR(check(segment, rows({{0.5, 0.4, -0.3}, {0.5, 0.4, 2}}), "collinear segments").lower,
              0, 1e-13);
  // Repeated points change nothing.
  VertexMatrix repeated(16, 3);
  repeated << unit, unit;
  check(repeated, transformed(unit, Eigen::Matrix3d::Identity(), {0.3, 0.4, 0.5}), "repeated");
}

TEST(Penetration, PointTouchingSegmentHasCoincidentWitnesses) {
  // The dual solver's witnesses were 0.1-0.5 apart here for a distance of -2e-7.
  const VertexMatrix segment = rows({{-0.4, 0.1, 0.2}, {0.6, -0.3, 0.1}});
  for (const Scalar t : {0.0, 0.3, 0.75, 1.0}) {
    const Vector3 on = (1 - t) * segment.row(0).transpose() + t * segment.row(1).transpose();
    const PenetrationBounds r =
        check(rows({on}), segment, "t = " + std::to_string(t), Vector3(0.3, 1, 0.2));
    EXPECT_NEAR(r.lower, 0, 1e-13);
    EXPECT_LE((r.point_b - r.point_a).norm(), 1e-12);
    EXPECT_LE((r.point_a - on).norm(), 1e-12);
  }
}

TEST(Penetration, NeedlesAndSlivers) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d turn = rotation(unit(rng) * 3, unit(rng) * 3, unit(rng) * 3);
    // A needle: length 2, width 1e-5; a sliver: a tetrahedron 1e-7 thick.
    const VertexMatrix needle =
        transformed(rows({{-1, 0, 0}, {1, 0, 0}, {0, 1e-5, 0}, {0, 0, 1e-5}, {0.2, -1e-5, -1e-5}}),
                    turn, Vector3(unit(rng), unit(rng), unit(rng)) * 0.2);
    const VertexMatrix sliver =
        rows({{-1, -1, 0}, {1, -1, 1e-7}, {0, 1, -1e-7}, {0.1, 0.2, 1e-7}, {0.3, -0.4, 0}});
    check(needle, sliver, "needle and sliver " + std::to_string(trial));
    check(sliver, random_points(rng, 12, Vector3::Zero(), 0.5),
          "sliver and blob " + std::to_string(trial));
  }
}

TEST(Penetration, LargeSizeRatios) {
  const VertexMatrix unit = box({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5});
  const VertexMatrix tiny = box({-0.5e-6, -0.5e-6, -0.5e-6}, {0.5e-6, 0.5e-6, 0.5e-6});
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  EXPECT_NEAR(check(unit, transformed(tiny, I, {0.1, 0.2, 0.3}), "tiny inside").lower,
              -0.2 - 0.5e-6, 1e-12);
  EXPECT_NEAR(check(unit, transformed(tiny, I, {0.5, 0.2, 0.1}), "tiny on a face").lower, -0.5e-6,
              1e-12);
  check(transformed(tiny, rotation(0.2, 0.4, 0.1), {0.5, 0.5, 0.5}), unit, "tiny at a corner");
}

TEST(Penetration, SeparatedPairsGetValidBounds) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  for (int trial = 0; trial < 30; ++trial) {
    const VertexMatrix a = random_points(rng, 6 + trial, Vector3::Zero(), 0.5);
    const Vector3 offset = Vector3(unit(rng), unit(rng), unit(rng)).normalized() * 1.5;
    const PenetrationBounds r =
        check(a, random_points(rng, 9, offset, 0.5), "trial " + std::to_string(trial),
              Vector3::Zero(), kTolerance, false);
    EXPECT_GT(r.upper, 0);
  }
}

TEST(Penetration, LargeSpherePointHulls) {
  std::mt19937_64 rng(9);
  for (const int n : {100, 300}) {
    VertexMatrix a = random_points(rng, n, Vector3::Zero(), 1);
    VertexMatrix b = random_points(rng, n, Vector3::Zero(), 1);
    a.rowwise().normalize();
    b.rowwise().normalize();
    b.rowwise() += Vector3(0.8, 0.5, -0.3).transpose();
    check(a, b, "spheres of " + std::to_string(n));
  }
}

TEST(Penetration, IterationCapStillGivesValidBounds) {
  std::mt19937_64 rng(10);
  const VertexMatrix a = random_points(rng, 200, Vector3::Zero(), 1);
  const VertexMatrix b = random_points(rng, 200, Vector3(0.2, 0.1, 0), 1);
  const Hull ha = compute_hull(a);
  const Hull hb = compute_hull(b);
  const Scalar exact = oracle_signed_distance(a, b);
  for (const int cap : {1, 2, 5}) {
    const PenetrationBounds r = penetration(a, ha, b, hb, Vector3::Zero(), 0, cap);
    EXPECT_LE(r.lower, exact + kOracleSlack);
    EXPECT_GE(r.upper, exact - kOracleSlack);
    EXPECT_FALSE(r.proven);
  }
}

}  // namespace
}  // namespace swarmcollide
