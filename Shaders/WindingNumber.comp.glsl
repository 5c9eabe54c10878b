#version 450 core
// The winding-number sign per sample (Filters/Core/Winding/WindingNumber.h, Inside): the
// hierarchy's order-1 expansions with their error bound at CoarseAccuracy, then at
// Accuracy, then the exact sum, in double precision: the CPU's expressions in the CPU's
// order, `precise`, with IEEE's square roots and quotients (SqrtRN, DivRN) and the CPU's
// arctangent (ArcTangent2), so that the decisions, the signs and the values are the
// CPU's bits. The exact solid angles are summed as the argument of a product of complex
// numbers, one per triangle (Van Oosterom and Strackee: a triangle's angle is
// 2 arg(den + i det)), counting the turns the product makes (AngleProduct):
// w = Turns + arg(Product) / 2 pi.
// A sample whose loops would run past IterationBudget (Mesa's llvmpipe silently ends a
// shader's loops after 65,535 iterations of a SIMD vector; no limit on hardware) stops
// and is answered "unfinished": the host decides it with the CPU's same function.
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
  uint answer[]; // bit 0: inside; bit 1: the exact sum was needed; bit 2: unfinished
};
layout(std430, binding = 4) writeonly buffer Values
{
  float value[]; // w, when WantValues
};
//DF::SampleGrid
uniform int First; // sample index of invocation 0
uniform int Last;  // one past the last sample of this dispatch
uniform int TriangleCount;
uniform double CoarseAccuracy, Accuracy, ValueAccuracy, RoundingSlack;
uniform double TwoPi, FourPi; // 2 M_PI and 4 M_PI, the CPU's doubles
uniform int WantValues;
uniform int IterationBudget; // an invocation's loop iterations and loop entries
//DF::CorrectlyRounded
//DF::ArcTangent2

dvec2 Product; // the running product, kept near 1 by powers of two (which keep arg)
int Turns;     // full turns its argument made
int Spent;     // loop iterations and entries so far, against IterationBudget

double Dot(dvec3 a, dvec3 b)
{
  precise double c = a.x * b.x + a.y * b.y + a.z * b.z;
  return c;
}

void MultiplyAngle(double re, double im)
{
  if (re == 0.0lf && im == 0.0lf)
  {
    return; // q at a corner: atan2(0, 0) = 0
  }
  precise double pr = Product.x * re - Product.y * im;
  precise double pi = Product.x * im + Product.y * re;
  // Arguments in (-pi, pi]: the sum wrapped when both lie on one side and the product on
  // the other.
  if (Product.y >= 0.0lf && im >= 0.0lf)
  {
    if (pi < 0.0lf || (pi == 0.0lf && pr > 0.0lf && Product.x < 0.0lf && re < 0.0lf))
    {
      Turns += 1;
    }
  }
  else if (Product.y < 0.0lf && im < 0.0lf && pi >= 0.0lf)
  {
    Turns -= 1;
  }
  Product = dvec2(pr, pi);
  double m = max(abs(pr), abs(pi));
  if (m > ldexp(1.0lf, 100) || m < ldexp(1.0lf, -100))
  {
    int e;
    frexp(m, e);
    Product = dvec2(ldexp(pr, -e), ldexp(pi, -e));
  }
}

void AddTriangle(int t, dvec3 q)
{
  int b = 9 * t;
  precise dvec3 u = dvec3(corner[b], corner[b + 1], corner[b + 2]) - q;
  precise dvec3 v = dvec3(corner[b + 3], corner[b + 4], corner[b + 5]) - q;
  precise dvec3 w = dvec3(corner[b + 6], corner[b + 7], corner[b + 8]) - q;
  precise double lu = SqrtRN(Dot(u, u)), lv = SqrtRN(Dot(v, v)), lw = SqrtRN(Dot(w, w));
  precise double det = u.x * (v.y * w.z - v.z * w.y) + u.y * (v.z * w.x - v.x * w.z) +
    u.z * (v.x * w.y - v.y * w.x);
  precise double den = lu * lv * lw + Dot(u, v) * lw + Dot(u, w) * lv + Dot(v, w) * lu;
  MultiplyAngle(den, det);
}

