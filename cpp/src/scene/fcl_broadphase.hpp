// FCL's broadphase managers as collectors of candidate pairs; private to the library's sources.
#pragma once

#include <fcl/broadphase/broadphase_collision_manager.h>
#include <fcl/narrowphase/collision_object.h>

#include <memory>
#include <utility>
#include <vector>

#include "swarmcollide/geometry/aabb.hpp"
#include "swarmcollide/scene/broadphase.hpp"
#include "swarmcollide/scene/scene_options.hpp"
#include "swarmcollide/scene/scene_result.hpp"

namespace swarmcollide::detail {

/// An FCL collision object whose world box is set directly. FCL 0.7 boxes a rotated object by
/// the box of its bounding sphere; the managers read only `getAABB()`, so writing the box FCL
/// keeps (a protected member, there for derived objects) gives them our tight boxes at no cost:
/// no geometry to resize, no transform to set.
class BoxedObject : public fcl::CollisionObjectd {
 public:
  /// `owner` is the body the object stands for.
  BoxedObject(void* owner, BodyId owner_id, const BodyFilter& owner_filter);
  void set_box(const Aabb& box);
  void* owner() const { return getUserData(); }

  /// Copies of the owner's id and filter, in the cache line the traversal has just read (the
  /// box's), so that sorting out the candidates it returns touches no other memory.
  BodyId id;
  BodyFilter filter;
};

/// Two objects whose boxes overlap.
using ObjectPair = std::pair<BoxedObject*, BoxedObject*>;

/// One FCL manager, used only to collect the pairs of objects whose boxes overlap: no FCL
/// narrowphase, no callback beyond appending the pair.
class FclBroadphase {
 public:
  explicit FclBroadphase(Broadphase kind);
  ~FclBroadphase();
  FclBroadphase(const FclBroadphase&) = delete;
  FclBroadphase& operator=(const FclBroadphase&) = delete;

  void insert(const std::vector<BoxedObject*>& objects);
  void erase(const std::vector<BoxedObject*>& objects);
  /// Tells the manager that the boxes of `moved` changed (of every object when `all`).
  void refit(const std::vector<BoxedObject*>& moved, bool all);
  /// Every pair of registered objects whose boxes overlap, appended to `out` (each once).
  void overlapping_pairs(std::vector<ObjectPair>& out);
  /// Every registered object whose box overlaps that of `query` (which need not be
  /// registered), appended to `out` as (query, object).
  void overlapping(BoxedObject* query, std::vector<ObjectPair>& out);

 private:
  // Whether the manager is rebuilt from `objects_` rather than told of changes (see refit).
  bool rebuilds() const;
  void rebuild();

  Broadphase kind_;
  std::unique_ptr<fcl::BroadPhaseCollisionManagerd> manager_;
  // The registered objects, for managers that are rebuilt.
  std::vector<BoxedObject*> objects_;
  bool stale_ = false;
};

}  // namespace swarmcollide::detail
