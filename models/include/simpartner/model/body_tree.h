// The flat model as a tree of bodies joined by joints, the form engines in
// reduced coordinates (MuJoCo) and the MJCF exporter need: every moving
// body hangs from the static world or from one parent by at most one of
// our joints, or floats free. Joints that would close a loop have no place
// in a tree and are listed apart.
#pragma once

#include <vector>

#include "simpartner/model/flat_model.h"

namespace simpartner::model {

struct TreeNode {
  int parent = -1;              // flat body index, -1 = the static world
  int joint = -1;               // flat joint that joins it to its parent; -1 = welded or free
  bool free = false;            // root of a floating tree (six degrees of freedom)
  bool joint_reversed = false;  // the parent is the joint's body1 (ours count body1
                                // relative to body2, a tree the child to its parent)
  std::vector<int> children;
};

struct BodyTree {
  // One node per flat body; static bodies' nodes are unused (parent -1,
  // not free).
  std::vector<TreeNode> nodes;
  // Flat joints between two moving bodies (or a moving body and the world)
  // already joined another way: they close a loop.
  std::vector<int> loop_joints;
  // Flat bodies in an order where every parent comes before its children.
  std::vector<int> order;
};

// Breadth first from the static world over the joints, then from each
// body nothing reached (the root of a floating tree).
BodyTree BuildBodyTree(const FlatModel& model);

}  // namespace simpartner::model
