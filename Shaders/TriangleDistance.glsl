// The exact squared distance from a point to a segment and to a triangle, in double
// precision: Filters/Core/Common/PointTriangleDistance.h operation for operation (`precise`,
// so that nothing is fused or reordered), with the closest point or without. Shaders that
// need it have the line //DF::TriangleDistance where these go (HeadlessGL's BuildProgram
// puts them there, GridUniforms.h).

double DistanceDot(dvec3 u, dvec3 v)
{
  precise double d = u.x * v.x + u.y * v.y + u.z * v.z;
  return d;
}

double SquaredDistanceToSegment(dvec3 p, dvec3 a, dvec3 b, out dvec3 closest)
{
  precise dvec3 ab = b - a, ap = p - a;
  precise double length2 = DistanceDot(ab, ab), along = DistanceDot(ap, ab);
  precise double t = length2 > 0.0lf ? min(1.0lf, max(0.0lf, along / length2)) : 0.0lf;
  precise dvec3 on = a + t * ab;
  precise dvec3 e = on - p;
  precise double sum = e.x * e.x + e.y * e.y + e.z * e.z;
  closest = on;
  return sum;
}

// Ericson, Real-Time Collision Detection, 5.1.5; a degenerate triangle is its edges.
double SquaredDistanceToTriangle(dvec3 p, dvec3 a, dvec3 b, dvec3 c, out dvec3 closest)
{
  precise dvec3 ab = b - a, ac = c - a, ap = p - a, bp = p - b, cp = p - c;
  precise double d1 = DistanceDot(ab, ap), d2 = DistanceDot(ac, ap);
  precise double d3 = DistanceDot(ab, bp), d4 = DistanceDot(ac, bp);
  precise double d5 = DistanceDot(ab, cp), d6 = DistanceDot(ac, cp);
  precise double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
  precise double v = 0.0lf, w = 0.0lf;
  if (d1 <= 0.0lf && d2 <= 0.0lf)
  {
    v = 0.0lf;
    w = 0.0lf;
  }
  else if (d3 >= 0.0lf && d4 <= d3)
  {
    v = 1.0lf;
    w = 0.0lf;
  }
  else if (vc <= 0.0lf && d1 >= 0.0lf && d3 <= 0.0lf)
  {
    v = d1 / (d1 - d3);
    w = 0.0lf;
  }
  else if (d6 >= 0.0lf && d5 <= d6)
  {
    v = 0.0lf;
    w = 1.0lf;
  }
  else if (vb <= 0.0lf && d2 >= 0.0lf && d6 <= 0.0lf)
  {
    v = 0.0lf;
    w = d2 / (d2 - d6);
  }
  else if (va <= 0.0lf && (d4 - d3) >= 0.0lf && (d5 - d6) >= 0.0lf)
  {
    w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    v = 1.0lf - w;
  }
  else
  {
    precise double area2 = va + vb + vc;
    if (!(area2 > 0.0lf))
    {
      dvec3 onAB, onBC, onCA;
      double e0 = SquaredDistanceToSegment(p, a, b, onAB);
      double e1 = SquaredDistanceToSegment(p, b, c, onBC);
      double e2 = SquaredDistanceToSegment(p, c, a, onCA);
      if (e0 <= e1 && e0 <= e2)
      {
        closest = onAB;
        return e0;
      }
      if (e1 <= e2)
      {
        closest = onBC;
        return e1;
      }
      closest = onCA;
      return e2;
    }
    precise double denominator = 1.0lf / area2;
    v = vb * denominator;
    w = vc * denominator;
  }
  precise dvec3 on = a + v * ab + w * ac;
  precise dvec3 e = on - p;
  precise double sum = e.x * e.x + e.y * e.y + e.z * e.z;
  closest = on;
  return sum;
}

double SquaredDistanceToSegment(dvec3 p, dvec3 a, dvec3 b)
{
  dvec3 closest;
  return SquaredDistanceToSegment(p, a, b, closest);
}

double SquaredDistanceToTriangle(dvec3 p, dvec3 a, dvec3 b, dvec3 c)
{
  dvec3 closest;
  return SquaredDistanceToTriangle(p, a, b, c, closest);
}
