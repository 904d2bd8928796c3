// forward_specialization.glsl: the forward pass's specialization constants (ids in
// shared/gpu_types.h), read by both of its stages, and what follows from them: what a skin
// material reads (kSpecSkinInputs), which skin terms the vertex stage finds, and the material's
// own LutMapping (kSpecLutMapping). Pipelines are specialised so that work a material does not
// need is not compiled: a CPU driver (lavapipe) runs both sides of every branch under a lane
// mask, so a skipped branch still costs it.
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
layout(constant_id = kSpecSpecular) const uint kSpecular = kSpecularIbl;
const float kSpecularWeight = kSpecular != kSpecularOff ? 1.0 : 0.0;
layout(constant_id = kSpecProfileMix) const uint kProfileMix = 4;
// The area light types the light loop has code for (bit kLight* - kLightSphere each; 0: none, the
// punctual loop; a directional light with an angular radius counts as a sphere), and whether the
// shadow light has a size: a CPU driver would pay for code of absent types in every loop.
layout(constant_id = kSpecAreaLights) const uint kAreaLights = 0;
const uint kAreaLightShapes = kAreaLights & 15u;  // the bits of the four area light types
const bool kSizedShadowLight = (kAreaLights & kAreaLightSizedShadow) != 0u;
// The shadow light shaded as a cap (a sun wide enough, or sphere lights in the frame anyway).
const bool kCapShadowLight = (kAreaLights & (kAreaLightSizedShadow | 1u)) == (kAreaLightSizedShadow | 1u);
// What a skin material reads (kSpecSkinInputs): a pipeline for a material without a detail map or
// with per-vertex curvature has no code for the others.
layout(constant_id = kSpecSkinInputs) const uint kSkinInputs = 0;
const bool kSkinDetailNormals = (kSkinInputs & kSkinInputDetailNormals) != 0u;
const uint kSkinCurvatureSource = (kSkinInputs >> kSkinInputCurvatureShift) & 3u;
const uint kSkinNormalLevels = (kSkinInputs >> kSkinInputNormalLevelsShift) & 31u;  // PreskinNormalMaps::levelCount
const bool kSkinSpecularMap = (kSkinInputs & kSkinInputSpecularMap) != 0u;
const bool kSkinSpecularInBaseAlpha = (kSkinInputs & kSkinInputSpecularInBaseAlpha) != 0u;
const bool kSkinDoubleSided = (kSkinInputs & kSkinInputDoubleSided) != 0u;
const bool kSkinSpecularFromLevels = (kSkinInputs & kSkinInputSpecularFromLevels) != 0u;  // PreskinNormalMaps::specularFromLevels
// What depends on curvature, the geometric normal and the shadow light alone
// (preskin/skin_vertex.glsl) is found by the vertex stage and interpolated where curvature is per
// vertex or from a curvature map, read at the vertex (unless RenderSettings::skinTermsPerVertex is
// off: kSkinInputTermsPerFragment; never for screen-derivative curvature): the shadow
// lookup's lift, the SH transfer, the diffuse row's smoothed ramp and, on single-sided skin (the vertex stage cannot tell which side
// faces the viewer), the transmittance the diffuse LUT already holds; a material blending profiles
// finds them for the blend at the vertex (materialProfileMix of forward_material.glsl).
// (Written as comparisons of uints: glslang turns && of specialization constants into control flow.)
const uint kSkinVertexCurvature = uint(kMaterialModel == kModelSkin) &
                                  uint(kSkinCurvatureSource != kCurvatureSourceDerivatives) &
                                  uint((kSkinInputs & kSkinInputTermsPerFragment) == 0u);
const bool kSkinShPerVertex =
    (kSkinVertexCurvature & uint((kSkinFeatures & kSkinShAmbient) != 0u)) != 0u;
const bool kSkinLiftPerVertex = (kSkinVertexCurvature & uint((kSkinFeatures & kSkinLutDiffuse) != 0u)) != 0u;
// The diffuse row's smoothed ramp (preskinDiffuseFit), which the lights without the table read.
const bool kSkinRowFitPerVertex =
    (kSkinVertexCurvature & uint((kSkinFeatures & kSkinLutDiffuse) != 0u) &
     uint((kSkinFeatures & (kSkinLutOtherLights | kSkinLutShadowLight)) != (kSkinLutOtherLights | kSkinLutShadowLight))) != 0u;
// Skin with penumbra scattering samples the wide shadow map (shaders/shadow_reduce.comp) too.
const bool kSkinWideShadow =
    (uint(kMaterialModel == kModelSkin) & uint((kSkinFeatures & kSkinWideShadowBits) == kSkinWideShadowBits)) != 0u;
