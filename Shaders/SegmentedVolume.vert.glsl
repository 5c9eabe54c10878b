//VTK::System::Dec

// A vertex of the volume box's faces, in world coordinates.
in vec4 vertexWC;
uniform mat4 worldToClip;
uniform mat4 worldToIndex;
out vec3 positionWC;
out vec3 positionI;

void main()
{
  positionWC = vertexWC.xyz;
  positionI = (worldToIndex * vertexWC).xyz;
  gl_Position = worldToClip * vertexWC;
}
