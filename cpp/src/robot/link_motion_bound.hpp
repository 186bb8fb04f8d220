// How far the geometries of a robot can move along a straight segment in joint space (Schwarzer,
// Saha and Latombe's motion bounds); private to the library's sources.
#pragma once

#include <vector>

#include "swarmcollide/robot/pair_filter.hpp"
#include "swarmcollide/robot/robot_model.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// Bounds on how fast the distance between two geometries of a robot can shrink while the joints
/// move from `q0` to `q1` along the straight segment q(t) = q0 + t (q1 - q0), t in [0, 1].
///
/// Link L's frame is `F_n = O_1 M_1 ... O_n M_n` over the joints J_1 ... J_n from the root to L
/// (O_i the joint origin, M_i its motion: a turn about the unit axis a_i through the origin of
/// the child's frame, or a slide along it). Changing one joint value by d moves a point p of L:
/// a turn of J_i by d moves it by at most |F_i| |d| dist(p, axis_i) (a chord is shorter than its
/// arc), a slide by |F_i| |d|. Between two configurations on the segment the joints can be changed
/// one at a time, every intermediate configuration having each joint value within its range over
/// the segment, so p moves by at most sum_i |F_i| |d_i| r_i(L), where r_i(L) bounds the distance
/// from axis_i to L's points at every such configuration: in J_i's child frame the points are
/// `O_{i+1} M_{i+1} (...)`, so r_i <= |perp_i(O_{i+1}.t)| + |O_{i+1}.R| (s_{i+1} + z_{i+1}), with
/// z_k bounding the points' distance from F_k's origin (z_{k-1} <= |O_k.t| + |O_k.R| (s_k + z_k),
/// z_n the geometry's reach about L's origin) and s_k the largest slide of J_k over the segment
/// (0 for a turn). For i = n the exact distance of the geometry's points to the axis is used.
/// |d_i| = rate_i |q1 - q0| h over a time h (rate: a mimic joint's multiplier).
///
/// The distance from axis_i to L's points changes only through the joints below J_i (those
/// above move the axis and the points alike, J_i's turn keeps it), by at most B_i = sum_{k > i}
/// of their speeds over the whole motion, so it is also measured: with d_i(q0) and d_i(q1) the
/// distances from the placed axis to the corners of the geometry's box at the two ends, every
/// configuration in the box of the joint ranges is within x of q0's and B_i - x of q1's (some x
/// in [0, B_i]), and r_i <= (d_i(q0) + d_i(q1) + B_i) / 2, taken from the bottom of the chain
/// up (B_i needs the speeds below) where it is smaller than the chain's bound.
///
/// A pair may leave out the joints both chains share (the joints above their links' common
/// ancestor, a common prefix of the two chains in a tree): changing a shared joint applies the
/// same map `F_i -> F_i Rot(a_i, d)` (or a common translation, for a slide) to both geometries,
/// which leaves every distance between their points unchanged when F_i is a rotation. The joint
/// origins are rigid only to validate_pose's tolerance, so F_i^T F_i = I + S with |S| <= sigma_i:
/// then |F_i x| - |x| changes by at most sigma_i |d| |x| / sqrt(1 - sigma_i) for |x| a point
/// difference turned by d, and a shared turn costs that, with |x| <= Z_a + Z_b (the points'
/// distances from the world's origin); a shared slide costs nothing.
///
/// Near a configuration the motion passes through, the distances from the axes are known rather
/// than bounded: `local_speed` takes d_i, the distance from axis_i (placed there) to the
/// geometry's bounding ball, plus its radius. A turn of J_i keeps every point's distance from
/// axis_i, and the joints above J_i move both rigidly, so that distance changes only through the
/// joints below J_i, at most at their speed bound v_i (the sum over the chain below J_i). At a
/// time s from there, r_i(s) <= d_i + |s| v_i, so the pair closes at most at `at + |s| growth`,
/// with at = sum_i |dq_i| d_i and growth = sum_i |dq_i| v_i, over the same joints as above.
///
/// Along a fixed unit direction n (a query's separating direction, along which its lower bound is
/// the separation of the two bodies), a turn of J_i moves a point p at the rate |n . (a_i x (p -
/// o_i))| <= |n x a_i| dist(p, axis_i), and a slide at |n . a_i|: a turn about n, or a slide
/// across it, does not change the separation. The axis a_i turns at most at the rates of the
/// turns above J_i (Omega_i), so at a time s from the configuration |n x a_i(s)| <= c_i + |s|
/// Omega_i, and the separation shrinks at most at `sum_i |dq_i| (c_i + |s| Omega_i) (d_i + |s|
/// v_i)` over every joint of both chains.
///
/// A pair whose chains share joints is measured in the frame C of the link where they part (the
/// child of the last shared joint) rather than the world's: the shared joints move C alone, so in
/// C's coordinates the two bodies move by the other joints only, and the separation along a
/// direction fixed in C (one that turns with C in the world) shrinks by their terms alone, the
/// turns' Omega summed from the first joint below C. C's frame is rigid only to within sigma_C
/// (its chain's), R^T R = I + S with |S| <= sigma_C at every configuration (the turns are exact
/// rotations): with x the points in C's coordinates, p = R x + T, a world separation `apart`
/// along the unit n is a separation apart / |R^T n| >= apart / sqrt(1 + sigma_C) along the unit m
/// = R^T n / |R^T n| in C's coordinates, and a separation g along m there is a distance at least
/// |R (x_b - x_a)| >= sqrt(1 - sigma_C) g in the world at any configuration. So the distance
/// stays at least `apart (1 - sigma_C) - closing`, where `closing` is the bound above in C's
/// coordinates. Those coordinates differ from the world's measurements of the axes, the
/// direction and the distances (the placed chains, taken in the world) by the factor R: a
/// direction or an axis made unit turns by at most 2 |E| / (1 - |E|) with R = Q (I + E) (Q
/// orthogonal, |E| <= sigma_C), so |m x a_i| exceeds the world's |n x a_i| by at most 4.01
/// sigma_C, and lengths differ by at most the factor 1 + sigma_C, covered by 1 + 4 sigma_C on
/// every term. `loss` is the fraction 2 sigma_C of the gap lost (0 in the world's frame).
///
/// The margin covers the rounding: of q(t) (a few roundoffs of the joint values, times the speed
/// coefficients), of the forward kinematics (64 roundoffs of Z per joint on the chain) and of the
/// queries' frames (256 roundoffs of Z_a + Z_b).
class LinkMotionBound {
 public:
  /// The model's part of the bounds (chains, the joint origins' deviation from rigid, every
  /// geometry's reach); the model must outlive this.
  explicit LinkMotionBound(const RobotModel& model);

