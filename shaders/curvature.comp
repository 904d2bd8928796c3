#version 460
// curvature.comp: per-vertex signed mean curvature of a deformed mesh instance (> 0 convex, < 0
// concave, outward normals), the same estimator as
// computeVertexCurvature (<preskin/Curvature.h>; Rusinkiewicz 2004) over the same welded mesh
// (vertices welded by position and normal hemisphere at load, so seams stay continuous), in four
// steps selected by a specialization constant, each one dispatch:
//   kCurvatureStepWelded    per welded vertex: the position of its first member and the unit sum
//                           of its members' unit normals (the area-weighted face normal where
//                           those cancel);
//   kCurvatureStepTriangles per triangle: the shape operator fitted by least squares to the change
//                           of the welded normals along the three edges, in the triangle's own
//                           frame with edges scaled by the longest (for float precision); writes
//                           its area and mean curvature (half the trace);
//   kCurvatureStepVertices  per welded vertex: the area-weighted mean over incident triangles
//                           (a gather over an adjacency list built at load: deterministic);
//   kCurvatureStepSmooth    per welded vertex: half its own value, half its one-ring's mean,
//                           signed, written into every member vertex whose material asks for
//                           deformed curvature.
// Limits: float precision (the CPU estimator uses double); triangles whose welded corners repeat
// are left out at load, as the CPU estimator does.
#extension GL_GOOGLE_include_directive : require
#include "shared/deform.h"

layout(constant_id = kCurvatureSpecStep) const uint kStep = kCurvatureStepWelded;
layout(local_size_x = kDeformGroupSize) in;

layout(std430, set = 0, binding = kDeformBindingOutput) buffer Output { float vertices[]; };
layout(std430, set = 0, binding = kDeformBindingTopology) readonly buffer Topology { uint topology[]; };
layout(std430, set = 0, binding = kDeformBindingScratch) buffer Scratch { vec4 scratch[]; };
layout(push_constant) uniform Push { CurvaturePush push; };

uint weldedCount() { return push.counts.x; }
uint memberStart(uint w) { return topology[push.topology.x + w]; }
uint member(uint i) { return topology[push.topology.x + weldedCount() + 1 + i]; }
uint incidentStart(uint w) { return topology[push.topology.y + w]; }
uint incident(uint i) { return topology[push.topology.y + weldedCount() + 1 + i]; }
uint neighbourStart(uint w) { return topology[push.topology.z + w]; }
uint neighbour(uint i) { return topology[push.topology.z + weldedCount() + 1 + i]; }
uvec3 triangle(uint t) {
    uint i = push.topology.w + 3 * t;
    return uvec3(topology[i], topology[i + 1], topology[i + 2]);
}

uint vertexFloat(uint memberValue, uint component) {
    return (push.counts.z + (memberValue & ~kCurvatureKeepRest)) * kVertexFloats + component;
}
vec3 vertex3(uint memberValue, uint component) {
    uint i = vertexFloat(memberValue, component);
    return vec3(vertices[i], vertices[i + 1], vertices[i + 2]);
}
vec3 weldedPosition(uint w) { return scratch[push.scratch.x + w].xyz; }
vec3 weldedNormal(uint w) { return scratch[push.scratch.y + w].xyz; }

void stepWelded(uint w) {
    uint first = memberStart(w);
    uint end = memberStart(w + 1);
    vec3 position = vertex3(member(first), kVertexPosition);
    vec3 sum = vec3(0.0);
    for (uint i = first; i < end; ++i) {
        vec3 n = vertex3(member(i), kVertexNormal);
        float len = length(n);
        if (len > 1e-12) sum += n / len;
    }
    if (length(sum) < 1e-6) {  // normals cancel: the area-weighted normal of the incident triangles
        sum = vec3(0.0);
        for (uint i = incidentStart(w); i < incidentStart(w + 1); ++i) {
            uvec3 t = triangle(incident(i));
            vec3 a = vertex3(member(memberStart(t.x)), kVertexPosition);
            vec3 b = vertex3(member(memberStart(t.y)), kVertexPosition);
            vec3 c = vertex3(member(memberStart(t.z)), kVertexPosition);
            sum += cross(b - a, c - a);
        }
    }
    float len = length(sum);
    scratch[push.scratch.x + w] = vec4(position, 0.0);
    scratch[push.scratch.y + w] = vec4(len > 0.0 ? sum / len : vec3(0.0), 0.0);
}

