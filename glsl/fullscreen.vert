// One triangle that covers the viewport (vertices at (-1,-1), (3,-1),
// (-1,3)), with no vertex buffer: cheaper than a quad and no diagonal seam.
void main() {
  const vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