const bool kSkinSphereTransmittancePerVertex =
    (kSkinVertexCurvature & uint((kSkinFeatures & kSkinLutDiffuse) != 0u) &
     uint((kSkinFeatures & kSkinTransmission) != 0u) & uint(!kSkinDoubleSided)) != 0u;

// A skin material's own profile's LutMapping (kSpecLutMapping: the pipeline is specialised to its
// LUT layout): uniform-buffer reads would cost a CPU driver (lavapipe) a gather per component, lane
// by lane, in every fragment.
layout(constant_id = kSpecLutMapping + 0u) const float kLutMapping0 = 0.0;
layout(constant_id = kSpecLutMapping + 1u) const float kLutMapping1 = 0.0;
layout(constant_id = kSpecLutMapping + 2u) const float kLutMapping2 = 0.0;
layout(constant_id = kSpecLutMapping + 3u) const float kLutMapping3 = 0.0;
layout(constant_id = kSpecLutMapping + 4u) const float kLutMapping4 = 0.0;
layout(constant_id = kSpecLutMapping + 5u) const float kLutMapping5 = 0.0;
layout(constant_id = kSpecLutMapping + 6u) const float kLutMapping6 = 0.0;
layout(constant_id = kSpecLutMapping + 7u) const float kLutMapping7 = 0.0;
layout(constant_id = kSpecLutMapping + 8u) const float kLutMapping8 = 0.0;
layout(constant_id = kSpecLutMapping + 9u) const float kLutMapping9 = 0.0;
layout(constant_id = kSpecLutMapping + 10u) const float kLutMapping10 = 0.0;
layout(constant_id = kSpecLutMapping + 11u) const float kLutMapping11 = 0.0;
layout(constant_id = kSpecLutMapping + 12u) const float kLutMapping12 = 0.0;
layout(constant_id = kSpecLutMapping + 13u) const float kLutMapping13 = 0.0;
layout(constant_id = kSpecLutMapping + 14u) const float kLutMapping14 = 0.0;
layout(constant_id = kSpecLutMapping + 15u) const float kLutMapping15 = 0.0;
layout(constant_id = kSpecLutMapping + 16u) const float kLutMapping16 = 0.0;
layout(constant_id = kSpecLutMapping + 17u) const float kLutMapping17 = 0.0;
layout(constant_id = kSpecLutMapping + 18u) const float kLutMapping18 = 0.0;
layout(constant_id = kSpecLutMapping + 19u) const float kLutMapping19 = 0.0;
layout(constant_id = kSpecLutMapping + 20u) const float kLutMapping20 = 0.0;
layout(constant_id = kSpecLutMapping + 21u) const float kLutMapping21 = 0.0;
layout(constant_id = kSpecLutMapping + 22u) const float kLutMapping22 = 0.0;
layout(constant_id = kSpecLutMapping + 23u) const float kLutMapping23 = 0.0;
layout(constant_id = kSpecLutMapping + 24u) const float kLutMapping24 = 0.0;
layout(constant_id = kSpecLutMapping + 25u) const float kLutMapping25 = 0.0;
layout(constant_id = kSpecLutMapping + 26u) const float kLutMapping26 = 0.0;
layout(constant_id = kSpecLutMapping + 27u) const float kLutMapping27 = 0.0;
layout(constant_id = kSpecLutMapping + 28u) const float kLutMapping28 = 0.0;
layout(constant_id = kSpecLutMapping + 29u) const float kLutMapping29 = 0.0;
layout(constant_id = kSpecLutMapping + 30u) const float kLutMapping30 = 0.0;
layout(constant_id = kSpecLutMapping + 31u) const float kLutMapping31 = 0.0;

LutMapping specializedLutMapping() {
    LutMapping m;
    m.diffuseNoL = vec4(kLutMapping0, kLutMapping1, kLutMapping2, kLutMapping3);
    m.diffuseCurvature = vec4(kLutMapping4, kLutMapping5, kLutMapping6, kLutMapping7);
    m.penumbraShadow = vec4(kLutMapping8, kLutMapping9, kLutMapping10, kLutMapping11);
    m.penumbraWidth = vec4(kLutMapping12, kLutMapping13, kLutMapping14, kLutMapping15);
    m.shCurvature = vec4(kLutMapping16, kLutMapping17, kLutMapping18, kLutMapping19);
    m.shBandV = vec4(kLutMapping20, kLutMapping21, kLutMapping22, kLutMapping23);
    m.shLambert = vec4(kLutMapping24, kLutMapping25, kLutMapping26, kLutMapping27);
    m.transmittance = vec4(kLutMapping28, kLutMapping29, kLutMapping30, kLutMapping31);
    return m;
}

#endif