  /// Sets the motion: `q0` and `q1` hold one admitted value per degree of freedom.
  void set_motion(const Scalar* q0, const Scalar* q1);
  /// The same, given the link poses at `q0` and `q1` (link_poses).
  void set_motion(const Scalar* q0, const Scalar* q1, const std::vector<Pose>& start_links,
                  const std::vector<Pose>& end_links);

  /// A bound on how fast `pair`'s distance can shrink, per unit of time, forwards or backwards.
  Scalar pair_speed(const GeometryPair& pair) const;
  /// The closing speed of `pair` around a configuration whose link poses are `links`, with its
  /// geometries at `pose_a` and `pose_b`: over a time h either way from it, the pair's distance
  /// shrinks by at most `at h + growth h^2 / 2`.
  struct LocalSpeed {
    Scalar at;
    Scalar growth;
  };
  LocalSpeed local_speed(const GeometryPair& pair, const std::vector<Pose>& links,
                         const Pose& pose_a, const Pose& pose_b) const;

  /// How fast the separation of `pair` along the unit `direction` can shrink around the
  /// configuration of `links`: over a time h either way, a separation `apart` there leaves the
  /// pair at least `apart (1 - loss) - (linear h + quadratic h^2 / 2 + cubic h^3 / 3)` apart (for
  /// a pair whose chains share joints, along the direction turned with the frame where they part;
  /// `common_link`).
  struct DirectionalSpeed {
    Scalar linear;
    Scalar quadratic;
    Scalar cubic;
    Scalar loss;
  };
  DirectionalSpeed directional_speed(const GeometryPair& pair, const Vector3& direction,
                                     const std::vector<Pose>& links, const Pose& pose_a,
                                     const Pose& pose_b) const;

