#version 450 core
// The union closest-point views (Filters/Core/Union/UnionClosestPointGPU.h), many queries
// per draw: instance k is query k of the batch. The pieces' corners are relative to the
// scene's centre in float, so that subtracting O loses little.
layout(location = 0) in vec3 Position;

// Per query of the batch: O (relative to the scene's centre) and Far.
layout(std430, binding = 0) readonly buffer QueryBlock
{
  vec4 Queries[];
};

out vec3 Relative;
flat out int Instance;

void main()
{
  Relative = Position - Queries[gl_InstanceID].xyz;
  Instance = gl_InstanceID;
}
