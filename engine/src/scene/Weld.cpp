// Vertex welding by position and normal hemisphere (see Weld.h).
#include "scene/Weld.h"

#include <array>
#include <bit>
#include <cmath>
#include <unordered_map>

namespace preskin {

namespace {

struct PositionKey {
    std::array<uint32_t, 3> bits;
    bool operator==(const PositionKey&) const = default;
};

struct PositionKeyHash {
    size_t operator()(const PositionKey& k) const {
        uint64_t h = 1469598103934665603ull;
        for (uint32_t b : k.bits) {
            h ^= b;
            h *= 1099511628211ull;
        }
        return static_cast<size_t>(h);
    }
};

PositionKey keyOf(const glm::vec3& p) {
    PositionKey k{};
    for (int i = 0; i < 3; ++i) {
        const float c = p[i] == 0.0f ? 0.0f : p[i];  // -0 and +0 weld
        k.bits[static_cast<size_t>(i)] = std::bit_cast<uint32_t>(c);
    }
    return k;
}

}  // namespace

WeldedVertices weldVertices(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals) {
    using dvec3 = glm::dvec3;
    WeldedVertices out;
    out.weldedOf.resize(positions.size());
    std::vector<dvec3> normalSum;
    std::unordered_map<PositionKey, std::vector<uint32_t>, PositionKeyHash> groups;
    groups.reserve(positions.size());
    for (size_t i = 0; i < positions.size(); ++i) {
        dvec3 n(i < normals.size() ? normals[i] : glm::vec3(0.0f));
        const double len = glm::length(n);
        n = (std::isfinite(len) && len > 1e-12) ? n / len : dvec3(0.0);
        auto& ids = groups[keyOf(positions[i])];
        uint32_t id = UINT32_MAX;
        for (uint32_t candidate : ids) {
            const dvec3& sum = normalSum[candidate];
            if (glm::dot(sum, n) > 0.0 || n == dvec3(0.0) || sum == dvec3(0.0)) {
                id = candidate;
                break;
            }
        }
        if (id == UINT32_MAX) {
            id = static_cast<uint32_t>(normalSum.size());
            ids.push_back(id);
            normalSum.emplace_back(0.0);
        }
        normalSum[id] += n;
        out.weldedOf[i] = id;
    }
    out.weldedCount = static_cast<uint32_t>(normalSum.size());
    return out;
}

}  // namespace preskin
