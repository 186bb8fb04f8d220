#include "fcl_broadphase.hpp"

#include <fcl/broadphase/broadphase_SSaP.h>
#include <fcl/broadphase/broadphase_SaP.h>
#include <fcl/broadphase/broadphase_bruteforce.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/broadphase_interval_tree.h>
#include <fcl/broadphase/broadphase_spatialhash.h>
#include <fcl/geometry/shape/box.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_set>

namespace swarmcollide::detail {

namespace {

// Every object shares one geometry, which FCL never looks at: it needs one to build an object.
std::shared_ptr<fcl::CollisionGeometryd> placeholder_geometry() {
  static const auto geometry = std::make_shared<fcl::Boxd>(1, 1, 1);
  return geometry;
}

using Grid = fcl::SpatialHashingCollisionManagerd<>;

std::unique_ptr<fcl::BroadPhaseCollisionManagerd> make_manager(Broadphase kind) {
  switch (kind) {
    case Broadphase::dynamic_aabb_tree:
      return std::make_unique<fcl::DynamicAABBTreeCollisionManagerd>();
    case Broadphase::sap:
      return std::make_unique<fcl::SaPCollisionManagerd>();
    case Broadphase::ssap:
      return std::make_unique<fcl::SSaPCollisionManagerd>();
    case Broadphase::interval_tree:
      return std::make_unique<fcl::IntervalTreeCollisionManagerd>();
    case Broadphase::spatial_hashing:
      // An empty grid; `rebuild` sizes one to its bodies.
      return std::make_unique<Grid>(1, fcl::Vector3d::Zero(), fcl::Vector3d::Ones());
    case Broadphase::brute_force:
      break;
  }
  return std::make_unique<fcl::NaiveCollisionManagerd>();
}

// Every object registered (and every query) is a BoxedObject.
bool collect(fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* data) {
  static_cast<std::vector<ObjectPair>*>(data)->emplace_back(static_cast<BoxedObject*>(a),
                                                            static_cast<BoxedObject*>(b));
  return false;  // never stop: every pair is wanted
}

}  // namespace

BoxedObject::BoxedObject(void* owner, BodyId owner_id, const BodyFilter& owner_filter)
    : fcl::CollisionObjectd(placeholder_geometry()), id(owner_id), filter(owner_filter) {
  setUserData(owner);
}

void BoxedObject::set_box(const Aabb& box) {
  aabb.min_ = box.min;
  aabb.max_ = box.max;
}

FclBroadphase::FclBroadphase(Broadphase kind) : kind_(kind), manager_(make_manager(kind)) {}

FclBroadphase::~FclBroadphase() = default;

// Three FCL 0.7 managers are rebuilt rather than updated. SaPCollisionManager::update moves an
// interval's two ends as if its length were unchanged: a box that grows (a body turning, a
// query padding it more) links an end point to itself and the next update never returns.
// IntervalTreeCollisionManager::update(object) looks for the moved box's upper ends among the
// lower ones, leaving stale ends behind, and its getObjects and clear cannot be trusted after
// that. The spatial hash sizes its cells to the bodies it was built with.
bool FclBroadphase::rebuilds() const {
  return kind_ == Broadphase::sap || kind_ == Broadphase::interval_tree ||
         kind_ == Broadphase::spatial_hashing;
}

void FclBroadphase::insert(const std::vector<BoxedObject*>& objects) {
  objects_.insert(objects_.end(), objects.begin(), objects.end());
  if (rebuilds()) {
    stale_ = true;
    return;
  }
  manager_->registerObjects(std::vector<fcl::CollisionObjectd*>(objects.begin(), objects.end()));
  manager_->setup();
}

void FclBroadphase::erase(const std::vector<BoxedObject*>& objects) {
  const std::unordered_set<BoxedObject*> gone(objects.begin(), objects.end());
  objects_.erase(std::remove_if(objects_.begin(), objects_.end(),
                                [&](BoxedObject* o) { return gone.count(o) > 0; }),
                 objects_.end());
  if (rebuilds()) {
    stale_ = true;
    return;
  }
  for (BoxedObject* object : objects) manager_->unregisterObject(object);
}

void FclBroadphase::refit(const std::vector<BoxedObject*>& moved, bool all) {
  if (rebuilds()) {
    // The spatial hash handles moves; the sweeps are sorted afresh.
    if (kind_ != Broadphase::spatial_hashing) stale_ = true;
    if (!stale_) manager_->update();
    return;
  }
  if (all) {
    manager_->update();
  } else if (!moved.empty()) {
    const std::vector<fcl::CollisionObjectd*> base(moved.begin(), moved.end());
    manager_->update(base);
  }
}

// A fresh manager holding `objects_`. A grid's cells are about twice the median box, so most
// bodies fall in a few cells and a cell holds few bodies; its limits enclose every box, and
// bodies that later leave them are still found (FCL checks those against every other body).
void FclBroadphase::rebuild() {
  stale_ = false;
  const std::vector<fcl::CollisionObjectd*> objects(objects_.begin(), objects_.end());
  if (kind_ != Broadphase::spatial_hashing || objects.empty()) {
    manager_ = make_manager(kind_);
  } else {
    std::vector<double> extents;
    extents.reserve(objects.size());
    fcl::AABBd limits = objects.front()->getAABB();
    for (const fcl::CollisionObjectd* object : objects) {
      const fcl::AABBd& box = object->getAABB();
      extents.push_back((box.max_ - box.min_).maxCoeff());
      limits += box;
    }
    std::nth_element(extents.begin(), extents.begin() + extents.size() / 2, extents.end());
    const double median = extents[extents.size() / 2];
    const double span = (limits.max_ - limits.min_).maxCoeff();
    // At most about 256 cells along the longest axis, and never a cell of size zero.
    const double cell = std::max({2 * median, span / 256, 1e-300});
    const auto table =
        static_cast<unsigned>(std::clamp<std::size_t>(objects.size(), 1000, 1u << 20));
    manager_ = std::make_unique<Grid>(cell, limits.min_, limits.max_, table);
  }
  if (!objects.empty()) manager_->registerObjects(objects);
  manager_->setup();
}

void FclBroadphase::overlapping_pairs(std::vector<ObjectPair>& out) {
  if (stale_) rebuild();
  manager_->collide(&out, collect);
}

void FclBroadphase::overlapping(BoxedObject* query, std::vector<ObjectPair>& out) {
  if (stale_) rebuild();
  const std::size_t before = out.size();
  manager_->collide(query, &out, collect);
  // FCL passes the query as either argument; put it first.
  for (std::size_t k = before; k < out.size(); ++k) {
    if (out[k].second == query) std::swap(out[k].first, out[k].second);
  }
}

}  // namespace swarmcollide::detail
