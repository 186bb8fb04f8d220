#include "swarmcollide/scene/scene_options.hpp"

#include <stdexcept>
#include <string>

#include "swarmcollide/queries/batch.hpp"

#include "../detail/number_text.hpp"

namespace swarmcollide {

namespace {

struct BroadphaseName {
  Broadphase broadphase;
  std::string name;
};

const std::vector<BroadphaseName>& table() {
  static const std::vector<BroadphaseName> names = {
      {Broadphase::dynamic_aabb_tree, "dynamic_aabb_tree"},
      {Broadphase::sap, "sap"},
      {Broadphase::ssap, "ssap"},
      {Broadphase::interval_tree, "interval_tree"},
      {Broadphase::spatial_hashing, "spatial_hashing"},
      {Broadphase::brute_force, "brute_force"},
  };
  return names;
}

}  // namespace

const std::vector<std::string>& broadphase_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> list;
    for (const BroadphaseName& entry : table()) list.push_back(entry.name);
    return list;
  }();
  return names;
}

const std::string& broadphase_name(Broadphase broadphase) {
  return table().at(static_cast<std::size_t>(broadphase)).name;
}

Broadphase broadphase_from_name(const std::string& name) {
  if (name == "dynamic_aabb_tree_array") {
    // FCL 0.7 (and FCL's master) cannot keep this manager sound through its public interface: a
    // top-down rebalance renumbers the leaves behind the manager's table of objects, so later
    // updates move other bodies' boxes and pairs are lost; and inserting reads the node array
    // after reallocating it.
    throw std::invalid_argument(
        "broadphase 'dynamic_aabb_tree_array' is no longer offered: FCL's array tree loses pairs "
        "once it rebalances itself and reads freed memory as it grows; use 'dynamic_aabb_tree', "
        "the same tree with its nodes on the heap");
  }
  std::string list;
  for (const BroadphaseName& entry : table()) {
    if (entry.name == name) return entry.broadphase;
    list += (list.empty() ? "'" : ", '") + entry.name + "'";
  }
  throw std::invalid_argument("unknown broadphase '" + name + "'; choose one of " + list);
}

void SceneOptions::validate() const {
  query.validate();
  if (!(query.tolerance <= kMaxSceneTolerance)) {
    throw std::invalid_argument(
        "a scene's tolerance must be at most 0.1 (its broadphase pads every box by the contact "
        "threshold), got " +
        detail::number_text(query.tolerance));
  }
  if (threads < 0 || threads > kMaxThreads) {
    throw std::invalid_argument("threads must be in [0, " + std::to_string(kMaxThreads) +
                                "] (0: one per hardware thread), got " + std::to_string(threads));
  }
  if (static_cast<std::size_t>(broadphase) >= table().size()) {
    throw std::invalid_argument("broadphase is not one of the Broadphase values");
  }
}

}  // namespace swarmcollide
