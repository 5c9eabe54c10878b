// ArcTangent2 of Filters/Core/Common/ArcTangent.h, operation for operation (`precise`,
// IEEE quotients by DivRN), on the same constants as uniforms (SetArcTangentUniforms):
// the CPU's bits. Shaders that need it have the line //DF::ArcTangent2 after
// //DF::CorrectlyRounded.
// The tables as the bits of their doubles (an array of doubles may be kept in single
// precision: see MedialAxis.comp.glsl).
uniform uvec2 AtanAtPoint[9];     // atan(k / 8)
uniform uvec2 AtanCoefficient[8]; // (-1)^n / (2n + 1)
uniform double AtanPi, AtanHalfPi;

double ArcTangent2(double y, double x)
{
  if (y == 0.0lf)
  {
    return x >= 0.0lf ? 0.0lf : AtanPi;
  }
  if (x == 0.0lf)
  {
    return y > 0.0lf ? AtanHalfPi : -AtanHalfPi;
  }
  precise double ax = abs(x), ay = abs(y);
  bool steep = ay > ax;
  precise double t = steep ? DivRN(ax, ay) : DivRN(ay, ax);
  if (!(t <= 1.0lf))
  {
    return t;
  }
  int k = int(t * 8.0lf + 0.5lf);
  precise double c = double(k) * 0.125lf;
  precise double z = DivRN(t - c, 1.0lf + t * c);
  precise double z2 = z * z;
  precise double series = packDouble2x32(AtanCoefficient[7]);
  // Horner's rule, written out (no loop in a helper: CorrectlyRounded.glsl's SqrtRN).
  series = series * z2 + packDouble2x32(AtanCoefficient[6]);
  series = series * z2 + packDouble2x32(AtanCoefficient[5]);
  series = series * z2 + packDouble2x32(AtanCoefficient[4]);
  series = series * z2 + packDouble2x32(AtanCoefficient[3]);
  series = series * z2 + packDouble2x32(AtanCoefficient[2]);
  series = series * z2 + packDouble2x32(AtanCoefficient[1]);
  series = series * z2 + packDouble2x32(AtanCoefficient[0]);
  precise double angle = packDouble2x32(AtanAtPoint[k]) + z * series;
  if (steep)
  {
    angle = AtanHalfPi - angle;
  }
  if (x < 0.0lf)
  {
    angle = AtanPi - angle;
  }
  return y < 0.0lf ? -angle : angle;
}
