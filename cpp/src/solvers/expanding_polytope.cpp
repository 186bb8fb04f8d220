#include "expanding_polytope.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

namespace swarmcollide::detail {

namespace {

// Bound on the error of det(p, q, r) computed as p . (q x r) from points each rounded by one
// roundoff per coordinate (they are differences x_i - y_j): the cross product and the dot product
// add at most 5 roundoffs on sqrt(2) |p| |q| |r| and the rounded inputs another 3 |p| |q| |r|
// (to first order); 16 roundoffs cover both, doubled here. The norms are computed once, when
// their point joins the polytope.
Scalar determinant_bound(Scalar norm_p, Scalar norm_q, Scalar norm_r) {
  return 32 * kRoundoff * norm_p * norm_q * norm_r;
}

// True when det(p, q, r) is provably positive, given the points' norms. Where the bound
// underflows, so may the determinant's terms, and no sign is trusted.
bool positively_oriented(const Vector3& p, const Vector3& q, const Vector3& r, Scalar norm_p,
                         Scalar norm_q, Scalar norm_r) {
  const Scalar bound = determinant_bound(norm_p, norm_q, norm_r);
  return bound >= std::numeric_limits<Scalar>::min() && p.dot(q.cross(r)) > bound;
}

// The triangle (p, q, r) along `n`: false when `n` has no length; else `n` becomes its unit
// vector and `lowest`, `highest` the corners' least and greatest heights along it. Always inline:
// every face made asks it, and its call out of line was a tenth of making one.
[[gnu::always_inline]] inline bool heights_along(Vector3& n, const Vector3& p, const Vector3& q,
                                                 const Vector3& r, Scalar& lowest,
                                                 Scalar& highest) {
  const Scalar length = n.norm();
  if (!(length > 0)) return false;
  n /= length;
  const Scalar hp = n.dot(p);
  const Scalar hq = n.dot(q);
  const Scalar hr = n.dot(r);
  lowest = std::min({hp, hq, hr});
  highest = std::max({hp, hq, hr});
  return true;
}

// The corner after each of a face's: a table, as `% 3` of an index read at run time costs a
// multiplication and shifts (cone asks it of every horizon edge, linked of every face verified).
constexpr std::array<int, 3> kNext = {1, 2, 0};

using HeapEntry = std::pair<Scalar, int>;
constexpr auto kNearestFirst = std::greater<HeapEntry>();

// Puts `entry` in place of the heap's first (nearest) one: one pass down the heap where popping
// the first and pushing `entry` would make two.
void replace_nearest(std::vector<HeapEntry>& heap, const HeapEntry& entry) {
  const std::size_t size = heap.size();
  std::size_t i = 0;
  for (std::size_t child = 1; child < size; child = 2 * i + 1) {
    if (child + 1 < size && heap[child + 1] < heap[child]) ++child;
    if (!(heap[child] < entry)) break;
    heap[i] = heap[child];
    i = child;
  }
  heap[i] = entry;
}

}  // namespace

bool ExpandingPolytope::flatten(int f) {
  Face& face = faces_[f];
  const Scalar largest = std::max({norms_[face.v[0]], norms_[face.v[1]], norms_[face.v[2]]});
  if (!(face.top - face.distance > 64 * kRoundoff * largest)) return false;
  const Vector3& p = vertices_[face.v[0]].w;
  const Vector3& q = vertices_[face.v[1]].w;
  const Vector3& r = vertices_[face.v[2]].w;
  const Scalar pq = (q - p).squaredNorm();
  const Scalar qr = (r - q).squaredNorm();
  const Scalar rp = (p - r).squaredNorm();
  // (q - p) x (r - p) = (r - q) x (p - q) = (p - r) x (q - r): the same orientation; make_face
  // took the first.
  if (qr >= pq && qr >= rp) return false;
  Vector3 n = rp >= pq ? Vector3((r - q).cross(p - q)) : Vector3((p - r).cross(q - r));
  Scalar distance = 0;
  Scalar top = 0;
  if (!heights_along(n, p, q, r, distance, top)) return false;
  if (!(top - distance < face.top - face.distance)) return false;
  face.normal = n;
  face.distance = distance;
  face.top = top;
  face.low = distance - 16 * kRoundoff * largest;  // as make_face bounds it
  return true;
}

// Always inline: the expansion makes a few faces a step, in loops whose calls cost more than the
// faces' bookkeeping.
[[gnu::always_inline]] inline bool ExpandingPolytope::make_face(int v0, int v1, int v2,
                                                                Face& face) const {
  const Vector3& p = vertices_[v0].w;
  const Vector3& q = vertices_[v1].w;
  const Vector3& r = vertices_[v2].w;
  const Scalar norm_p = norms_[v0];
  const Scalar norm_q = norms_[v1];
  const Scalar norm_r = norms_[v2];
  if (!positively_oriented(p, q, r, norm_p, norm_q, norm_r)) return false;
  Vector3 n = (q - p).cross(r - p);
  Scalar distance = 0;
  Scalar top = 0;
  if (!heights_along(n, p, q, r, distance, top)) return false;
  face.v = {v0, v1, v2};
  face.normal = n;
  face.distance = distance;
  face.top = top;
  // Any unit vector n bounds the distance of every point of the triangle from below by
  // min_k n . v_k; 16 roundoffs of the largest |v_k| cover the dot products and the rounded
  // vertices (and 8 more on the result, in verify, the rounding of |n|).
  face.low = face.distance - 16 * kRoundoff * std::max({norm_p, norm_q, norm_r});
  face.alive = true;
  return true;
}

// Always inline into expand, its one caller, once per attempt.
[[gnu::always_inline]] inline int ExpandingPolytope::cone(int added) {
  horizon_.clear();
  for (int f : visible_) {
    for (int k = 0; k < 3; ++k) {
      if (seen_stamp_[faces_[f].adj[k]] != stamp_) horizon_.emplace_back(f, k);
    }
  }
  if (horizon_.empty()) return kConeBroken;
  // Vertices are marked with a stamp of their own per attempt (start_stamp_), so an attempt
  // never reads an earlier one's marks.
  ++vertex_stamp_;
  // The cone from the new point: one triangle per horizon edge, all provably oriented, and the
  // horizon one loop through distinct vertices (else the surface would not stay a 2-manifold).
  // Made in place after the surface's faces: a cone that is not kept is overwritten or ignored.
  const std::size_t needed = static_cast<std::size_t>(face_count_) + horizon_.size();
  if (faces_.size() < needed) faces_.resize(2 * needed);
  Face* made = faces_.data() + face_count_;
  for (std::size_t e = 0; e < horizon_.size(); ++e) {
    const Face& f = faces_[horizon_[e].first];
    const int k = horizon_[e].second;
    const int from = f.v[k];
    const int to = f.v[kNext[k]];
    if (!make_face(from, to, added, made[e])) return f.adj[k];
    if (start_stamp_[from] == vertex_stamp_) return kConeBroken;
    start_stamp_[from] = vertex_stamp_;
    start_face_[from] = static_cast<int>(e);
  }
  for (std::size_t e = 0; e < horizon_.size(); ++e) {
    if (start_stamp_[made[e].v[1]] != vertex_stamp_) return kConeBroken;
  }
  return kConeMade;
}

bool ExpandingPolytope::expand(int closest, int added, Scalar ceiling) {
  const Vector3& w = vertices_[added].w;
  const auto sees = [&](int f) { return faces_[f].normal.dot(w) > faces_[f].top; };
  if (!sees(closest)) return false;
  ++stamp_;
  // Grown ahead (each step adds a few faces and a vertex), so not resized at every step.
  const std::size_t count = static_cast<std::size_t>(face_count_);
  if (seen_stamp_.size() < count) seen_stamp_.resize(2 * count, 0);
  if (start_stamp_.size() < vertices_.size()) {
    start_stamp_.resize(2 * vertices_.size(), 0);
    start_face_.resize(2 * vertices_.size(), 0);
  }
  visible_.clear();
  stack_.assign(1, closest);
  seen_stamp_[closest] = stamp_;
  // Every face enters the stack once, so the flood ends after at most face_count_ pops.
  while (!stack_.empty()) {
    const int f = stack_.back();
    stack_.pop_back();
    visible_.push_back(f);
    for (int k = 0; k < 3; ++k) {
      const int g = faces_[f].adj[k];
      if (seen_stamp_[g] != stamp_ && sees(g)) {
        seen_stamp_[g] = stamp_;
        stack_.push_back(g);
      }
    }
  }
  // The faces replaced need not be exactly those that see the new point: the surface stays a
  // proof (verify) whatever faces it replaces, as long as it stays closed and every new face is
  // proven oriented. Where a point only just above the nearest face (the flat facets of curved
  // bodies' differences, a cylinder's cap on a box's face) lies beyond an edge whose other face,
  // nearly coplanar, does not see it, the triangle on that edge cannot be proven oriented; the
  // face across it then joins the replaced ones, a few times at most. Such a face lies above the
  // point, so the new faces may dip below the nearest face, and the bound with them. Stopping
  // there left most of the 20 cylinder and cone pairs in 750 that stayed unproven at a
  // tolerance of 1e-12 (cap-rim contacts, a few 1e-12 short): the surface as it is is verified
  // instead, its bound kept (a verified surface proves it whatever comes after), and the
  // expansion goes on, the next steps lifting the dipping faces as any others.
  for (int widening = 0;; ++widening) {
    const int across = cone(added);
    if (across == kConeMade) {
      if (widening == 0) break;
      const Scalar nearest_low = faces_[closest].low;
      const Face* made = faces_.data() + face_count_;
      const bool dips = std::any_of(made, made + horizon_.size(),
                                    [&](const Face& face) { return face.low < nearest_low; });
      Scalar before = 0;
      if (dips) {
        if (!verify(before)) return false;
        kept_depth_ = std::max(kept_depth_, before);
      }
      break;
    }
    if (across == kConeBroken || widening == kWidenings) return false;
    seen_stamp_[across] = stamp_;
    visible_.push_back(across);
  }
  const int base = face_count_;
  for (std::size_t e = 0; e < horizon_.size(); ++e) {
    const Face& f = faces_[horizon_[e].first];
    const int k = horizon_[e].second;
    Face& face = faces_[base + e];
    face.adj[0] = f.adj[k];
    face.adj_edge[0] = f.adj_edge[k];
    faces_[f.adj[k]].adj[f.adj_edge[k]] = base + static_cast<int>(e);
    faces_[f.adj[k]].adj_edge[f.adj_edge[k]] = 0;
    const int next = start_face_[face.v[1]];
    face.adj[1] = base + next;
    face.adj_edge[1] = 2;
    faces_[base + next].adj[2] = base + static_cast<int>(e);
    faces_[base + next].adj_edge[2] = 1;
  }
  for (int f : visible_) faces_[f].alive = false;
  for (std::size_t e = 0; e < horizon_.size(); ++e) {
    const HeapEntry entry(faces_[base + e].distance, face_count_++);
    if (entry.first > ceiling) continue;
    // The nearest face's entry leads the heap (run drops stale ones before it picks `closest`),
    // and the face is replaced: the first new face takes its place.
    if (e == 0 && heap_.front().second == closest) {
      replace_nearest(heap_, entry);
    } else {
      heap_.push_back(entry);
      std::push_heap(heap_.begin(), heap_.end(), kNearestFirst);
    }
  }
  return true;
}

void ExpandingPolytope::heap_live_faces() {
  heap_.resize(static_cast<std::size_t>(face_count_));
  std::size_t live = 0;
  for (int f = 0; f < face_count_; ++f) {
    if (faces_[f].alive) heap_[live++] = HeapEntry(faces_[f].distance, f);
  }
  heap_.resize(live);
  std::make_heap(heap_.begin(), heap_.end(), kNearestFirst);
}

// Always inline: verify asks it of every live face, and its call was a sixth of what it cost.
[[gnu::always_inline]] inline bool ExpandingPolytope::linked(int i) const {
  const Face& f = faces_[i];
  for (int k = 0; k < 3; ++k) {
    // One unsigned comparison each also rejects the negative.
    const auto g = static_cast<unsigned>(f.adj[k]);
    const auto e = static_cast<unsigned>(f.adj_edge[k]);
    if (g >= static_cast<unsigned>(face_count_) || e > 2) return false;
    const Face& h = faces_[g];
    if (!h.alive || h.adj[e] != i || h.adj_edge[e] != k) return false;
    if (h.v[e] != f.v[kNext[k]] || h.v[kNext[e]] != f.v[k]) return false;
  }
  return true;
}

bool ExpandingPolytope::verify(Scalar& depth_lower) const {
  Scalar nearest = 1e300;
  bool any = false;
  for (int i = 0; i < face_count_; ++i) {
    const Face& f = faces_[i];
    if (!f.alive) continue;
    any = true;
    if (!linked(i)) return false;
    // Its orientation was proven and its bound `low` computed when make_face built it, from
    // these very vertices (a face never changes; the expansion replaces faces whole).
    nearest = std::min(nearest, f.low);
  }
  if (!any) return false;
  depth_lower = std::max(Scalar(0), nearest) * (1 - 8 * kRoundoff);
  return true;
}

ExpansionResult ExpandingPolytope::run(const FramedBody& a, const FramedBody& b,
                                       const std::array<DifferencePoint, 4>& start, Scalar stop_gap,
                                       int max_iterations, bool verify_end) {
  ExpansionResult result;
  kept_depth_ = -1;
  closed_.reset();
  started_from_ = nullptr;
  vertices_.assign(start.begin(), start.end());
  norms_.clear();
  for (const DifferencePoint& v : vertices_) norms_.push_back(v.w.norm());
  face_count_ = 0;
  heap_.clear();
  {
    const Vector3& p = vertices_[0].w;
    if ((vertices_[1].w - p).cross(vertices_[2].w - p).dot(vertices_[3].w - p) > 0) {
      std::swap(vertices_[1], vertices_[2]);
      std::swap(norms_[1], norms_[2]);
    }
  }
  // With vertex 3 behind the triangle (0, 1, 2), these four face away from the opposite corner.
  constexpr int kTetrahedron[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  // The face across each edge k (v[k] -> v[k + 1]) of these, and which of its edges that is (the
  // one running v[k + 1] -> v[k]); verify checks them as every face's.
  constexpr int kAcross[4][3] = {{1, 3, 2}, {2, 3, 0}, {0, 3, 1}, {1, 2, 0}};
  constexpr int kAcrossEdge[4][3] = {{2, 2, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 1}};
  if (faces_.size() < 4) faces_.resize(64);
  for (int f = 0; f < 4; ++f) {
    if (!make_face(kTetrahedron[f][0], kTetrahedron[f][1], kTetrahedron[f][2], faces_[f])) {
      // Too flat to start: no surface, which a resume finds empty (with the four counted, it
      // went on from faces of earlier runs, or from none at all, and met a support along a zero
      // normal: a certified depth of 0 for a cone's rim 0.05 deep in a cylinder).
      return result;
    }
  }
  face_count_ = 4;
  for (int f = 0; f < 4; ++f) {
    for (int k = 0; k < 3; ++k) {
      faces_[f].adj[k] = kAcross[f][k];
      faces_[f].adj_edge[k] = kAcrossEdge[f][k];
    }
    heap_.emplace_back(faces_[f].distance, f);
  }
  // Four entries in increasing order are a heap (each before its children): sorted in place, as
  // make_heap's two sifts out of line cost three times as much. The entries are distinct (each
  // names its face), so the nearest is the same whatever heap holds them.
  for (std::size_t i = 1; i < heap_.size(); ++i) {
    for (std::size_t j = i; j > 0 && heap_[j] < heap_[j - 1]; --j) {
      std::swap(heap_[j], heap_[j - 1]);
    }
  }
  return expand_surface(a, b, stop_gap, max_iterations, false, verify_end);
}

ExpansionResult ExpandingPolytope::run(const FramedBody& a, const FramedBody& b,
                                       const KeptSurface& kept, Scalar stop_gap,
                                       int max_iterations, bool& started) {
  started = false;
  ExpansionResult result;
  started_from_ = nullptr;
  if (kept.faces.size() < 4) return result;
  kept_depth_ = -1;
  closed_.reset();
  face_count_ = 0;  // until every face is made: a failed start leaves no surface to resume
  vertices_.clear();
  norms_.clear();
  points_a_.clear();
  points_b_.clear();
  for (const std::array<int, 2>& c : kept.corners) {
    if (c[0] < 0 || c[0] >= a.size() || c[1] < 0 || c[1] >= b.size()) return result;
    points_a_.push_back(a.vertex(c[0]));
    points_b_.push_back(b.vertex(c[1]));
    const Vector3 w = -(points_b_.back() - points_a_.back());
    vertices_.push_back({w, c[0], c[1]});
    norms_.push_back(w.norm());
  }
  const int corners = static_cast<int>(vertices_.size());
  const int count = static_cast<int>(kept.faces.size());
  if (faces_.size() < kept.faces.size()) faces_.resize(2 * kept.faces.size());
  heap_.clear();
  for (int f = 0; f < count; ++f) {
    const KeptSurface::Face& k = kept.faces[f];
    if (k.v[0] >= corners || k.v[1] >= corners || k.v[2] >= corners) return result;
    // The expansion walks the adjacency before verify checks it: a kept surface naming a face or
    // an edge that is not there starts nothing. Neighbours that do not name each other back are
    // left to verify (every live face's, at the end): on them the walk stays in range, and
    // whatever it makes is not verified (checked here, they cost 3% of a drift frame).
    for (int e = 0; e < 3; ++e) {
      if (k.adj[e] >= count || k.adj_edge[e] > 2) return result;
      faces_[f].adj[e] = k.adj[e];
      faces_[f].adj_edge[e] = k.adj_edge[e];
    }
    if (!make_face(k.v[0], k.v[1], k.v[2], faces_[f])) return result;
    heap_.emplace_back(faces_[f].distance, f);
  }
  face_count_ = count;
  std::make_heap(heap_.begin(), heap_.end(), kNearestFirst);
  started = true;
  started_from_ = &kept;
  return expand_surface(a, b, stop_gap, max_iterations, true);
}

ExpansionResult ExpandingPolytope::resume(const FramedBody& a, const FramedBody& b,
                                          Scalar stop_gap, int max_iterations) {
  // The vertices' points kept in the frame (points_a_, points_b_) are still the surface's.
  return expand_surface(a, b, stop_gap, max_iterations, true);
}

void ExpandingPolytope::keep(const ExpansionResult& last, int most_corners, KeptSurface& out) {
  // A run from `out` that added no face (faces are only ever added: face_count_ counts the
  // replaced ones too) ends on the very surface `out` holds, faces and corners in its order.
  if (started_from_ == &out && face_count_ == static_cast<int>(out.faces.size()) &&
      vertices_.size() == out.corners.size() && last.verified) {
    return;
  }
  out.clear();
  if (!last.verified || static_cast<int>(vertices_.size()) > most_corners) return;
  // Only live faces, renumbered; every corner is kept (a corner no live face uses is rare).
  std::vector<int>& number = stack_;
  number.assign(static_cast<std::size_t>(face_count_), -1);
  int live = 0;
  for (int f = 0; f < face_count_; ++f) {
    if (faces_[f].alive) number[f] = live++;
  }
  if (live > 255) return;
  out.corners.reserve(vertices_.size());
  out.faces.reserve(static_cast<std::size_t>(live));
  for (const DifferencePoint& v : vertices_) out.corners.push_back({v.ia, v.ib});
  for (int f = 0; f < face_count_; ++f) {
    const Face& face = faces_[f];
    if (!face.alive) continue;
    KeptSurface::Face k;
    for (int e = 0; e < 3; ++e) {
      k.v[e] = static_cast<std::uint8_t>(face.v[e]);
      const int across = face.adj[e] >= 0 && face.adj[e] < face_count_ ? number[face.adj[e]] : -1;
      if (across < 0) {
        out.clear();
        return;
      }
      k.adj[e] = static_cast<std::uint8_t>(across);
      k.adj_edge[e] = static_cast<std::uint8_t>(face.adj_edge[e]);
    }
    out.faces.push_back(k);
  }
}

int ExpandingPolytope::face_crossed(int from, const Vector3& d,
                                    std::array<DifferencePoint, 3>& corners) const {
  int f = from;
  for (int step = 0; step < kMostCrossingSteps; ++step) {
    if (f < 0 || f >= face_count_ || !faces_[f].alive) return -1;
    const Face& face = faces_[f];
    // d = sum_k c_k v_k over the corners: det(v_k, v_k+1, d) is the opposite corner's c times
    // det(v_0, v_1, v_2), positive on a face proven oriented. The ray crosses the face where no
    // c is negative, and passes beyond the edge of the most negative one.
    int beyond = -1;
    Scalar least = 0;
    for (int k = 0; k < 3; ++k) {
      const Scalar c = vertices_[face.v[k]].w.cross(vertices_[face.v[(k + 1) % 3]].w).dot(d);
      if (c < least) {
        least = c;
        beyond = k;
      }
    }
    if (beyond < 0) {
      for (int k = 0; k < 3; ++k) corners[k] = vertices_[face.v[k]];
      return f;
    }
    f = face.adj[beyond];
  }
  return -1;
}

int ExpandingPolytope::corners_around(
    int from, std::array<DifferencePoint, kMostNearbyCorners>& corners) const {
  const auto live = [&](int f) { return f >= 0 && f < face_count_ && faces_[f].alive; };
  if (!live(from)) return 0;
  // The face, the faces across its edges, and the faces across theirs: at most 1 + 3 + 6.
  std::array<int, 10> near{from};
  int faces = 1;
  int ring_start = 0;
  for (int ring = 0; ring < 2; ++ring) {
    const int ring_end = faces;
    for (int i = ring_start; i < ring_end; ++i) {
      for (const int g : faces_[near[i]].adj) {
        if (!live(g) || faces == static_cast<int>(near.size()) ||
            std::find(near.begin(), near.begin() + faces, g) != near.begin() + faces) {
          continue;
        }
        near[faces++] = g;
      }
    }
    ring_start = ring_end;
  }
  std::array<int, kMostNearbyCorners> numbers{};
  int count = 0;
  for (int i = 0; i < faces; ++i) {
    for (const int v : faces_[near[i]].v) {
      if (count == kMostNearbyCorners ||
          std::find(numbers.begin(), numbers.begin() + count, v) != numbers.begin() + count) {
        continue;
      }
      numbers[count] = v;
      corners[count++] = vertices_[v];
    }
  }
  return count;
}

ExpansionResult ExpandingPolytope::expand_surface(const FramedBody& a, const FramedBody& b,
                                                  Scalar stop_gap, int max_iterations,
                                                  bool placed, bool verify_end) {
  ExpansionResult result;
  // Climbs start from a corner on large polytopes only: a curved body's support ignores starts.
  const bool climb_a = !a.curved() && a.size() > kHillClimbingThreshold;
  const bool climb_b = !b.curved() && b.size() > kHillClimbingThreshold;
  // Their corners' heights read the corners' points kept in the frame (points_a_, points_b_):
  // for a placed body height(i, n) is vertex(i).dot(n), the same value from the same point,
  // placed once per vertex instead of twice per corner at every step. Points given in the frame
  // have their own heights, and no scan shortfall: a positive one tells a placed body.
  const bool keep_a = climb_a && a.scan_shortfall() > 0;
  const bool keep_b = climb_b && b.scan_shortfall() > 0;
  if (!placed) {
    points_a_.clear();
    points_b_.clear();
    for (const DifferencePoint& v : vertices_) {
      if (keep_a) points_a_.push_back(a.vertex(v.ia));
      if (keep_b) points_b_.push_back(b.vertex(v.ib));
    }
  }
  const auto height_a = [&](int v, const Vector3& n) {
    return keep_a ? points_a_[v].dot(n) : a.height(vertices_[v].ia, n);
  };
  const auto height_b = [&](int v, const Vector3& n) {
    return keep_b ? points_b_[v].dot(n) : b.height(vertices_[v].ib, n);
  };
  // The largest indices of A's and of B's points among the vertices.
  int most_ia = -1;
  int most_ib = -1;
  for (const DifferencePoint& v : vertices_) {
    most_ia = std::max(most_ia, v.ia);
    most_ib = std::max(most_ib, v.ib);
  }

  // The corner the best normal's support point became (-1 until one did).
  int best_vertex = -1;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    // Stale entries (faces removed since, or flattened since: see flatten) are dropped.
    while (!heap_.empty() && (!faces_[heap_.front().second].alive ||
                              heap_.front().first != faces_[heap_.front().second].distance)) {
      std::pop_heap(heap_.begin(), heap_.end(), kNearestFirst);
      heap_.pop_back();
    }
    // The heap lacks only faces made farther than the least support met then, so farther than
    // it now (it never rises): its nearest face is every live face's while that is no farther.
    // Past it (rounding alone allows that: the faces lie inside A - B) the nearest face is too,
    // so the test below stops on the best face's gap alone; if that is not closed, every live
    // face is heaped again and the expansion takes the nearest as if none had been left out.
    if (heap_.empty() || heap_.front().first > -result.best_separation) {
      if (-result.best_separation - result.best_face_distance <= stop_gap) {
        result.converged = true;
        break;
      }
      heap_live_faces();
      if (heap_.empty()) break;  // no surface (a start too flat to make one)
    }
    const int closest = heap_.front().second;
    const Face& face = faces_[closest];
    // The gap the answer will carry is the least support met against the nearest face's plane:
    // once a direction met earlier closes it, no support call is needed, if that direction's own
    // face closed it too, so that its corners give the witnesses (witnesses_from_face). Where
    // its plane lies lower (an earlier face of a curved pair's polytope, by more than the
    // tolerance in a third of them), the nearest face's support is asked all the same: if it is
    // the least, its face gives the witnesses, and one support point costs less than the search
    // for witnesses elsewhere (Solver::witnesses_within).
    if (-result.best_separation - face.distance <= stop_gap &&
        -result.best_separation - result.best_face_distance <= stop_gap) {
      result.converged = true;
      break;
    }
    const Vector3 n = face.normal;
    // The climbs start from the face's corner highest along n (and lowest, for B): the support
    // is usually a few steps from it. Small bodies are scanned, from no start.
    int start_a = vertices_[face.v[0]].ia;
    int start_b = vertices_[face.v[0]].ib;
    if (climb_a) {
      Scalar top = height_a(face.v[0], n);
      for (int k = 1; k < 3; ++k) {
        const Scalar h = height_a(face.v[k], n);
        if (h > top) {
          top = h;
          start_a = vertices_[face.v[k]].ia;
        }
      }
    }
    if (climb_b) {
      Scalar bottom = height_b(face.v[0], n);
      for (int k = 1; k < 3; ++k) {
        const Scalar h = height_b(face.v[k], n);
        if (h < bottom) {
          bottom = h;
          start_b = vertices_[face.v[k]].ib;
        }
      }
    }
    // The support of A - B along n is minus the point of B - A least along n (minkowski_support's
    // arithmetic, its two points kept).
    const int ia = a.support_index(n, start_a);
    const int ib = b.support_index(-n, start_b);
    const Vector3 x = a.vertex(ia);
    const Vector3 y = b.vertex(ib);
    const Vector3 w = -(y - x);
    const Scalar h = n.dot(w);
    result.iterations = iteration + 1;
    const bool best_here = -h > result.best_separation;
    if (best_here) {
      result.best_separation = -h;
      result.best_normal = n;
      result.best_ia = ia;
      result.best_ib = ib;
      for (int k = 0; k < 3; ++k) result.best_face[k] = vertices_[face.v[k]];
      result.best_face_index = closest;
      result.best_face_distance = face.distance;
    }
    if (-result.best_separation - face.distance <= stop_gap) {
      result.converged = true;
      break;
    }
    // A support point already on the surface, or one not above the nearest face, cannot move
    // it (rounding has the last word), unless the face's normal was the rounding's: then the
    // face is measured again along a better one, and the support asked along that.
    // A curved body's new support point is appended to its points, its index above every
    // vertex's: the scan for a vertex with both indices is only needed when neither is new.
    const bool known = !(h > face.top) || (ia <= most_ia && ib <= most_ib &&
                                           std::any_of(vertices_.begin(), vertices_.end(),
                                                       [&](const auto& v) {
                                                         return v.ia == ia && v.ib == ib;
                                                       }));
    if (known) {
      if (!flatten(closest)) break;
      heap_.emplace_back(faces_[closest].distance, closest);
      std::push_heap(heap_.begin(), heap_.end(), kNearestFirst);
      continue;
    }
    vertices_.push_back({w, ia, ib});
    norms_.push_back(w.norm());
    if (keep_a) points_a_.push_back(x);
    if (keep_b) points_b_.push_back(y);
    if (!expand(closest, static_cast<int>(vertices_.size()) - 1, -result.best_separation)) {
      vertices_.pop_back();
      norms_.pop_back();
      if (keep_a) points_a_.pop_back();
      if (keep_b) points_b_.pop_back();
      break;
    }
    if (best_here) best_vertex = static_cast<int>(vertices_.size()) - 1;
    most_ia = std::max(most_ia, ia);
    most_ib = std::max(most_ib, ib);
  }
  result.near_best_face = result.best_face_index;
  if (result.best_face_index >= 0 && !faces_[result.best_face_index].alive) {
    // The best normal's face was replaced by the cone from its support point, which stays a
    // corner of the surface: a live face there.
    result.near_best_face = -1;
    for (int f = 0; f < face_count_ && best_vertex >= 0; ++f) {
      const Face& face = faces_[f];
      if (face.alive && (face.v[0] == best_vertex || face.v[1] == best_vertex ||
                         face.v[2] == best_vertex)) {
        result.near_best_face = f;
        break;
      }
    }
  }
  closed_.reset();
  if (verify_end) {
    result.verified = verify(result.depth_lower);
    closed_ = result.verified;
  }
  if (kept_depth_ >= 0) {
    result.depth_lower = result.verified ? std::max(result.depth_lower, kept_depth_) : kept_depth_;
    result.verified = true;
  }
  return result;
}

}  // namespace swarmcollide::detail
