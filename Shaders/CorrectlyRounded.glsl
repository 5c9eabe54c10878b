// Correctly rounded double-precision square root and quotient, for the passes whose
// branches must match the CPU's IEEE 754 arithmetic (the medial pass, the side labels).
// GLSL asks no more of double sqrt and division than single precision (GLSL 4.50,
// section 4.7.1) and some drivers give about that; llvmpipe gives IEEE's. Each function
// refines the driver's value by two Newton steps, then picks among the value and its two
// neighbours the one nearest the exact result, by the sign of an exact residual: IEEE's
// result for positive normal operands (the residual of a value within an ulp is a
// double: Markstein, IA-64 and Elementary Functions, 2000). The residuals are exact by
// Dekker's product (only +, - and *, which both GLs round as IEEE does, where `precise`
// keeps them apart; a GL's fma() need not be fused: llvmpipe's is not). Others keep the
// driver's value.

// The driver's values that the functions refine (a test spoils them).
#ifndef DF_SEED_SQRT
#define DF_SEED_SQRT(x) sqrt(x)
#define DF_SEED_DIV(a, b) ((a) / (b))
#endif

// The next double above or below a positive finite v, through its bits.
double NextUp(double v)
{
  uvec2 bits = unpackDouble2x32(v);
  bits.x += 1u;
  bits.y += bits.x == 0u ? 1u : 0u;
  return packDouble2x32(bits);
}

double NextDown(double v)
{
  uvec2 bits = unpackDouble2x32(v);
  bits.y -= bits.x == 0u ? 1u : 0u;
  bits.x -= 1u;
  return packDouble2x32(bits);
}

// The rounding error of a * b: a * b = p + TwoProductError(a, b, p) exactly, for
// |a|, |b| well inside the range (Dekker 1971, Veltkamp's split into 26-bit halves).
double TwoProductError(double a, double b, double p)
{
  precise double ca = 134217729.0lf * a, cb = 134217729.0lf * b; // 2^27 + 1
  precise double ah = ca - (ca - a), bh = cb - (cb - b);
  precise double al = a - ah, bl = b - bh;
  precise double e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
  return e;
}

// x - a * b, exact when it is a double and a * b lies within a factor 2 of x.
double Residual(double x, double a, double b)
{
  precise double p = a * b;
  precise double near = x - p; // exact (Sterbenz)
  precise double r = near - TwoProductError(a, b, p);
  return r;
}

// sqrt(x) rounded to nearest. Near sqrt(x), s + u/2 (u = NextUp(s) - s) lies below
// sqrt(x) exactly when x - s^2 > s u: both sides are multiples of u^2, and the exact
// condition is x - s^2 > s u + u^2 / 4. A seed within an ulp (|x - s^2| < 2 s u, the
// smaller u of its two sides) needs no Newton step.
double SqrtRN(double x)
{
  precise double s = DF_SEED_SQRT(x);
  if (!(x > 1e-290lf && x < 1e290lf)) // zero, negative, not a number, tiny or huge
  {
    return s;
  }
  precise double down = NextDown(s);
  precise double r = Residual(x, s, s);
  if (!(abs(r) < 1.99lf * s * (s - down)))
  {
    // Two Newton steps, written out: no loop in a helper, so that a caller's count of
    // its loop iterations (Mesa's llvmpipe ends a shader's loops after 65,535) is whole.
    precise double correction = r * DF_SEED_DIV(0.5lf, s);
    s = s + correction;
    r = Residual(x, s, s);
    correction = r * DF_SEED_DIV(0.5lf, s);
    s = s + correction;
    r = Residual(x, s, s);
    down = NextDown(s);
  }
  precise double up = NextUp(s);
  if (r > s * (up - s))
  {
    return up;
  }
  if (Residual(x, down, down) <= down * (s - down))
  {
    return down;
  }
  return s;
}

// a / b rounded to nearest. For positive a, b and q near a / b: a / b lies above
// q + u/2 exactly when a - q b > b u / 2 (a quotient is never a midpoint). A seed within
// an ulp (|a - q b| < b u) needs no Newton step.
double DivRN(double a, double b)
{
  precise double q = DF_SEED_DIV(a, b);
  precise double x = abs(a), y = abs(b);
  if (!(x > 1e-290lf && y > 1e-290lf && x < 1e290lf && y < 1e290lf))
  {
    return q; // zero, not a number, infinite, tiny or huge operands
  }
  precise double t = abs(q);
  if (!(t > 1e-290lf && t < 1e290lf))
  {
    return q;
  }
  precise double down = NextDown(t);
  precise double r = Residual(x, t, y);
  if (!(abs(r) < 0.99lf * (t - down) * y))
  {
    precise double inverse = DF_SEED_DIV(1.0lf, y);
    // Two Newton steps, written out (as SqrtRN's).
    precise double correction = r * inverse;
    t = t + correction;
    r = Residual(x, t, y);
    correction = r * inverse;
    t = t + correction;
    r = Residual(x, t, y);
    down = NextDown(t);
  }
  precise double up = NextUp(t);
  if (r > 0.5lf * (up - t) * y)
  {
    t = up;
  }
  else if (Residual(x, down, y) < 0.5lf * (t - down) * y)
  {
    t = down;
  }
  return (a < 0.0lf) != (b < 0.0lf) ? -t : t;
}