  /// One geometry's chain placed at a configuration: per joint of its link's chain (root first),
  /// the joint's axis in the world and the reach of the geometry's bounding ball about it (its
  /// centre's distance from the axis plus its radius and the frames' rounding), what
  /// `local_speed` and `directional_speed` take from the configuration. Computed once, it serves
  /// every pair of the geometry there (zero for fixed joints; nothing for an obstacle, whose
  /// chain no bound reads). The vectors may run past the chain: what is there is not read.
  struct PlacedChain {
    std::vector<Vector3> axis;
    std::vector<Scalar> reach;
    /// Per joint, its child frame's origin (a point of its axis); the geometry's bounding ball's
    /// centre and its radius with the frames' rounding (what `reach` adds to the distance).
    std::vector<Vector3> origin;
    Vector3 centre = Vector3::Zero();
    Scalar radius = 0;
  };
  /// The twist bound along a unit direction n: over a time h forward (backward) a separation
  /// `apart` along n leaves the pair at least `apart (1 - loss) - (forward h + a0 h^2 / 2 + a1
  /// h^3 / 6 + a2 h^4 / 12)` apart (`backward` in place of `forward`; `loss` directional_speed's).
  ///
  /// Proof. In the frame C the pair is measured in, a geometry's points move with the twist of
  /// its joints below C: x' = sum_k w_k a_k x (x - o_k) over its turns (rate w_k, unit axis a_k
  /// through o_k) plus sum_k w_k a_k over its slides, i.e. x' = V + W x x with W = sum w_k a_k
  /// over the turns. For a point pair (x in A, y in B) f = n . (y - x) has f(t + h) = f(t) + h
  /// f'(t) + int_0^h (h - s) f''(t + s) ds. Every point lies in the bounding ball (c, r), so
  /// n . x' >= n . x'(c) - r |n x W| and <= n . x'(c) + r |n x W|: f'(t) >= low and <= high
  /// (forward = -low, backward = high, each with the rounding added). The acceleration of a
  /// material point is x'' = sum_k (Omega_k x v_k(x) + w_k a_k x v_{>=k}(x)), with v_k(x) the
  /// velocity joint k alone gives x, v_{>=k} the sum from k down, and Omega_k the angular velocity
  /// of the frames above k below C (differentiate w_k a_k x (x - o_k): a_k turns at Omega_k, o_k
  /// moves with the frames above, and (A x B) x C + B x (A x C) = A x (B x C) folds the two
  /// Omega_k terms into one; a slide's v_k = w_k a_k turns at Omega_k alone). With |v_k| <= S_k =
  /// |w_k| (d_k + s B_k) (d_k the reach about k's axis at the sample, B_k the speed of the joints
  /// below it over the motion: they alone change that distance; |w_k| for a slide) and |n x a_k|
  /// <= c_k + s Omega_k, |n . x''| <= sum_k (Omega_k S_k + |w_k| (c_k + s Omega_k) sum_{j >= k}
  /// S_j) = a0 + a1 s + a2 s^2 at a time s either way, and the integral gives the h^2, h^3, h^4
  /// terms. The frames' deviation from rigid and the placed chains' rounding are the factors and
  /// slacks directional_speed takes (1 + 4 sigma on every rate, 8u + 4.01 sigma_C on |n x a|),
  /// with 64u + 8 sigma of |c - o_k| per turn for the rounding of the cross products.
  struct TwistSpeed {
    Scalar forward;
    Scalar backward;
    Scalar a0;
    Scalar a1;
    Scalar a2;
  };
  TwistSpeed twist_speed(const GeometryPair& pair, const Vector3& direction, const PlacedChain& a,
                         const PlacedChain& b) const;
  /// Geometry `g`'s chain at the configuration of `links`, the geometry at `pose`, into `placed`;
  /// the joints before `first` in the chain are left as they were (a pair's shared joints, which
  /// neither speed of the pair reads: `shared_count`).
  void place_chain(int g, const std::vector<Pose>& links, const Pose& pose, PlacedChain& placed,
                   std::size_t first = 0) const;
  /// place_chain at the motion's start (`end` 0) or end (1), `links` the link poses set_motion
  /// was given there: the turning joints' axes are set_motion's (the same expressions, made once
  /// per motion rather than once per geometry on the joint's chain).
  void place_end_chain(int g, int end, const std::vector<Pose>& links, const Pose& pose,
                       PlacedChain& placed) const;
  /// local_speed from the two geometries' placed chains (the same bound, bit for bit).
  LocalSpeed local_speed(const GeometryPair& pair, const PlacedChain& a,
                         const PlacedChain& b) const;
  /// directional_speed from the two geometries' placed chains (the same bound, bit for bit).
  DirectionalSpeed directional_speed(const GeometryPair& pair, const Vector3& direction,
                                     const PlacedChain& a, const PlacedChain& b) const;

  /// The number of joints at the head of `pair`'s two chains that both share (0 with an
  /// obstacle): local_speed and directional_speed read the placed chains from there on.
  std::size_t shared_count(const GeometryPair& pair) const;

  /// The link whose frame `directional_speed` measures `pair` in: the child of the last joint
  /// the two chains share (-1: none, the world's frame).
  int common_link(const GeometryPair& pair) const;

  /// sigma_C of the frame `common_link` names (0 for the world's): a bound on the norm of R^T R
  /// - I for its rotation R at any configuration.
  Scalar common_sigma(const GeometryPair& pair) const;

  /// A bound on how far the computed poses of `pair` at any time of the motion can be from the
  /// exact ones, measured as the change of their distance.
  Scalar pair_margin(const GeometryPair& pair) const;

