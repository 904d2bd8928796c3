// The deformation and curvature compute passes (shaders/deform.comp, shaders/curvature.comp):
// bindings, push constants and the vertex layout they read and write, shared by C++
// (engine/src/render/GpuDeformer.cpp) and GLSL.
#ifndef PRESKIN_SHARED_DEFORM_H
#define PRESKIN_SHARED_DEFORM_H

#include "shared/common.h"
#include "shared/constants.h"

PRESKIN_GPU_BEGIN

// A vertex in a float[] buffer: the interleaved Vertex of <preskin/Scene.h> (position 3, normal 3,
// tangent 4, uv 2, curvature 1).
PRESKIN_CONST(uint, kVertexFloats, 13)
PRESKIN_CONST(uint, kVertexPosition, 0)
PRESKIN_CONST(uint, kVertexNormal, 3)
PRESKIN_CONST(uint, kVertexTangent, 6)
PRESKIN_CONST(uint, kVertexCurvature, 12)
// A vertex's skin normal basis in a float[] buffer (NormalBasis of <preskin/NormalBasis.h>):
// kNormalBasisCount vec3 averaged normals, kNormalBasisCount vec3 opposing normals, the opposing
// centroid's offset (vec3); a second buffer laid out like the vertices.
PRESKIN_CONST(uint, kNormalBasisFloats, 27)
// Morph deltas per vertex and target: position 3, normal 3, tangent 3.
PRESKIN_CONST(uint, kDeltaFloats, 9)

// ---- descriptor set 0 of deform.comp and curvature.comp ------------------------------------------
PRESKIN_CONST(uint, kDeformBindingRest, 0)         // float[]: rest vertices (the scene's vertex buffer)
PRESKIN_CONST(uint, kDeformBindingDeltas, 1)       // float[]: morph deltas (kDeltaFloats per vertex and target)
PRESKIN_CONST(uint, kDeformBindingInfluences, 2)   // DeformInfluences[]: joints and weights per skinned vertex
PRESKIN_CONST(uint, kDeformBindingWeights, 3)      // float[]: this frame's morph weights
PRESKIN_CONST(uint, kDeformBindingJoints, 4)       // mat4[]: this frame's joint matrices
PRESKIN_CONST(uint, kDeformBindingOutput, 5)       // float[]: this frame's deformed vertices
PRESKIN_CONST(uint, kDeformBindingTopology, 6)     // uint[]: the curvature pass's welded topology
PRESKIN_CONST(uint, kDeformBindingScratch, 7)      // vec4[]: the curvature pass's per-frame scratch
PRESKIN_CONST(uint, kDeformBindingRestNormalBasis, 8)  // float[]: rest normal basis (the scene's, kNormalBasisFloats per vertex)
PRESKIN_CONST(uint, kDeformBindingNormalBasis, 9)      // float[]: this frame's deformed normal basis

PRESKIN_CONST(uint, kDeformGroupSize, 64)

// curvature.comp: specialization constant 0 selects the step.
PRESKIN_CONST(uint, kCurvatureSpecStep, 0)
PRESKIN_CONST(uint, kCurvatureStepWelded, 0)     // per welded vertex: position and unit normal
PRESKIN_CONST(uint, kCurvatureStepTriangles, 1)  // per triangle: area and mean curvature
PRESKIN_CONST(uint, kCurvatureStepVertices, 2)   // per welded vertex: area-weighted mean
PRESKIN_CONST(uint, kCurvatureStepSmooth, 3)     // per welded vertex: one-ring smoothing, written to the vertices
// Set on a member vertex whose material keeps its bind-pose curvature (the value is not written).
PRESKIN_CONST(uint, kCurvatureKeepRest, 0x80000000u)

struct DeformInfluences {
    uvec4 joints0;
    uvec4 joints1;
    vec4 weights0;
    vec4 weights1;
};
PRESKIN_CHECK_SIZE(DeformInfluences, 64)

// deform.comp, one dispatch per deformed primitive of an instance.
struct DeformPush {
    uvec4 vertices;  // x: first rest vertex, y: first output vertex, z: vertex count, w: morph targets
    uvec4 offsets;   // x: first delta (float index), y: first influence (or ~0: not skinned),
                     // z: first weight, w: first joint matrix
};
PRESKIN_CHECK_SIZE(DeformPush, 32)

// curvature.comp, four dispatches per deformed mesh instance. Topology (uint[] at topology
// offset): for W welded vertices and T triangles, memberStart[W + 1], members[] (vertex index
// within the instance's output range, | kCurvatureKeepRest), incidentStart[W + 1], incident[]
// (triangle indices), neighbourStart[W + 1], neighbours[], triangles[3 T] (welded indices).
struct CurvaturePush {
    uvec4 counts;    // x: welded vertices W, y: triangles T, z: first output vertex of the instance, w: unused
    uvec4 topology;  // uint offsets: x memberStart, y incidentStart, z neighbourStart, w triangles
    uvec4 scratch;   // vec4 offsets: x welded position (xyz), y welded normal (xyz), z per triangle (area, H),
                     // w per welded vertex (H)
};
PRESKIN_CHECK_SIZE(CurvaturePush, 48)

PRESKIN_GPU_END

#endif
