//VTK::System::Dec

// A vertex of a view-aligned slice polygon, in world coordinates.
in vec4 vertexWC;
uniform mat4 worldToClip;
out vec3 positionWC;

void main()
{
  positionWC = vertexWC.xyz;
  gl_Position = worldToClip * vertexWC;
}