// Turns + arg(Product) / 2 pi (AngleProduct::Winding).
double Winding()
{
  precise double w = double(Turns) + DivRN(ArcTangent2(Product.y, Product.x), TwoPi);
  return w;
}

// The approximation at `accuracy` (WindingNumber::Evaluate): returns w, with its bound
// in `bound`.
double Evaluate(dvec3 q, double accuracy, out double bound)
{
  Product = dvec2(1.0lf, 0.0lf);
  Turns = 0;
  precise double far = 0.0lf;
  precise double sum = 0.0lf;
  int stack[64];
  int depth = 0;
  stack[depth++] = 0;
  while (depth > 0)
  {
    // A node: an iteration, and the entry of the leaf loop the other lanes may run.
    Spent += 2;
    if (Spent > IterationBudget)
    {
      break;
    }
    int n = stack[--depth];
    int b = 17 * n;
    precise dvec3 d = dvec3(node[b], node[b + 1], node[b + 2]) - q;
    double radius = node[b + 3];
    precise double r2 = Dot(d, d);
    precise double reach = accuracy * accuracy * radius * radius;
    precise double r = SqrtRN(r2);
    precise double gap = r - radius;
    ivec4 l = link[n];
    if (r2 > reach && gap > 0.0lf)
    {
      // FarTerm: M . d / r^3 + (tr T - 3 d.T.d / r^2) / r^3, over 4 pi.
      dvec3 moment = dvec3(node[b + 4], node[b + 5], node[b + 6]);
      precise dvec3 td = dvec3(node[b + 7] * d.x + node[b + 8] * d.y + node[b + 9] * d.z,
        node[b + 10] * d.x + node[b + 11] * d.y + node[b + 12] * d.z,
        node[b + 13] * d.x + node[b + 14] * d.y + node[b + 15] * d.z);
      precise double r3 = r2 * r;
      precise double numerator =
        Dot(moment, d) + node[b + 7] + node[b + 11] + node[b + 15] - DivRN(3.0lf * Dot(d, td), r2);
      far = far + DivRN(numerator, FourPi * r3);
      precise double gap2 = gap * gap;
      sum = sum + DivRN(3.0lf * node[b + 16], FourPi * gap2 * gap2);
    }
    else if (l.z < 0)
    {
      Spent += l.y;
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
  bound = sum;
  precise double w = far + Winding();
  return w;
}

bool Decides(double w, double bound)
{
  precise double margin = abs(abs(w) - 0.5lf);
  precise double needed = bound + RoundingSlack;
  return margin > needed;
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
  precise dvec3 q = Origin + dvec3(Lo + ivec3(i, j, k)) * Spacing;
  Spent = 0;
  bool decided = false, inside = false;
  double w = 0.0lf, bound = 0.0lf;
  if (WantValues != 0)
  {
    w = Evaluate(q, max(Accuracy, ValueAccuracy), bound);
    decided = Decides(w, bound);
  }
  else
  {
    w = Evaluate(q, min(CoarseAccuracy, Accuracy), bound);
    decided = Decides(w, bound);
    if (!decided)
    {
      w = Evaluate(q, Accuracy, bound);
      decided = Decides(w, bound);
    }
  }
  // A walk cut short, or an exact sum (an iteration a triangle, and its entry) that the
  // budget cannot hold.
  if (Spent > IterationBudget || (!decided && TriangleCount >= IterationBudget - Spent))
  {
    answer[s - First] = 4u;
    return;
  }
  if (decided)
  {
    inside = abs(w) > 0.5lf;
  }
  else
  {
    Product = dvec2(1.0lf, 0.0lf);
    Turns = 0;
    for (int t = 0; t < TriangleCount; ++t)
    {
      AddTriangle(t, q);
    }
    // w = Turns + arg / 2 pi with arg in (-pi, pi]: |w| > 1/2 but for w = -1/2.
    inside = Turns != 0 && !(Turns == -1 && Product.y == 0.0lf && Product.x < 0.0lf);
    w = Winding();
  }
  answer[s - First] = (inside ? 1u : 0u) | (decided ? 0u : 2u);
  if (WantValues != 0)
  {
    value[s - First] = float(w);
  }
}
