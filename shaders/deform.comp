#version 460
// deform.comp: one deformed primitive of a mesh instance per dispatch, one invocation per vertex:
// morph targets add their weighted deltas to position, normal and tangent, then linear blend
// skinning applies sum_k w_k J[joint_k] (glTF 2.0, "Skins" and "Morph Targets"): positions by the
// blended matrix, normals by the inverse transpose of its 3x3 (as its cofactor matrix, which
// differs by the positive factor |det| and needs no division), tangents by its 3x3, both
// renormalised. The skin's normal basis (averaged normals, <preskin/NormalBasis.h>) moves like
// the normal: each vector takes the normal's morph delta in proportion to its length along the
// rest normal and the normal's transform and scale, so rigid motion carries it exactly (the rest
// pose's neighbourhood is kept: a fold that forms is seen by curvature, not by the basis); its
// opposing neighbours' normal integrals move by the normal's transform and scale alone, their
// centroid's offset by the blended matrix's 3x3 (as a tangent does). A
// skinned vertex ends in world space (the joint matrices put it there), an unskinned one stays in
// object space. uv, tangent.w and curvature are copied (curvature.comp
// recomputes curvature afterwards where the material asks for it). A normal or tangent that the
// deformation collapses to zero length keeps its undeformed value, as on the CPU.
// The CPU reference is deformPrimitive (<preskin/Deformation.h>).
// Limits: 8 influences per vertex (two JOINTS/WEIGHTS sets); float precision.
#extension GL_GOOGLE_include_directive : require
#include "shared/deform.h"

layout(local_size_x = kDeformGroupSize) in;

layout(std430, set = 0, binding = kDeformBindingRest) readonly buffer Rest { float rest[]; };
layout(std430, set = 0, binding = kDeformBindingDeltas) readonly buffer Deltas { float deltas[]; };
layout(std430, set = 0, binding = kDeformBindingInfluences) readonly buffer Influences { DeformInfluences influences[]; };
layout(std430, set = 0, binding = kDeformBindingWeights) readonly buffer Weights { float weights[]; };
layout(std430, set = 0, binding = kDeformBindingJoints) readonly buffer Joints { mat4 joints[]; };
layout(std430, set = 0, binding = kDeformBindingOutput) writeonly buffer Output { float outVertices[]; };
layout(std430, set = 0, binding = kDeformBindingRestNormalBasis) readonly buffer RestBasis { float restBasis[]; };
layout(std430, set = 0, binding = kDeformBindingNormalBasis) writeonly buffer OutBasis { float outBasis[]; };
layout(push_constant) uniform Push { DeformPush push; };

vec3 load3(uint i) { return vec3(rest[i], rest[i + 1], rest[i + 2]); }
vec3 delta3(uint i) { return vec3(deltas[i], deltas[i + 1], deltas[i + 2]); }
void store3(uint i, vec3 v) {
    outVertices[i] = v.x;
    outVertices[i + 1] = v.y;
    outVertices[i + 2] = v.z;
}

void main() {
    uint v = gl_GlobalInvocationID.x;
    uint count = push.vertices.z;
    if (v >= count) return;
    uint src = (push.vertices.x + v) * kVertexFloats;
    uint dst = (push.vertices.y + v) * kVertexFloats;
    vec3 position = load3(src + kVertexPosition);
    vec3 restNormal = load3(src + kVertexNormal);
    vec3 restTangent = load3(src + kVertexTangent);
    vec3 normal = restNormal;
    vec3 tangent = restTangent;
    uint basisSrc = (push.vertices.x + v) * kNormalBasisFloats;
    uint basisDst = (push.vertices.y + v) * kNormalBasisFloats;
    vec3 basis[2 * kNormalBasisCount + 1];  // averaged, opposing, centroid offset
    for (uint b = 0; b < 2 * kNormalBasisCount + 1; ++b)
        basis[b] = vec3(restBasis[basisSrc + 3 * b], restBasis[basisSrc + 3 * b + 1], restBasis[basisSrc + 3 * b + 2]);

    uint targets = push.vertices.w;
    for (uint t = 0; t < targets; ++t) {
        float w = weights[push.offsets.z + t];
        if (w == 0.0) continue;
        uint d = push.offsets.x + (t * count + v) * kDeltaFloats;
        position += w * delta3(d);
        normal += w * delta3(d + 3);
        tangent += w * delta3(d + 6);
    }

    vec3 normalDelta = normal - restNormal;
    for (uint b = 0; b < kNormalBasisCount; ++b) basis[b] += dot(basis[b], restNormal) * normalDelta;
    mat3 normalTransform = mat3(1.0);
    mat3 linear = mat3(1.0);
    if (push.offsets.y != 0xffffffffu) {
        DeformInfluences inf = influences[push.offsets.y + v];
        uint jointBase = push.offsets.w;
        mat4 m = inf.weights0.x * joints[jointBase + inf.joints0.x] + inf.weights0.y * joints[jointBase + inf.joints0.y] +
                 inf.weights0.z * joints[jointBase + inf.joints0.z] + inf.weights0.w * joints[jointBase + inf.joints0.w];
        if (inf.weights1 != vec4(0.0))
            m += inf.weights1.x * joints[jointBase + inf.joints1.x] + inf.weights1.y * joints[jointBase + inf.joints1.y] +
                 inf.weights1.z * joints[jointBase + inf.joints1.z] + inf.weights1.w * joints[jointBase + inf.joints1.w];
        position = (m * vec4(position, 1.0)).xyz;
        linear = mat3(m);
        // The inverse transpose up to a positive factor: the cofactor matrix times sign(det).
        mat3 cofactor = mat3(cross(linear[1], linear[2]), cross(linear[2], linear[0]), cross(linear[0], linear[1]));
        normalTransform = (determinant(linear) < 0.0 ? -1.0 : 1.0) * cofactor;
        normal = normalTransform * normal;
        tangent = linear * tangent;
    }
    float nl = length(normal);
    float tl = length(tangent);
    store3(dst + kVertexPosition, position);
    // A normal or tangent the deformation collapses to zero keeps its undeformed value.
    store3(dst + kVertexNormal, nl > 0.0 && !isinf(nl) ? normal / nl : restNormal);
    store3(dst + kVertexTangent, tl > 0.0 && !isinf(tl) ? tangent / tl : restTangent);
    for (uint i = kVertexTangent + 3; i < kVertexFloats; ++i) outVertices[dst + i] = rest[src + i];
    float basisScale = nl > 0.0 && !isinf(nl) ? 1.0 / nl : 1.0;
    for (uint b = 0; b < 2 * kNormalBasisCount + 1; ++b) {
        vec3 m = b < 2 * kNormalBasisCount ? basisScale * (normalTransform * basis[b]) : linear * basis[b];
        outBasis[basisDst + 3 * b] = m.x;
        outBasis[basisDst + 3 * b + 1] = m.y;
        outBasis[basisDst + 3 * b + 2] = m.z;
    }
}
