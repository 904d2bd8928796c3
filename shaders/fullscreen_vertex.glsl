// fullscreen_vertex.glsl: one triangle over the viewport for the passes after the forward pass
// (shaders/screen_diffusion.frag), in every eye: the including file defines PRESKIN_EYE_INDEX
// (and PRESKIN_WRITE_LAYER for layered drawing), as forward_vertex.glsl does.
layout(location = 0) flat out uint outEye;

void main() {
    outEye = uint(PRESKIN_EYE_INDEX);
    vec2 p = vec2(float((gl_VertexIndex << 1) & 2), float(gl_VertexIndex & 2)) * 2.0 - 1.0;
    gl_Position = vec4(p, 0.0, 1.0);
#ifdef PRESKIN_WRITE_LAYER
    gl_Layer = int(outEye);
#endif
}
