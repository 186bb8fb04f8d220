#include "ball_screen.hpp"

#include <utility>

#include "../geometry/normalise.hpp"
#include "../solvers/answer.hpp"
#include "verdict.hpp"

namespace swarmcollide::detail {

namespace {

// The body's ball radius, as kept with its derived data.
struct BallRadius {
  Scalar radius;
};

}  // namespace

Scalar ball_radius(const ConvexPolyhedron& body) {
  return body
      .derived<BallRadius>([&body] {
        // Each norm is within a few roundoffs of the exact distance of its point from the box
        // centre (the centred points are themselves rounded relative to it); 2^-40 is far more.
        const Scalar largest = body.centred_vertices().rowwise().norm().maxCoeff();
        return BallRadius{largest * (1 + 0x1p-40)};
      })
      .radius;
}

std::optional<DistanceResult> collision_by_balls(const FramedPair& pair, Scalar radius_a,
                                                 Scalar radius_b, Method method) {
  // The box centres land at the bodies' offsets; the balls scale with the frame, exactly.
  const Vector3 between = pair.b.offset() - pair.a.offset();
  const Scalar centres = between.norm();
  const Scalar lower = centres - times_power_of_two(radius_a, -pair.a.exponent()) -
                       times_power_of_two(radius_b, -pair.b.exponent());
  // A cheap test first: most pairs that reach here are not apart by their balls.
  if (!(lower > pair.tolerance)) return std::nullopt;
  Answer answer;
  answer.lower = lower;
  answer.direction = between / centres;
  answer.point_a = pair.a.vertex(0);
  answer.point_b = pair.b.vertex(0);
  answer.upper = (answer.point_b - answer.point_a).norm();
  answer.weights_a = ConvexWeights(pair.a.size(), {0, 0, 0, 0}, {1, 0, 0, 0}, 1);
  answer.weights_b = ConvexWeights(pair.b.size(), {0, 0, 0, 0}, {1, 0, 0, 0}, 1);
  // The rounding margins are the verdict's: it is proven only beyond them.
  if (!verdict_proven(pair, answer)) return std::nullopt;
  return finish_result(pair, std::move(answer), method, Goal::verdict);
}

}  // namespace swarmcollide::detail
