#version 460
// background.frag: the environment's radiance in the pixel's direction, from its equirectangular
// image at the mip level whose texels match the pixel's angular size, turned by the environment's
// rotation; exposure and (for 8-bit targets) tone mapping as forward.frag applies them.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "preskin/ibl.glsl"
#include "preskin/tonemap.glsl"

layout(constant_id = kSpecOutputMode) const uint kOutputMode = kOutputTonemapped;

layout(set = 0, binding = kBindingFrame) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = kBindingEnvironmentImage) uniform sampler2D environmentImage;

layout(location = 0) in vec3 inDirectionWs;
layout(location = 0) out vec4 outColor;

void main() {
    vec3 d = preskinIblDirection(normalize(inDirectionWs), frame.environment.xy);
    // The pixel's angle (radians) over the image's texel angle (2 pi / width).
    float pixelAngle = length(fwidth(d));
    float width = float(textureSize(environmentImage, 0).x);
    float lod = floor(log2(max(pixelAngle * width / (2.0 * PRESKIN_PI), 1e-6)) + 0.5);  // one level: bilinear
    vec3 color = textureLod(environmentImage, preskinEquirectUv(d), lod).rgb * frame.params.x;
    outColor = vec4(kOutputMode == kOutputTonemapped ? preskinTonemapNeutral(max(color, vec3(0.0))) : color, 1.0);
}