 private:
  // place_chain, the turning joints' axes read from `turn_axes` (per joint) when it is given.
  void place_chain_from(int g, const std::vector<Pose>& links, const Pose& pose,
                        PlacedChain& placed, std::size_t first,
                        const std::vector<Vector3>* turn_axes) const;

  // The number of joints the chains of links `a` and `b` share (0 with an obstacle, -1).
  std::size_t shared_joints(int a, int b) const;

  // sigma_C of the frame where link `link`'s chain parts from another after `shared` joints.
  Scalar sigma_after(int link, std::size_t shared) const;

  struct GeometryMotion {
    // Per joint of the link's chain (root first): the speed of the geometry's points due to it,
    // per unit of time.
    std::vector<Scalar> speed;
    // A bound on the points' distance from the world's origin.
    Scalar extent = 0;
    // The displacement of the points from the rounding of q(t).
    Scalar rounding = 0;
    // The sum of `speed`.
    Scalar total = 0;
    // Per joint of the chain, the sum of the speeds of the joints below it (they alone change
    // the points' distance from its axis), rounded up.
    std::vector<Scalar> speed_below;
    // The chain's moving joints as the local and directional speeds read them, root first: the
    // index in the chain, whether it turns, its change, 1 + 4 sigma of the chain to it, and
    // `speed_below` there.
    struct Term {
      std::size_t k;
      bool turn;
      Scalar change;
      Scalar rigid;
      Scalar below;
      // Its signed rate (the joint value's change over the motion).
      Scalar velocity;
    };
    std::vector<Term> terms;
  };

  // Adds to `speed` what the first `shared` joints of link `link`'s chain (those both links of a
  // pair share) cost a pair whose points lie within `extents` of the world's origin: a shared
  // turn leaves distances unchanged but for the origins' deviation from rigid.
  void add_shared_turns(Scalar& speed, int link, std::size_t shared, Scalar extents) const;

  const RobotModel& model_;
  // Per link, its chain of joints from the root down (fixed joints included).
  std::vector<std::vector<int>> chains_;
  // Per two links a and b, at a * (number of links) + b, the number of joints their chains share
  // (read for every pair by every speed: a table rather than the chains compared each time).
  std::vector<std::size_t> shared_;
  // Per joint, sigma of its origin, and of the product of the origins from the root to it.
  std::vector<Scalar> origin_sigma_;
  std::vector<Scalar> chain_sigma_;
  // Per joint: bounds on the spectral norms of its origin and of the product of the origins from
  // the root to it, its origin's length, and its origin's distance from the axis of the joint
  // above it (0 at the root).
  std::vector<Scalar> origin_norm_;
  std::vector<Scalar> chain_norm_;
  std::vector<Scalar> origin_length_;
  std::vector<Scalar> origin_off_axis_;
  // Per geometry, its core points' reach about its link's origin and about its link's parent
  // joint's axis.
  std::vector<Scalar> origin_reach_;
  std::vector<Scalar> axis_reach_;
  // Per motion: each joint's change (absolute), its largest slide, the rounding of its value.
  std::vector<Scalar> change_;
  // Per motion: each joint's signed change (its value's rate).
  std::vector<Scalar> velocity_;
  std::vector<Scalar> slide_;
  std::vector<Scalar> value_error_;
  // Per motion: each turning joint's axis in the world at the two ends.
  std::vector<Vector3> start_axes_;
  std::vector<Vector3> end_axes_;
  std::vector<GeometryMotion> geometries_;
  // Scratch: the link poses at the ends, the chain's bounds on one geometry's distances from
  // the axes.
  std::vector<Pose> start_links_;
  std::vector<Pose> end_links_;
  std::vector<Scalar> turns_;
  // A box's 8 corners, one array per coordinate, so that they are placed and their distances
  // from an axis taken side by side (two corners an instruction rather than one).
  struct BoxCorners {
    Eigen::Array<Scalar, 8, 1> x;
    Eigen::Array<Scalar, 8, 1> y;
    Eigen::Array<Scalar, 8, 1> z;

    // Corner c has box.max's coordinate i where bit i of c is set, box.min's elsewhere.
    static BoxCorners of(const Aabb& box);
    // The corners placed by `pose`: pose.rotation * corner + pose.translation, the same
    // products summed in the same order as the matrix product's.
    BoxCorners placed(const Pose& pose) const;
    // The largest distance of the corners from the line through `origin` along the unit
    // `axis`: the largest off_axis(corner - origin, axis), its expressions in its order.
    Scalar farthest_off_axis(const Vector3& origin, const Vector3& axis) const;
  };
  // Per geometry, its box's corners in its own frame.
  std::vector<BoxCorners> box_corners_;
};

}  // namespace swarmcollide::detail
