// Per-vertex mean curvature of a triangle mesh, for the skin's diffuse LUT (curvature = 1/r).
//
// Estimator: the shape operator of each triangle is fitted by least squares to the change of the
// vertex normals along its three edges (Rusinkiewicz, "Estimating Curvatures and Their
// Derivatives on Triangle Meshes", 3DPVT 2004); the triangle's mean curvature is half its trace,
// which does not depend on the frame chosen in the triangle's plane. Vertex values are the
// area-weighted average over the incident triangles, followed by one light smoothing pass over
// the one-ring (half the vertex's own value, half its neighbours' mean).
//
// Convention: signed mean curvature H = (k1 + k2) / 2 in 1 / (mesh units), positive where the
// surface bends away from its normals (convex, with outward normals): a sphere of radius r gives
// 1/r seen from outside and -1/r from inside (the inside of a bowl, normals pointing inwards), a
// cylinder 1/(2r), a plane 0. A saddle whose principal curvatures cancel gives about 0; one
// that bends more along its concave direction gives a negative value.
//
// Seams: vertices are welded by exact position before the estimate, so vertices duplicated along
// UV or normal seams get one value. Vertices at one position whose normals face apart (more than
// 90 degrees: hard edges, the two sides of a double-sided sheet) stay separate.
//
// Limits: the estimate is only as smooth as the vertex normals it is given (pass smooth normals;
// flat per-face normals are averaged per position, which works for tessellated smooth shapes).
// Positions must be finite. Cost is linear in the mesh size; recompute after deformation.
#pragma once

#include <preskin/Export.h>

#include <preskin/Glm.h>

#include <cstdint>
#include <span>
#include <vector>

namespace preskin {

struct Mesh;

// Signed mean curvature per vertex, in 1 / (units of `positions`). `normals` are per-vertex
// unit normals (same count as `positions`), `indices` a triangle list. Throws preskin::Error
// when the counts disagree or an index is out of range.
PRESKIN_API std::vector<float> computeVertexCurvature(std::span<const glm::vec3> positions,
                                                      std::span<const glm::vec3> normals,
                                                      std::span<const uint32_t> indices);

// Recomputes Vertex::curvaturePerM of every primitive of `mesh` in object-space units. All
// primitives are treated as one surface, so curvature is continuous across primitive borders.
PRESKIN_API void updateMeshCurvature(Mesh& mesh);

}  // namespace preskin
