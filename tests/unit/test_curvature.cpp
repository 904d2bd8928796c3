// Per-vertex signed mean curvature (preskin/Curvature.h) against closed forms: a sphere of radius
// r has mean curvature 1/r seen from outside and -1/r from inside, a cylinder 1/(2r), a plane 0,
// the quadric z = (k1 x^2 + k2 y^2) / 2 with normals towards +z -(k1 + k2) / 2 at its centre. Meshes are built here from their analytic
// parametrisations; normals are either analytic or averaged from the faces (the harder case).
#include <preskin/Curvature.h>
#include <preskin/Error.h>
#include <preskin/Scene.h>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace preskin::test {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

struct TestMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<uint32_t> indices;
};

// UV sphere with a seam: the column at u = 1 duplicates u = 0 (as exporters write UV seams),
// and every pole ring vertex is its own copy.
TestMesh uvSphere(float radius, int segments, int rings) {
    TestMesh m;
    for (int r = 0; r <= rings; ++r) {
        const float theta = kPi * static_cast<float>(r) / static_cast<float>(rings);
        for (int s = 0; s <= segments; ++s) {
            const float phi = 2.0f * kPi * static_cast<float>(s % segments) / static_cast<float>(segments);
            const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            m.positions.push_back(radius * n);
            m.normals.push_back(n);
        }
    }
    const auto row = static_cast<uint32_t>(segments + 1);
    for (uint32_t r = 0; r < static_cast<uint32_t>(rings); ++r) {
        for (uint32_t s = 0; s < static_cast<uint32_t>(segments); ++s) {
            const uint32_t a = r * row + s, b = a + 1, c = a + row, d = c + 1;
            m.indices.insert(m.indices.end(), {a, b, c, b, d, c});  // counter-clockwise seen from outside
        }
    }
    return m;
}

// Open cylinder of radius r along y, height h.
TestMesh cylinder(float radius, float height, int segments, int rings) {
    TestMesh m;
    for (int r = 0; r <= rings; ++r) {
        const float y = height * (static_cast<float>(r) / static_cast<float>(rings) - 0.5f);
        for (int s = 0; s < segments; ++s) {
            const float phi = 2.0f * kPi * static_cast<float>(s) / static_cast<float>(segments);
            const glm::vec3 n(std::cos(phi), 0.0f, std::sin(phi));
            m.positions.push_back(glm::vec3(radius * n.x, y, radius * n.z));
            m.normals.push_back(n);
        }
    }
    const auto row = static_cast<uint32_t>(segments);
    for (uint32_t r = 0; r < static_cast<uint32_t>(rings); ++r) {
        for (uint32_t s = 0; s < row; ++s) {
            const uint32_t a = r * row + s, b = r * row + (s + 1) % row, c = a + row, d = b + row;
            m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
        }
    }
    return m;
}

// Area-weighted average of the face normals: normals the estimator has to cope with in practice.
std::vector<glm::vec3> averagedNormals(const TestMesh& m) {
    std::vector<glm::vec3> sum(m.positions.size(), glm::vec3(0.0f));
    for (size_t t = 0; t < m.indices.size(); t += 3) {
        const uint32_t a = m.indices[t], b = m.indices[t + 1], c = m.indices[t + 2];
        const glm::vec3 n = glm::cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
        sum[a] += n;
        sum[b] += n;
        sum[c] += n;
    }
    // Vertices at the same position (seams, poles) share their sums, as a smooth exporter would.
    std::vector<glm::vec3> out(sum.size());
    for (size_t i = 0; i < sum.size(); ++i) {
        glm::vec3 total(0.0f);
        for (size_t j = 0; j < sum.size(); ++j)
            if (m.positions[j] == m.positions[i]) total += sum[j];
        out[i] = glm::normalize(total);
    }
    return out;
}

// Largest relative error of curvature against `expected` over vertices with |y| <= yLimit.
float maxRelativeError(const TestMesh& m, const std::vector<float>& curvature, float expected, float yLimit) {
    float worst = 0.0f;
    for (size_t i = 0; i < m.positions.size(); ++i) {
        if (std::abs(m.positions[i].y) > yLimit) continue;
        worst = std::max(worst, std::abs(curvature[i] - expected) / expected);
    }
    return worst;
}

}  // namespace

