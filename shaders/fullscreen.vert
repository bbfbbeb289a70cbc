// One triangle covering the viewport (vertices 0, 1, 2, no buffers): the background and the
// screen-space occlusion passes.
void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
