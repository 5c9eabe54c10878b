#version 450 core
// The depth is the Euclidean distance from O, over Far: monotone along each ray, so the
// depth tests compare distances, with no 1/cos conversion and no perspective loss. Front
// faces come nearer by Bias, so that a piece touching the current boundary opens a window.
in vec3 FragRelative;
flat in float FragFar;
uniform float Bias;

void main()
{
  gl_FragDepth = clamp(length(FragRelative) / FragFar - Bias, 0.0, 1.0);
}