TEST(Curvature, SphereGivesInverseRadiusForTwoRadii) {
    for (float radius : {0.05f, 2.0f}) {
        const TestMesh m = uvSphere(radius, 64, 32);
        const std::vector<float> analytic = preskin::computeVertexCurvature(m.positions, m.normals, m.indices);
        const std::vector<float> averaged = preskin::computeVertexCurvature(m.positions, averagedNormals(m), m.indices);
        ASSERT_EQ(analytic.size(), m.positions.size());
        // Away from the poles (|y| <= 0.9 r); the seam column is included.
        EXPECT_LT(maxRelativeError(m, analytic, 1.0f / radius, 0.9f * radius), 0.02f) << "r = " << radius;
        EXPECT_LT(maxRelativeError(m, averaged, 1.0f / radius, 0.9f * radius), 0.02f) << "r = " << radius;
        // The poles are still close with analytic normals.
        EXPECT_LT(maxRelativeError(m, analytic, 1.0f / radius, radius), 0.05f) << "r = " << radius;
    }
}

TEST(Curvature, SeamDuplicatesGetTheSameValue) {
    const TestMesh m = uvSphere(0.1f, 48, 24);
    const std::vector<float> curvature = preskin::computeVertexCurvature(m.positions, averagedNormals(m), m.indices);
    // Column 0 and column `segments` are the seam copies: identical values, and no jump from their
    // neighbours on either side of the seam.
    const int segments = 48, row = segments + 1;
    for (int r = 1; r < 24; ++r) {
        const size_t left = static_cast<size_t>(r * row), right = left + static_cast<size_t>(segments);
        EXPECT_EQ(m.positions[left], m.positions[right]);
        EXPECT_FLOAT_EQ(curvature[left], curvature[right]);
        EXPECT_NEAR(curvature[left], curvature[left + 1], 0.01f * curvature[left + 1]);
        EXPECT_NEAR(curvature[right], curvature[right - 1], 0.01f * curvature[right - 1]);
    }
}

TEST(Curvature, SeamSplitSphereMatchesWeldedSphere) {
    // The same sphere without duplicated seam vertices must give the same values.
    const TestMesh split = uvSphere(0.3f, 32, 16);
    TestMesh welded;
    const int segments = 32, row = segments + 1;
    std::vector<uint32_t> remap(split.positions.size());
    for (size_t i = 0; i < split.positions.size(); ++i) {
        if (static_cast<int>(i) % row == segments) {
            remap[i] = remap[i - static_cast<size_t>(segments)];
            continue;
        }
        remap[i] = static_cast<uint32_t>(welded.positions.size());
        welded.positions.push_back(split.positions[i]);
        welded.normals.push_back(split.normals[i]);
    }
    for (uint32_t index : split.indices) welded.indices.push_back(remap[index]);
    const auto a = preskin::computeVertexCurvature(split.positions, split.normals, split.indices);
    const auto b = preskin::computeVertexCurvature(welded.positions, welded.normals, welded.indices);
    for (size_t i = 0; i < split.positions.size(); ++i) EXPECT_NEAR(a[i], b[remap[i]], 1e-4f * b[remap[i]]);
}

TEST(Curvature, InsideOfASphereIsConcave) {
    // The same sphere with its normals turned inwards (the inside of a bowl): -1/r.
    const float radius = 0.5f;
    TestMesh m = uvSphere(radius, 64, 32);
    for (glm::vec3& n : m.normals) n = -n;
    const std::vector<float> curvature = preskin::computeVertexCurvature(m.positions, m.normals, m.indices);
    for (size_t i = 0; i < m.positions.size(); ++i) {
        if (std::abs(m.positions[i].y) > 0.9f * radius) continue;
        EXPECT_NEAR(curvature[i], -1.0f / radius, 0.02f / radius);
    }
}

TEST(Curvature, QuadricSignFollowsTheNormal) {
    // z = (k1 x^2 + k2 y^2) / 2 near the origin, normals towards +z: a bowl (both k > 0) bends
    // towards its normals, concave, H < 0; a saddle takes the sign of its stronger bend.
    for (const auto& [k1, k2] : {std::pair{3.0f, 2.0f}, std::pair{2.0f, -5.0f}, std::pair{-1.0f, 4.0f}}) {
        TestMesh m;
        const int n = 40;
        const float half = 0.2f;
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                const float x = half * (2.0f * float(i) / float(n) - 1.0f),
                            y = half * (2.0f * float(j) / float(n) - 1.0f);
                m.positions.push_back(glm::vec3(x, y, 0.5f * (k1 * x * x + k2 * y * y)));
                m.normals.push_back(glm::normalize(glm::vec3(-k1 * x, -k2 * y, 1.0f)));
            }
        for (uint32_t j = 0; j < uint32_t(n); ++j)
            for (uint32_t i = 0; i < uint32_t(n); ++i) {
                const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
                m.indices.insert(m.indices.end(), {a, b, c, b, d, c});
            }
        const auto curvature = preskin::computeVertexCurvature(m.positions, m.normals, m.indices);
        const size_t centre = size_t(n / 2) * size_t(n + 1) + size_t(n / 2);
        const float expected = -0.5f * (k1 + k2);
        EXPECT_NEAR(curvature[centre], expected, 0.03f * std::abs(expected)) << "k1 " << k1 << " k2 " << k2;
    }
}

