// The samples a pass covers (Filters/Core/GL/GridUniforms.h sets them): Dims samples per
// axis from sample index Lo, sample (i, j, k) at Origin + (i, j, k) * Spacing.
uniform ivec3 Dims;
uniform ivec3 Lo;
uniform dvec3 Origin, Spacing;