float det3(mat3 a) { return determinant(a); }

void stepTriangles(uint t) {
    uvec3 w = triangle(t);
    vec3 p0 = weldedPosition(w.x), p1 = weldedPosition(w.y), p2 = weldedPosition(w.z);
    float longest = sqrt(max(max(dot(p1 - p0, p1 - p0), dot(p2 - p1, p2 - p1)), dot(p0 - p2, p0 - p2)));
    vec2 result = vec2(0.0);  // area, mean curvature
    if (longest > 0.0) {
        // Edges in units of the longest edge keep the normal equations near 1 in float.
        vec3 q1 = (p1 - p0) / longest, q2 = (p2 - p0) / longest;
        vec3 areaNormal = cross(q1, q2);
        float twiceArea = length(areaNormal);
        if (twiceArea > 1e-10) {
            vec3 faceNormal = areaNormal / twiceArea;
            vec3 u = normalize(q1);
            vec3 v = cross(faceNormal, u);
            vec3 corner[3] = vec3[3](vec3(0.0), q1, q2);
            vec3 normal[3] = vec3[3](weldedNormal(w.x), weldedNormal(w.y), weldedNormal(w.z));
            mat3 m = mat3(0.0);  // m[column][row]
            vec3 r = vec3(0.0);
            for (int k = 0; k < 3; ++k) {
                vec3 edge = corner[(k + 1) % 3] - corner[k];
                vec3 dn = normal[(k + 1) % 3] - normal[k];
                float eu = dot(edge, u), ev = dot(edge, v);
                float dnu = dot(dn, u), dnv = dot(dn, v);
                vec3 rowA = vec3(eu, ev, 0.0), rowB = vec3(0.0, eu, ev);
                m += outerProduct(rowA, rowA) + outerProduct(rowB, rowB);
                r += rowA * dnu + rowB * dnv;
            }
            float det = det3(m);
            float scale = max(max(abs(m[0][0]), abs(m[1][1])), max(abs(m[2][2]), max(abs(m[0][1]), abs(m[1][2]))));
            if (abs(det) > 1e-12 * scale * scale * scale) {
                // Cramer's rule, as the CPU estimator solves it.
                float e = det3(mat3(r, m[1], m[2])) / det;
                float g = det3(mat3(m[0], m[1], r)) / det;
                float h = 0.5 * (e + g) / longest;  // back to 1 / (mesh units)
                float area = 0.5 * twiceArea * longest * longest;
                if (!isnan(h) && !isinf(h)) result = vec2(area, h);
            }
        }
    }
    scratch[push.scratch.z + t] = vec4(result, 0.0, 0.0);
}

void stepVertices(uint w) {
    float weighted = 0.0, areas = 0.0;
    for (uint i = incidentStart(w); i < incidentStart(w + 1); ++i) {
        vec2 t = scratch[push.scratch.z + incident(i)].xy;
        weighted += t.x * t.y;
        areas += t.x;
    }
    scratch[push.scratch.w + w] = vec4(areas > 0.0 ? weighted / areas : 0.0);
}

void stepSmooth(uint w) {
    float h = scratch[push.scratch.w + w].x;
    uint first = neighbourStart(w), end = neighbourStart(w + 1);
    if (end > first) {
        float sum = 0.0;
        for (uint i = first; i < end; ++i) sum += scratch[push.scratch.w + neighbour(i)].x;
        h = 0.5 * h + 0.5 * sum / float(end - first);
    }
    for (uint i = memberStart(w); i < memberStart(w + 1); ++i) {
        uint m = member(i);
        if ((m & kCurvatureKeepRest) == 0u) vertices[vertexFloat(m, kVertexCurvature)] = h;
    }
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (kStep == kCurvatureStepTriangles) {
        if (i < push.counts.y) stepTriangles(i);
        return;
    }
    if (i >= weldedCount()) return;
    if (kStep == kCurvatureStepWelded) stepWelded(i);
    else if (kStep == kCurvatureStepVertices) stepVertices(i);
    else stepSmooth(i);
}
