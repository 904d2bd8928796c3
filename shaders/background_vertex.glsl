// background_vertex.glsl: the environment as the backdrop, drawn in the forward pass after the
// opaque draws: one triangle over the viewport at the far plane (depth 0, reversed Z), so the
// depth test keeps it where nothing was drawn. Each vertex carries the world direction through
// it (the eye's clip space unprojected at two depths, which is affine across the screen for
// perspective and orthographic eyes alike). The including file defines PRESKIN_EYE_INDEX (and
// PRESKIN_WRITE_LAYER for layered drawing), as forward_vertex.glsl does.
#include "shared/gpu_types.h"

layout(set = 0, binding = kBindingFrame) uniform Frame { FrameUniforms frame; };

layout(location = 0) out vec3 outDirectionWs;

void main() {
    uint eye = uint(PRESKIN_EYE_INDEX);
    vec2 p = vec2(float((gl_VertexIndex << 1) & 2), float(gl_VertexIndex & 2)) * 2.0 - 1.0;
    mat4 worldFromClip = inverse(frame.eyes[eye].clipFromWorld);
    vec4 nearWs = worldFromClip * vec4(p, 1.0, 1.0);
    vec4 farWs = worldFromClip * vec4(p, 0.5, 1.0);
    outDirectionWs = farWs.xyz / farWs.w - nearWs.xyz / nearWs.w;
    gl_Position = vec4(p, 0.0, 1.0);
#ifdef PRESKIN_WRITE_LAYER
    gl_Layer = int(eye);
#endif
}
