// Node hierarchy check and world transforms (see NodeHierarchy.h).
#include "anim/NodeHierarchy.h"

#include <cstdint>

namespace preskin::anim {

std::optional<HierarchyProblem> hierarchyProblem(std::span<const Node> nodes) {
    const size_t count = nodes.size();
    // Follow each node's parents up to a root; meeting the current path again is a cycle.
    std::vector<uint8_t> state(count, 0);  // 0 unseen, 1 on the current path, 2 leads to a root
    std::vector<size_t> path;
    for (size_t start = 0; start < count; ++start) {
        size_t n = start;
        while (state[n] == 0) {
            state[n] = 1;
            path.push_back(n);
            const int parent = nodes[n].parent;
            if (parent < 0) break;
            if (static_cast<size_t>(parent) >= count)
                return HierarchyProblem{HierarchyProblem::Kind::ParentOutOfRange, n};
            n = static_cast<size_t>(parent);
        }
        if (state[n] == 1 && nodes[n].parent >= 0) return HierarchyProblem{HierarchyProblem::Kind::Cycle, n};
        for (size_t visited : path) state[visited] = 2;
        path.clear();
    }
    return std::nullopt;
}

std::vector<glm::mat4> worldTransforms(std::span<const Node> nodes, std::span<const glm::mat4> local) {
    const size_t count = nodes.size();
    std::vector<glm::mat4> world(count, glm::mat4(1.0f));
    std::vector<uint8_t> done(count, 0);
    std::vector<size_t> chain;
    for (size_t start = 0; start < count; ++start) {
        // The chain of not yet transformed nodes up from `start`, then down it parents first.
        for (size_t n = start; !done[n];) {
            chain.push_back(n);
            done[n] = 1;
            if (nodes[n].parent < 0) break;
            n = static_cast<size_t>(nodes[n].parent);
        }
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
            const int parent = nodes[*it].parent;
            world[*it] = parent < 0 ? local[*it] : world[static_cast<size_t>(parent)] * local[*it];
        }
        chain.clear();
    }
    return world;
}

}  // namespace preskin::anim
