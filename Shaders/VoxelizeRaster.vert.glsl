// One point per triangle; the geometry shader reads the triangle by gl_PrimitiveIDIn.
void main()
{
  gl_Position = vec4(0.0);
}
