// forward_specialization.glsl: the forward pass's specialization constants (ids in
// shared/gpu_types.h), read by both of its stages, and what follows from them: what a skin
// material reads (kSpecSkinInputs) and where its SH transfer is found. Pipelines are specialised
// so that work a material does not need is not compiled: a CPU driver (lavapipe) runs both sides
// of every branch under a lane mask, so a skipped branch still costs it.
#ifndef PRESKIN_FORWARD_SPECIALIZATION_GLSL
#define PRESKIN_FORWARD_SPECIALIZATION_GLSL

#include "shared/gpu_types.h"

layout(constant_id = kSpecMaterialModel) const uint kMaterialModel = kModelStandard;
layout(constant_id = kSpecOutputMode) const uint kOutputMode = kOutputTonemapped;
layout(constant_id = kSpecDebugView) const uint kDebugView = kDebugNone;
layout(constant_id = kSpecAlphaMode) const uint kAlphaMode = 0;
layout(constant_id = kSpecSkinFeatures) const uint kSkinFeatures = kSkinAll;
layout(constant_id = kSpecLightLoop) const uint kLightLoop = kLightLoopAll;
layout(constant_id = kSpecAlphaToCoverage) const uint kAlphaToCoverage = 0;
layout(constant_id = kSpecSpecular) const uint kSpecular = 1;
layout(constant_id = kSpecProfileMix) const uint kProfileMix = 4;
// What a skin material reads (kSpecSkinInputs): a pipeline for a material without a detail map or
// with per-vertex curvature has no code for the others.
layout(constant_id = kSpecSkinInputs) const uint kSkinInputs = 0;
const bool kSkinDetailNormals = (kSkinInputs & 1u) != 0u;
const uint kSkinCurvatureSource = (kSkinInputs >> 1) & 3u;
const uint kSkinNormalLevels = (kSkinInputs >> 3) & 31u;  // PreskinNormalMaps::levelCount
// The SH transfer depends on curvature alone: with per-vertex curvature and one profile (no
// per-texel blend) the vertex stage looks it up and the fragment stage interpolates it.
// (Written as one comparison: glslang turns && of specialization constants into control flow.)
const bool kSkinShPerVertex = (uint(kMaterialModel == kModelSkin) & uint((kSkinFeatures & kSkinShAmbient) != 0u) &
                               uint(kSkinCurvatureSource == kCurvatureSourceVertex) & uint(kProfileMix == 1u)) != 0u;

#endif
