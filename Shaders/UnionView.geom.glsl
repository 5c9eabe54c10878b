#version 450 core
// Each triangle into the six cube-face views around its query's O (layer = 6 query +
// view): a 90-degree perspective per face, looking down -z of the view's right-handed
// frame, culled per view. In the zero-hop pass (ZeroPass), only the queries whose O the
// piece holds.
layout(triangles, invocations = 6) in;
layout(triangle_strip, max_vertices = 3) out;

layout(std430, binding = 0) readonly buffer QueryBlock
{
  vec4 Queries[];
};
// Per query and piece: 1 when the piece holds O.
layout(std430, binding = 1) readonly buffer ContainsBlock
{
  uint Contains[];
};

in vec3 Relative[];
flat in int Instance[];
// The triangle's plane in the view's frame, n . v = w (the fragment shader intersects
// each pixel's ray with it).
flat out vec4 FragPlane;
flat out float FragFar;

uniform mat3 Views[6]; // rows: right, up, back (= -forward)
uniform int ZeroPass;
uniform int Piece, PieceCount;

void main()
{
  const int query = Instance[0];
  if (ZeroPass != 0 && Contains[query * PieceCount + Piece] == 0u)
  {
    return;
  }
  const float far = Queries[query].w;
  const float near = far * 1e-7;
  const mat3 view = Views[gl_InvocationID];
  vec3 v[3];
  for (int k = 0; k < 3; ++k)
  {
    v[k] = view * Relative[k];
  }
  // View-frustum culling per view: a triangle wholly beyond one side of this view's
  // frustum (|x| <= -z, |y| <= -z, -z <= far) is not sent to it.
  for (int side = 0; side < 5; ++side)
  {
    bool beyond = true;
    for (int k = 0; k < 3; ++k)
    {
      const float w = -v[k].z;
      const float s = side == 0 ? v[k].x - w : side == 1 ? -v[k].x - w : side == 2 ? v[k].y - w
        : side == 3 ? -v[k].y - w : w - far;
      beyond = beyond && s > 0.0;
    }
    if (beyond)
    {
      return;
    }
  }
  const vec3 normal = cross(v[1] - v[0], v[2] - v[0]);
  const vec4 plane = vec4(normal, dot(normal, v[0]));
  for (int k = 0; k < 3; ++k)
  {
    // The standard perspective (z only clips: the depth is written by the fragment shader).
    gl_Position =
      vec4(v[k].x, v[k].y, (-v[k].z * (far + near) - 2.0 * far * near) / (far - near), -v[k].z);
    FragPlane = plane;
    FragFar = far;
    gl_Layer = 6 * query + gl_InvocationID;
    EmitVertex();
  }
  EndPrimitive();
}
