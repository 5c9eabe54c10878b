#version 450 core
// Each triangle into the six cube-face views around O at once (layer = view): a
// 90-degree perspective per face, looking down -z of the view's right-handed frame.
layout(triangles, invocations = 6) in;
layout(triangle_strip, max_vertices = 3) out;

in vec3 Relative[];
out vec3 FragRelative;

uniform mat3 Views[6]; // rows: right, up, back (= -forward)
uniform float Near, Far;

void main()
{
  const mat3 view = Views[gl_InvocationID];
  for (int k = 0; k < 3; ++k)
  {
    const vec3 v = view * Relative[k];
    // The standard perspective (z only clips: the depth is written by the fragment shader).
    gl_Position = vec4(v.x, v.y, (-v.z * (Far + Near) - 2.0 * Far * Near) / (Far - Near), -v.z);
    FragRelative = Relative[k];
    gl_Layer = gl_InvocationID;
    EmitVertex();
  }
  EndPrimitive();
}
