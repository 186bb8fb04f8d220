#include "swarmcollide/robot/pair_filter.hpp"

#include <numeric>
#include <stdexcept>
#include <string>

namespace swarmcollide {

namespace {

// The links' rigid groups and each group's parent group with geometry.
class LinkGroups {
 public:
  explicit LinkGroups(const RobotModel& model) : group_(model.links().size()) {
    std::iota(group_.begin(), group_.end(), 0);
    // Joints from the root outwards: a parent's group is final before its children take it.
    for (int j : model.joint_order()) {
      const Joint& joint = model.joints()[j];
      if (joint.type == JointType::fixed) group_[joint.child] = group_[joint.parent];
    }
    std::vector<char> has_geometry(group_.size(), 0);
    for (const Geometry& geometry : model.geometries()) {
      if (geometry.link >= 0) has_geometry[group_[geometry.link]] = 1;
    }
    std::vector<int> parent(group_.size(), -1);
    for (const Joint& joint : model.joints()) {
      if (joint.type != JointType::fixed) parent[group_[joint.child]] = group_[joint.parent];
    }
    geometric_parent_.assign(group_.size(), -1);
    for (std::size_t g = 0; g < group_.size(); ++g) {
      int up = parent[g];
      while (up >= 0 && !has_geometry[up]) up = parent[up];
      geometric_parent_[g] = up;
    }
  }

  bool adjacent(int a, int b) const {
    const int ga = group_[a];
    const int gb = group_[b];
    return ga == gb || geometric_parent_[ga] == gb || geometric_parent_[gb] == ga;
  }

 private:
  std::vector<int> group_;
  std::vector<int> geometric_parent_;
};

}  // namespace

bool adjacent_links(const RobotModel& model, int a, int b) {
  const int links = static_cast<int>(model.links().size());
  if (a < 0 || a >= links || b < 0 || b >= links) {
    throw std::invalid_argument("link indices must be in [0, " + std::to_string(links) +
                                "), got " + std::to_string(a) + " and " + std::to_string(b));
  }
  return LinkGroups(model).adjacent(a, b);
}

std::vector<GeometryPair> default_pairs(const RobotModel& model) {
  const std::vector<Geometry>& geometries = model.geometries();
  const int count = static_cast<int>(geometries.size());
  const LinkGroups groups(model);
  std::vector<GeometryPair> pairs;
  for (int a = 0; a < count; ++a) {
    for (int b = a + 1; b < count; ++b) {
      const int link_a = geometries[a].link;
      const int link_b = geometries[b].link;
      if (link_a < 0 && link_b < 0) continue;
      if (link_a >= 0 && link_b >= 0 && groups.adjacent(link_a, link_b)) continue;
      pairs.push_back({a, b});
    }
  }
  return pairs;
}

void validate_pairs(const RobotModel& model, const std::vector<GeometryPair>& pairs) {
  const int count = static_cast<int>(model.geometries().size());
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const GeometryPair& pair = pairs[p];
    if (pair.a < 0 || pair.a >= count || pair.b < 0 || pair.b >= count || pair.a == pair.b) {
      throw std::invalid_argument("pairs[" + std::to_string(p) + "] = (" + std::to_string(pair.a) +
                                  ", " + std::to_string(pair.b) +
                                  ") must name two different geometries in [0, " +
                                  std::to_string(count) + ")");
    }
  }
}

}  // namespace swarmcollide
