#version 450 core
// The winding-number sign per sample (Filters/Core/Winding/WindingNumber.h, Inside): the
// hierarchy's order-1 expansions with their error bound at CoarseAccuracy, then at
// Accuracy, then the exact sum, in double precision. GLSL has no double atan, so the
// exact solid angles are summed as the argument of a product of complex numbers, one
// per triangle (Van Oosterom and Strackee: a triangle's angle is 2 arg(den + i det)),
// counting the turns the product makes: w = Turns + arg(Product) / 2 pi. The sign of
// the exact sum needs no atan at all (|w| > 1/2 exactly when Turns is not 0, but for
// w = -1/2); the approximate ones take arg() in single precision, covered by AtanSlack.
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer NodeValues
{
  double node[]; // 17 per node: centre, radius, moment, tensor (row-major), second moment
};
layout(std430, binding = 1) readonly buffer NodeLinks
{
  ivec4 link[]; // first triangle, count, children (-1: a leaf)
};
layout(std430, binding = 2) readonly buffer Corners
{
  double corner[]; // 9 per triangle
};
layout(std430, binding = 3) writeonly buffer Answers
{
  uint answer[]; // bit 0: inside; bit 1: the exact sum was needed
};
layout(std430, binding = 4) writeonly buffer Values
{
  float value[]; // w, when WantValues
};
//DF::SampleGrid
uniform int First; // sample index of invocation 0
uniform int Last;  // one past the last sample of this dispatch
uniform int TriangleCount;
uniform double CoarseAccuracy, Accuracy, ValueAccuracy;
uniform int WantValues;

const double Pi = 3.141592653589793LF;
const double TwoPi = 6.283185307179586LF;
const double FourPi = 12.566370614359172LF;
// Single-precision atan errs by far less than 1e-5 rad; in w that is 1e-5 / 2 pi.
const double AtanSlack = 2e-6LF;

dvec2 Product; // the running product, scaled to keep it in range (scaling keeps arg)
int Turns;     // full turns its argument made

void MultiplyAngle(dvec2 z)
{
  if (z.x == 0.0LF && z.y == 0.0LF)
  {
    return; // q at a corner: atan2(0, 0) = 0
  }
  dvec2 p = dvec2(Product.x * z.x - Product.y * z.y, Product.x * z.y + Product.y * z.x);
  // Arguments in (-pi, pi]: the sum wrapped when both halves agree and the product's
  // imaginary part changed side.
  if (Product.y >= 0.0LF && z.y >= 0.0LF)
  {
    if (p.y < 0.0LF || (p.y == 0.0LF && p.x > 0.0LF && Product.x < 0.0LF && z.x < 0.0LF))
    {
      Turns += 1;
    }
  }
  else if (Product.y < 0.0LF && z.y < 0.0LF && p.y >= 0.0LF)
  {
    Turns -= 1;
  }
  Product = p / max(abs(p.x), abs(p.y));
}

void AddTriangle(int t, dvec3 q)
{
  int b = 9 * t;
  dvec3 u = dvec3(corner[b], corner[b + 1], corner[b + 2]) - q;
  dvec3 v = dvec3(corner[b + 3], corner[b + 4], corner[b + 5]) - q;
  dvec3 w = dvec3(corner[b + 6], corner[b + 7], corner[b + 8]) - q;
  double lu = sqrt(dot(u, u)), lv = sqrt(dot(v, v)), lw = sqrt(dot(w, w));
  double det = dot(u, cross(v, w));
  double den = lu * lv * lw + dot(u, v) * lw + dot(u, w) * lv + dot(v, w) * lu;
  MultiplyAngle(dvec2(den, det));
}

// arg(Product) in (-pi, pi], an imaginary part of 0 counting as the upper side (as the
// turns count it), also where single precision rounds a tiny one to 0.
double Angle()
{
  float y = float(Product.y), x = float(Product.x);
  if (y == 0.0)
  {
    return Product.x >= 0.0LF ? 0.0LF : (Product.y >= 0.0LF ? Pi : -Pi);
  }
  return double(atan(y, x));
}

// The approximation at `accuracy`: returns w, with its bound in `bound`.
double Evaluate(dvec3 q, double accuracy, out double bound)
{
  Product = dvec2(1.0LF, 0.0LF);
  Turns = 0;
  double far = 0.0LF;
  bound = 0.0LF;
  int stack[64];
  int depth = 0;
  stack[depth++] = 0;
  while (depth > 0)
  {
    int n = stack[--depth];
    int b = 17 * n;
    dvec3 d = dvec3(node[b], node[b + 1], node[b + 2]) - q;
    double radius = node[b + 3];
    double r2 = dot(d, d);
    double r = sqrt(r2);
    double gap = r - radius;
    ivec4 l = link[n];
    if (r2 > accuracy * accuracy * radius * radius && gap > 0.0LF)
    {
      dvec3 moment = dvec3(node[b + 4], node[b + 5], node[b + 6]);
      dvec3 td = dvec3(node[b + 7] * d.x + node[b + 8] * d.y + node[b + 9] * d.z,
        node[b + 10] * d.x + node[b + 11] * d.y + node[b + 12] * d.z,
        node[b + 13] * d.x + node[b + 14] * d.y + node[b + 15] * d.z);
      double trace = node[b + 7] + node[b + 11] + node[b + 15];
      far += (dot(moment, d) + trace - 3.0LF * dot(d, td) / r2) / (FourPi * r2 * r);
      double gap2 = gap * gap;
      bound += 3.0LF * node[b + 16] / (FourPi * gap2 * gap2);
    }
    else if (l.z < 0)
    {
      for (int t = l.x; t < l.x + l.y; ++t)
      {
        AddTriangle(t, q);
      }
    }
    else
    {
      stack[depth++] = l.z;
      stack[depth++] = l.w;
    }
  }
  return far + double(Turns) + Angle() / TwoPi;
}

void main()
{
  int s = First + int(gl_GlobalInvocationID.x);
  if (s >= Last)
  {
    return;
  }
  int i = s % Dims.x;
  int j = (s / Dims.x) % Dims.y;
  int k = s / (Dims.x * Dims.y);
  dvec3 q = Origin + dvec3(Lo + ivec3(i, j, k)) * Spacing;
  bool decided = false, inside = false;
  double w = 0.0LF, bound = 0.0LF;
  if (WantValues != 0)
  {
    w = Evaluate(q, max(Accuracy, ValueAccuracy), bound);
    decided = abs(abs(w) - 0.5LF) > bound + AtanSlack;
  }
  else
  {
    w = Evaluate(q, min(CoarseAccuracy, Accuracy), bound);
    decided = abs(abs(w) - 0.5LF) > bound + AtanSlack;
    if (!decided)
    {
      w = Evaluate(q, Accuracy, bound);
      decided = abs(abs(w) - 0.5LF) > bound + AtanSlack;
    }
  }
  if (decided)
  {
    inside = abs(w) > 0.5LF;
  }
  else
  {
    Product = dvec2(1.0LF, 0.0LF);
    Turns = 0;
    for (int t = 0; t < TriangleCount; ++t)
    {
      AddTriangle(t, q);
    }
    // w = Turns + arg / 2 pi with arg in (-pi, pi]: |w| > 1/2 but for w = -1/2.
    inside = Turns != 0 && !(Turns == -1 && Product.y == 0.0LF && Product.x < 0.0LF);
    w = double(Turns) + Angle() / TwoPi;
  }
  answer[s - First] = (inside ? 1u : 0u) | (decided ? 0u : 2u);
  if (WantValues != 0)
  {
    value[s - First] = float(w);
  }
}
