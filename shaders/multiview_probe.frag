#version 460
// multiview_probe.frag: white wherever the probe triangle covers (see multiview_probe.vert).

layout(location = 0) out vec4 outColor;

void main() { outColor = vec4(1.0); }
