#version 450
// facet's Vulkan renderer: one triangle covering the viewport; the fragment shader does the rest.
void main()
{
    vec2 p = vec2(float((gl_VertexIndex << 1) & 2), float(gl_VertexIndex & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
