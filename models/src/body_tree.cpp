#include "simpartner/model/body_tree.h"

namespace simpartner::model {
namespace {

bool Static(const FlatModel& model, int body) {
  return body < 0 || model.bodies[static_cast<size_t>(body)].source->is_static;
}

class TreeBuilder {
 public:
  explicit TreeBuilder(const FlatModel& model)
      : model_(model),
        placed_(model.bodies.size(), false),
        joint_used_(model.joints.size(), false) {
    tree_.nodes.assign(model.bodies.size(), TreeNode{});
  }

  BodyTree Run() {
    Grow({-1});
    for (size_t b = 0; b < model_.bodies.size(); ++b) {
      if (Static(model_, static_cast<int>(b)) || placed_[b]) continue;
      Place(static_cast<int>(b));
      tree_.nodes[b].free = true;
      Grow({static_cast<int>(b)});
    }
    for (size_t j = 0; j < model_.joints.size(); ++j) {
      const FlatJoint& joint = model_.joints[j];
      if (!joint_used_[j] && !(Static(model_, joint.body1) && Static(model_, joint.body2)))
        tree_.loop_joints.push_back(static_cast<int>(j));
    }
    return std::move(tree_);
  }

 private:
  void Place(int body) {
    placed_[static_cast<size_t>(body)] = true;
    tree_.order.push_back(body);
  }

  // Hangs every unplaced body joined to the frontier from it, level by level.
  void Grow(std::vector<int> frontier) {
    while (!frontier.empty()) {
      std::vector<int> next;
      for (int at : frontier) {
        for (size_t j = 0; j < model_.joints.size(); ++j) {
          if (joint_used_[j]) continue;
          const FlatJoint& joint = model_.joints[j];
          const int a = Static(model_, joint.body1) ? -1 : joint.body1;
          const int b = Static(model_, joint.body2) ? -1 : joint.body2;
          int child = -1;
          bool reversed = false;
          if (a == at && b != at) {
            child = b;
            reversed = true;
          } else if (b == at && a != at) {
            child = a;
          }
          if (child < 0 || placed_[static_cast<size_t>(child)]) continue;
          joint_used_[j] = true;
          Place(child);
          TreeNode& node = tree_.nodes[static_cast<size_t>(child)];
          node.parent = at;
          node.joint = static_cast<int>(j);
          node.joint_reversed = reversed;
          if (at >= 0) tree_.nodes[static_cast<size_t>(at)].children.push_back(child);
          next.push_back(child);
        }
      }
      frontier = std::move(next);
    }
  }

  const FlatModel& model_;
  BodyTree tree_;
  std::vector<bool> placed_;
  std::vector<bool> joint_used_;
};

}  // namespace

BodyTree BuildBodyTree(const FlatModel& model) { return TreeBuilder(model).Run(); }

}  // namespace simpartner::model
