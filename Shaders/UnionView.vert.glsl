#version 450 core
// The union closest-point views (Filters/Core/Union/UnionClosestPointGPU.h): the pieces'
// corners relative to the query point O, in float (relative to the scene's centre first,
// so that the subtraction loses little).
layout(location = 0) in vec3 Position;
uniform vec3 Query;
out vec3 Relative;

void main()
{
  Relative = Position - Query;
}
