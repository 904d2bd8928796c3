// Animations (glTF 2.0, "Animations"): samplers (input times: float SCALAR, finite, strictly
// increasing, >= 0; outputs: float VEC3 for translation and scale, float or normalized integer
// VEC4 for rotation and SCALAR for weights; STEP, LINEAR or CUBICSPLINE) and channels
// (translation, rotation, scale, weights of a node). A channel without a target node, or with a
// path preskin does not animate (KHR_animation_pointer's "pointer"), is ignored with a warning.
// Errors: input and output counts that disagree (CUBICSPLINE: three outputs per key; weights: one
// per morph target per key), NaN or infinite keys or values, non-increasing or negative times, a
// zero rotation key, a channel on a node that has a matrix, a weights channel on a node without
// morph targets, one sampler driving paths of different kinds, an unknown interpolation.
#pragma once

#include "scene/GltfContext.h"

namespace preskin::gltf {

// Fills Scene::animations; runs after Scene::nodes and the meshes are converted.
void convertAnimations(const LoadContext& ctx);

}  // namespace preskin::gltf
