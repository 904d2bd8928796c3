// The CPU deformation of a primitive in a pose (<preskin/Animation.h>): morph targets, then linear
// blend skinning, as the renderer's deformation compute pass does it on the GPU. The reference for
// that pass's tests, and for hosts that need deformed geometry on the CPU (picking, physics); in
// libpreskin_reference (preskin::reference) with the diffusion reference.
#pragma once

#include <preskin/Animation.h>
#include <preskin/Export.h>
#include <preskin/Scene.h>

#include <vector>

namespace preskin {

// Deforms `primitive` into `out` (same vertex count and order): positions, normals and tangents
// in draw space (object space; world space for a skinned primitive, whose pose carries joint
// matrices); normals and tangents renormalised, tangent.w, uv and curvature copied (curvature is
// not recomputed here: computeVertexCurvature of the result does that). `pose.morphWeights` may
// be shorter than the target list (missing weights are 0).
PRESKIN_API void deformPrimitive(const Primitive& primitive, const InstancePose& pose, std::vector<Vertex>& out);

}  // namespace preskin