TEST(Curvature, PlaneGivesZero) {
    TestMesh m;
    const int n = 10;
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) {
            // Irregular spacing so the mesh is not trivially symmetric.
            const float fx = static_cast<float>(x) + 0.3f * std::sin(static_cast<float>(x * 7 + y));
            m.positions.push_back(glm::vec3(fx, static_cast<float>(y) * 0.7f, 0.0f));
            m.normals.push_back(glm::vec3(0, 0, 1));
        }
    for (uint32_t y = 0; y < n; ++y)
        for (uint32_t x = 0; x < n; ++x) {
            const uint32_t a = y * (n + 1) + x, b = a + 1, c = a + n + 1, d = c + 1;
            m.indices.insert(m.indices.end(), {a, b, c, b, d, c});
        }
    for (float k : preskin::computeVertexCurvature(m.positions, m.normals, m.indices)) EXPECT_NEAR(k, 0.0f, 1e-5f);
    for (float k : preskin::computeVertexCurvature(m.positions, averagedNormals(m), m.indices))
        EXPECT_NEAR(k, 0.0f, 1e-5f);
}

TEST(Curvature, CylinderGivesHalfInverseRadius) {
    // Mean curvature convention: H = (k1 + k2) / 2 = (1/r + 0) / 2.
    const float radius = 0.2f;
    const TestMesh m = cylinder(radius, 1.0f, 48, 12);
    const auto analytic = preskin::computeVertexCurvature(m.positions, m.normals, m.indices);
    const auto averaged = preskin::computeVertexCurvature(m.positions, averagedNormals(m), m.indices);
    const float expected = 0.5f / radius;
    EXPECT_LT(maxRelativeError(m, analytic, expected, 1.0f), 0.02f);
    // With face-averaged normals the rims (open boundary) tilt; check the interior rings.
    EXPECT_LT(maxRelativeError(m, averaged, expected, 0.4f), 0.02f);
}

TEST(Curvature, ScalesInverselyWithSize) {
    const TestMesh small = uvSphere(1.0f, 24, 12);
    TestMesh large = small;
    for (glm::vec3& p : large.positions) p *= 10.0f;
    const auto a = preskin::computeVertexCurvature(small.positions, small.normals, small.indices);
    const auto b = preskin::computeVertexCurvature(large.positions, large.normals, large.indices);
    for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(b[i] * 10.0f, a[i], 1e-4f * a[i]);
}

TEST(Curvature, RejectsBadInput) {
    const std::vector<glm::vec3> p = {glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)};
    const std::vector<glm::vec3> n(3, glm::vec3(0, 0, 1));
    const std::vector<uint32_t> bad = {0, 1, 3};
    EXPECT_THROW(preskin::computeVertexCurvature(p, n, bad), preskin::Error);
    const std::vector<uint32_t> partial = {0, 1};
    EXPECT_THROW(preskin::computeVertexCurvature(p, n, partial), preskin::Error);
    const std::vector<glm::vec3> fewNormals(2, glm::vec3(0, 0, 1));
    const std::vector<uint32_t> ok = {0, 1, 2};
    EXPECT_THROW(preskin::computeVertexCurvature(p, fewNormals, ok), preskin::Error);
}

TEST(Curvature, UpdateMeshCurvatureSpansPrimitives) {
    // A sphere split into two primitives along its equator: the border rows must not drop.
    const TestMesh m = uvSphere(0.5f, 32, 16);
    preskin::Mesh mesh;
    mesh.primitives.resize(2);
    for (auto& prim : mesh.primitives) {
        for (size_t i = 0; i < m.positions.size(); ++i) {
            preskin::Vertex v;
            v.positionOs = m.positions[i];
            v.normalOs = m.normals[i];
            prim.vertices.push_back(v);
        }
    }
    const size_t half = m.indices.size() / 2;
    mesh.primitives[0].indices.assign(m.indices.begin(), m.indices.begin() + static_cast<std::ptrdiff_t>(half));
    mesh.primitives[1].indices.assign(m.indices.begin() + static_cast<std::ptrdiff_t>(half), m.indices.end());
    preskin::updateMeshCurvature(mesh);
    for (const auto& prim : mesh.primitives) {
        for (const auto& v : prim.vertices) {
            if (std::abs(v.positionOs.y) < 0.45f) {
                EXPECT_NEAR(v.curvaturePerM, 2.0f, 0.04f);
            }
        }
    }
}

}  // namespace preskin::test
