// Reflection test: the member offsets glslang assigned to every shared GPU struct in the
// compiled shaders (OpMemberDecorate Offset in the SPIR-V) equal the C++ offsets of the same
// struct in shaders/shared/*.h, so the two sides can never disagree on a layout.
#include "shared/cluster_build.h"
#include "shared/deform.h"
#include "shared/gpu_types.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <string_view>

namespace preskin::shaders {
std::span<const uint32_t> spirv(std::string_view fileName);
}

namespace preskin::test {

namespace {

// struct name -> member name -> byte offset, from OpName / OpMemberName / OpMemberDecorate Offset.
using Layouts = std::map<std::string, std::map<std::string, uint32_t>>;

std::string literalString(std::span<const uint32_t> words) {
    std::string s;
    for (uint32_t w : words)
        for (int b = 0; b < 4; ++b) {
            const char c = static_cast<char>((w >> (8 * b)) & 0xffu);
            if (c == '\0') return s;
            s += c;
        }
    return s;
}

Layouts reflect(std::span<const uint32_t> code) {
    constexpr uint32_t kOpName = 5, kOpMemberName = 6, kOpMemberDecorate = 72, kDecorationOffset = 35;
    std::map<uint32_t, std::string> typeNames;
    std::map<uint32_t, std::map<uint32_t, std::string>> memberNames;
    std::map<uint32_t, std::map<uint32_t, uint32_t>> memberOffsets;
    EXPECT_GT(code.size(), 5u);
    EXPECT_EQ(code[0], 0x07230203u) << "SPIR-V magic";
    for (size_t i = 5; i < code.size();) {
        const uint32_t count = code[i] >> 16;
        const uint32_t op = code[i] & 0xffffu;
        if (count == 0 || i + count > code.size()) {
            ADD_FAILURE() << "malformed SPIR-V at word " << i;
            break;
        }
        const auto operands = code.subspan(i + 1, count - 1);
        if (op == kOpName) typeNames[operands[0]] = literalString(operands.subspan(1));
        if (op == kOpMemberName) memberNames[operands[0]][operands[1]] = literalString(operands.subspan(2));
        if (op == kOpMemberDecorate && operands[2] == kDecorationOffset)
            memberOffsets[operands[0]][operands[1]] = operands[3];
        i += count;
    }
    Layouts layouts;
    for (const auto& [id, offsets] : memberOffsets) {
        auto name = typeNames.find(id);
        if (name == typeNames.end()) continue;
        for (const auto& [member, offset] : offsets) layouts[name->second][memberNames[id][member]] = offset;
    }
    return layouts;
}

#define PRESKIN_EXPECT_MEMBER(layouts, type, member)                                                         \
    do {                                                                                                     \
        ASSERT_TRUE(layouts.count(#type)) << #type " is not in the shader";                                  \
        ASSERT_TRUE(layouts.at(#type).count(#member)) << #type "." #member " is not in the shader";          \
        EXPECT_EQ(layouts.at(#type).at(#member), offsetof(preskin::gpu::type, member)) << #type "." #member; \
    } while (false)

TEST(GpuLayout, ForwardShaderStructsMatchCpp) {
    const Layouts l = reflect(preskin::shaders::spirv("forward.frag"));
    PRESKIN_EXPECT_MEMBER(l, FrameUniforms, eyes);
    PRESKIN_EXPECT_MEMBER(l, FrameUniforms, clusterFromWorld);
    PRESKIN_EXPECT_MEMBER(l, FrameUniforms, shadowClipFromWorld);
    PRESKIN_EXPECT_MEMBER(l, FrameUniforms, params);
    PRESKIN_EXPECT_MEMBER(l, FrameUniforms, viewport);
    PRESKIN_EXPECT_MEMBER(l, FrameUniforms, shadowParams);
    PRESKIN_EXPECT_MEMBER(l, FrameUniforms, shadowDirectionWs);
    PRESKIN_EXPECT_MEMBER(l, FrameUniforms, shRadiance);
    PRESKIN_EXPECT_MEMBER(l, FrameUniforms, lightCounts);
    PRESKIN_EXPECT_MEMBER(l, FrameUniforms, clusterScale);
    PRESKIN_EXPECT_MEMBER(l, FrameUniforms, clusterDims);
    PRESKIN_EXPECT_MEMBER(l, FrameUniforms, wideShadow);
    PRESKIN_EXPECT_MEMBER(l, FrameUniforms, environment);
    PRESKIN_EXPECT_MEMBER(l, EyeUniforms, clipFromWorld);
    PRESKIN_EXPECT_MEMBER(l, EyeUniforms, positionWs);
    PRESKIN_EXPECT_MEMBER(l, EyeUniforms, viewDepthFromWorld);
    PRESKIN_EXPECT_MEMBER(l, LutMapping, diffuseNoL);
    PRESKIN_EXPECT_MEMBER(l, LutMapping, diffuseCurvature);
    PRESKIN_EXPECT_MEMBER(l, LutMapping, penumbraShadow);
    PRESKIN_EXPECT_MEMBER(l, LutMapping, penumbraWidth);
    PRESKIN_EXPECT_MEMBER(l, LutMapping, shCurvature);
    PRESKIN_EXPECT_MEMBER(l, LutMapping, shBandV);
    PRESKIN_EXPECT_MEMBER(l, LutMapping, shLambert);
    PRESKIN_EXPECT_MEMBER(l, LutMapping, transmittance);
    PRESKIN_EXPECT_MEMBER(l, GpuLight, positionRange);
    PRESKIN_EXPECT_MEMBER(l, GpuLight, directionType);
    PRESKIN_EXPECT_MEMBER(l, GpuLight, colorIntensity);
    PRESKIN_EXPECT_MEMBER(l, GpuLight, spotScaleOffset);
    PRESKIN_EXPECT_MEMBER(l, MaterialUniforms, baseColorFactor);
    PRESKIN_EXPECT_MEMBER(l, MaterialUniforms, emissiveAlphaCutoff);
    PRESKIN_EXPECT_MEMBER(l, MaterialUniforms, pbr);
    PRESKIN_EXPECT_MEMBER(l, MaterialUniforms, skinScatter);
    PRESKIN_EXPECT_MEMBER(l, MaterialUniforms, skinNormalLodBias);
    PRESKIN_EXPECT_MEMBER(l, MaterialUniforms, skinTransmission);
    PRESKIN_EXPECT_MEMBER(l, MaterialUniforms, skinSpecular);
    PRESKIN_EXPECT_MEMBER(l, MaterialUniforms, textureFlags);
    PRESKIN_EXPECT_MEMBER(l, MaterialUniforms, hasTextures);
    PRESKIN_EXPECT_MEMBER(l, MaterialUniforms, skinProfileLayers);
    PRESKIN_EXPECT_MEMBER(l, MaterialUniforms, skinProfileBlend);
    PRESKIN_EXPECT_MEMBER(l, MaterialUniforms, uv);
}

TEST(GpuLayout, VertexShaderStructsMatchCpp) {
    const Layouts l = reflect(preskin::shaders::spirv("forward.vert"));
    PRESKIN_EXPECT_MEMBER(l, GpuInstance, worldFromObject);
    PRESKIN_EXPECT_MEMBER(l, GpuInstance, normalWorldFromObject);
    PRESKIN_EXPECT_MEMBER(l, GpuInstance, params);
    PRESKIN_EXPECT_MEMBER(l, DrawPush, indices);
    PRESKIN_EXPECT_MEMBER(l, EyeUniforms, clipFromWorld);
    PRESKIN_EXPECT_MEMBER(l, MaterialUniforms, skinNormalBasis);  // read by the vertex stage alone
}

// The light grid's compute build (cluster_build.comp, both passes in one module).
TEST(GpuLayout, ClusterBuildStructsMatchCpp) {
    const Layouts l = reflect(preskin::shaders::spirv("cluster_build.comp"));
    PRESKIN_EXPECT_MEMBER(l, ClusterBuildParams, viewFromWorld);
    PRESKIN_EXPECT_MEMBER(l, ClusterBuildParams, dims);
    PRESKIN_EXPECT_MEMBER(l, ClusterBuildParams, lightInfo);
    PRESKIN_EXPECT_MEMBER(l, ClusterBuildParams, geometryOffsets);
    PRESKIN_EXPECT_MEMBER(l, ClusterBuildParams, slack);
    PRESKIN_EXPECT_MEMBER(l, ClusterBuildParams, slicing);
    PRESKIN_EXPECT_MEMBER(l, ClusterLightVolume, centerRadius);
    PRESKIN_EXPECT_MEMBER(l, ClusterLightVolume, apexRange);
    PRESKIN_EXPECT_MEMBER(l, ClusterLightVolume, axisCos);
    PRESKIN_EXPECT_MEMBER(l, ClusterLightVolume, box);
    PRESKIN_EXPECT_MEMBER(l, ClusterCounters, values);
    PRESKIN_EXPECT_MEMBER(l, GpuLight, positionRange);
    PRESKIN_EXPECT_MEMBER(l, GpuLight, spotScaleOffset);
}

// The deformation and curvature compute passes.
TEST(GpuLayout, DeformationStructsMatchCpp) {
    const Layouts deform = reflect(preskin::shaders::spirv("deform.comp"));
    PRESKIN_EXPECT_MEMBER(deform, DeformInfluences, joints0);
    PRESKIN_EXPECT_MEMBER(deform, DeformInfluences, joints1);
    PRESKIN_EXPECT_MEMBER(deform, DeformInfluences, weights0);
    PRESKIN_EXPECT_MEMBER(deform, DeformInfluences, weights1);
    PRESKIN_EXPECT_MEMBER(deform, DeformPush, vertices);
    PRESKIN_EXPECT_MEMBER(deform, DeformPush, offsets);
    const Layouts curvature = reflect(preskin::shaders::spirv("curvature.comp"));
    PRESKIN_EXPECT_MEMBER(curvature, CurvaturePush, counts);
    PRESKIN_EXPECT_MEMBER(curvature, CurvaturePush, topology);
    PRESKIN_EXPECT_MEMBER(curvature, CurvaturePush, scratch);
}

}  // namespace

}  // namespace preskin::test
