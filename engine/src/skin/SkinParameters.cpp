// Derived skin material parameters; see <preskin/SkinParameters.h>.
#include <preskin/SkinParameters.h>

#include <algorithm>
#include <cmath>

namespace preskin {

glm::vec3 normalLodBias(const glm::vec3& widthMm, float scatterScale, float texelsPerMm) {
    const float scale = std::max(scatterScale, 1e-6f);
    return glm::log2(glm::vec3(1.0f) + widthMm / scale * std::max(texelsPerMm, 0.0f));
}

int normalLevelCount(const glm::vec3& lodBias, uint32_t mipLevels, bool withUnbiased) {
    const int levels = static_cast<int>(std::clamp(mipLevels, 1u, 32u));
    float high = std::max(lodBias.x, std::max(lodBias.y, lodBias.z));
    float low = std::min(lodBias.x, std::min(lodBias.y, lodBias.z));
    if (withUnbiased) {
        high = std::max(high, 0.0f);
        low = std::min(low, 0.0f);
    }
    const float span = high - low;
    if (!std::isfinite(span) || span >= float(levels)) return levels;
    return std::min(static_cast<int>(std::ceil(span)) + 2, levels);
}

void accumulateTexelDensity(const Primitive& primitive, const glm::mat4& worldFromObject, double& uvArea,
                            double& surfaceAreaMm2) {
    const glm::mat3 m(worldFromObject);
    for (size_t t = 0; t + 2 < primitive.indices.size(); t += 3) {
        const Vertex& a = primitive.vertices[primitive.indices[t]];
        const Vertex& b = primitive.vertices[primitive.indices[t + 1]];
        const Vertex& c = primitive.vertices[primitive.indices[t + 2]];
        const glm::vec3 e1 = m * (b.positionOs - a.positionOs) * 1000.0f;
        const glm::vec3 e2 = m * (c.positionOs - a.positionOs) * 1000.0f;
        surfaceAreaMm2 += 0.5 * double(glm::length(glm::cross(e1, e2)));
        const glm::vec2 u1 = b.uv0 - a.uv0;
        const glm::vec2 u2 = c.uv0 - a.uv0;
        uvArea += 0.5 * std::abs(double(u1.x * u2.y - u1.y * u2.x));
    }
}

float texelsPerMm(double uvArea, double surfaceAreaMm2, uint32_t width, uint32_t height) {
    if (!(surfaceAreaMm2 > 0.0)) return 0.0f;
    return static_cast<float>(std::sqrt(uvArea * double(width) * double(height) / surfaceAreaMm2));
}

}  // namespace preskin
