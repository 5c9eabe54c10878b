#version 450 core
// The depth is the Euclidean distance from O, over Far: monotone along each ray, so the
// depth tests compare distances, with no 1/cos conversion and no perspective loss. Front
// faces come nearer by Bias, so that a piece touching the current boundary opens a window.
// The distance is where the pixel's ray meets the triangle's plane, not an interpolated
// position: a triangle clipped at the near plane (Far 1e-7 from O) interpolates with
// weights of 1/w, and NVIDIA's GL (H100) was off by 5e-5 of the distance there, 50 times
// the touching bias.
flat in vec4 FragPlane;
flat in float FragFar;
uniform float Bias;
uniform float Pixels; // the views' side

void main()
{
  // The ray through the pixel's centre, in the view's frame (a 90-degree perspective
  // looking down -z): the points s (x, y, -1), s > 0.
  const vec3 ray = vec3(2.0 * gl_FragCoord.xy / Pixels - 1.0, -1.0);
  const float facing = dot(FragPlane.xyz, ray);
  if (facing == 0.0)
  {
    discard; // a triangle seen edge-on (or without area) has no distance to give
  }
  const float along = max(FragPlane.w / facing, 0.0);
  gl_FragDepth = clamp(along * length(ray) / FragFar - Bias, 0.0, 1.0);
}
