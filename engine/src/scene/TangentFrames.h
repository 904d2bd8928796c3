// Normals and tangent frames for loaded primitives.
//
// Flat normals: glTF 2.0 says a primitive without NORMAL is shaded flat, so each triangle gets its
// own three vertices carrying the face normal (the index list becomes 0, 1, 2, ...); morph deltas
// and joint influences are copied along with their vertices.
//
// Tangents (when TANGENT is missing): per triangle, dP/du and dP/dv from the UV deltas (Lengyel,
// "Computing Tangent Space Basis Vectors for an Arbitrary Mesh", 2001); each is projected into the
// tangent plane of the corner's vertex normal, normalised and accumulated with the corner angle as
// weight (as MikkTSpace weights corners). The tangent is the Gram-Schmidt orthonormalised sum of
// dP/du; w is the handedness, +1 when cross(N, T) points toward decreasing glTF v ("up" in the
// image, the +Y of glTF normal maps), so bitangent = cross(N, T) * w as the glTF spec defines.
// Triangles with (near) zero UV area or zero geometric area are skipped; a vertex left with no
// usable direction gets any unit vector perpendicular to its normal (w = +1).
// Limits: not bit-identical to MikkTSpace (no splitting of vertices at tangent discontinuities; a
// vertex shared by mirrored UV islands gets an average or the fallback).
#pragma once

#include <preskin/Scene.h>

#include <cstddef>

namespace preskin::scene {

// Splits `primitive` into three vertices per triangle carrying the face normal (with their
// morph deltas and joint influences).
void makeFlatNormals(Primitive& primitive);

// Fills Vertex::tangentOs for all vertices; returns how many got the fallback tangent.
size_t generateTangents(Primitive& primitive);

// Makes given tangents unit length and exactly perpendicular to the normals, w = +-1; returns how
// many were degenerate (zero or parallel to the normal) and were replaced by the fallback.
size_t orthonormalizeTangents(Primitive& primitive);

// A unit vector perpendicular to the unit vector `n`.
glm::vec3 anyPerpendicular(const glm::vec3& n);

}  // namespace preskin::scene
