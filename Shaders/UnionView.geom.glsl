#version 450 core
// Each triangle into the six cube-face views around its query's O (layer = 6 query +
// view): a 90-degree perspective per face, looking down -z of the view's right-handed
// frame. In the zero-hop pass (ZeroPass), only the queries whose O the piece holds.
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
out vec3 FragRelative;
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
  for (int k = 0; k < 3; ++k)
  {
    const vec3 v = view * Relative[k];
    // The standard perspective (z only clips: the depth is written by the fragment shader).
    gl_Position = vec4(v.x, v.y, (-v.z * (far + near) - 2.0 * far * near) / (far - near), -v.z);
    FragRelative = Relative[k];
    FragFar = far;
    gl_Layer = 6 * query + gl_InvocationID;
    EmitVertex();
  }
  EndPrimitive();
}
