// Covers the lanes a triangle may touch with a screen-aligned rectangle, once per lane
// texel layer (128 bits of lane each) its bits may fall in; the fragment shader decides
// every bit. Boundary (Mode 0) draws the BoundaryTri records of this view, solid (Mode 1)
// the Tri records. RasterInvocations (defined before this source from the grid's deepest
// lanes) invocations of up to 8 layers each: every layer of the grid, no idle invocation.
layout(points, invocations = RasterInvocations) in;
layout(triangle_strip, max_vertices = 32) out;

uniform int Mode; // 0: boundary, 1: solid
uniform int Nb, Nc, Na;

flat out int TriIndex;

void main()
{
  int index = gl_PrimitiveIDIn;
  int p0, p1, q0, q1, first, last;
  if (Mode == 0)
  {
    // The grown bounding box and depth range, set up on the CPU.
    BoundaryTri t = btris[index];
    p0 = t.Rect.x;
    p1 = t.Rect.y;
    q0 = t.Rect.z;
    q1 = t.Rect.w;
    first = t.Depth.x;
    last = t.Depth.y;
  }
  else
  {
    Tri t = tris[index];
    int64_t xmin = min(t.X.x, min(t.X.y, t.X.z)), xmax = max(t.X.x, max(t.X.y, t.X.z));
    int64_t ymin = min(t.Y.x, min(t.Y.y, t.Y.z)), ymax = max(t.Y.x, max(t.Y.y, t.Y.z));
    p0 = int(max(0l, -FloorDiv(-xmin, Subpixel)));
    p1 = int(min(int64_t(Nb - 1), FloorDiv(xmax, Subpixel)));
    q0 = int(max(0l, -FloorDiv(-ymin, Subpixel)));
    q1 = int(min(int64_t(Nc - 1), FloorDiv(ymax, Subpixel)));
    double zmin = min(t.Z[0], min(t.Z[1], t.Z[2])), zmax = max(t.Z[0], max(t.Z[1], t.Z[2]));
    first = SolidBit(zmin, Na);
    last = SolidBit(zmax, Na);
  }
  if (p0 > p1 || q0 > q1 || first > last)
  {
    return;
  }
  // Rectangle edges half-way between lane centres: exactly lanes p0..p1, q0..q1.
  float x0 = 2.0 * (float(p0) / float(Nb)) - 1.0, x1 = 2.0 * (float(p1 + 1) / float(Nb)) - 1.0;
  float y0 = 2.0 * (float(q0) / float(Nc)) - 1.0, y1 = 2.0 * (float(q1 + 1) / float(Nc)) - 1.0;
  for (int layer = first / 128 + gl_InvocationID; layer <= last / 128; layer += RasterInvocations)
  {
    vec2 corners[4] = vec2[4](vec2(x0, y0), vec2(x1, y0), vec2(x0, y1), vec2(x1, y1));
    for (int c = 0; c < 4; ++c)
    {
      TriIndex = index;
      gl_Layer = layer;
      gl_Position = vec4(corners[c], 0.0, 1.0);
      EmitVertex();
    }
    EndPrimitive();
  }
}
