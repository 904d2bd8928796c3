#version 460
// multiview_probe.vert: one triangle far larger than the viewport, the same in both views, so
// that each view has to clip it. engine/src/render/MultiviewProbe.cpp checks that both views of
// a 2-view multiview pass are covered (Mesa lavapipe 22.3 loses clipped triangles in the second
// view). Limits: tests clipping against the x/y planes of two views only.
#extension GL_EXT_multiview : require

void main() {
    const vec2 corners[3] = vec2[3](vec2(-4.0, -4.0), vec2(12.0, -4.0), vec2(-4.0, 12.0));
    gl_Position = vec4(corners[gl_VertexIndex], 0.5, 1.0);
}
