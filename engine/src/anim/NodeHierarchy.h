// The one walk of a node hierarchy (Scene::nodes, glTF 2.0 "Nodes and Hierarchy"): its check and
// its world transforms, used by the glTF loader for the rest pose and by posing for every frame.
#pragma once

#include <preskin/Animation.h>

#include <glm/glm.hpp>

#include <optional>
#include <span>
#include <vector>

namespace preskin::anim {

// What makes a node list not a forest: a node's parent index outside the list, or a node on a
// cycle of parents (the first such node met, following parents from node 0, 1, ... in order).
struct HierarchyProblem {
    enum class Kind { ParentOutOfRange, Cycle };
    Kind kind;
    size_t node;
};
std::optional<HierarchyProblem> hierarchyProblem(std::span<const Node> nodes);

// worldFromNode of every node, each parent's before its children's: world = world[parent] *
// local[node] (local: one per node). The nodes must form a forest (no hierarchyProblem).
std::vector<glm::mat4> worldTransforms(std::span<const Node> nodes, std::span<const glm::mat4> local);

}  // namespace preskin::anim
