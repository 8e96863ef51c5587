//VTK::System::Dec
// Media at a reduced resolution (vtkBrumeSliceVolumeMapper::
// ImageSampleDistance), first pass: each coarse pixel's depth is the
// farthest of the full-resolution depths it covers, so that its slices are
// drawn for every surface behind it; the upsampling picks, per full pixel,
// the coarse pixels at its own depth. The colour starts as no radiance and
// full transmittance.
in vec2 texCoord;
uniform sampler2D fullDepth;
uniform ivec2 fullSize;
uniform ivec2 coarseSize;
uniform float sampleDistance;
out vec4 fragOutput0;

void main()
{
  vec2 lower = floor(texCoord * vec2(coarseSize)) * sampleDistance;
  ivec2 first = ivec2(floor(lower));
  ivec2 last = min(ivec2(ceil(lower + sampleDistance)) - 1, fullSize - 1);
  float z = 0.0;
  for (int y = first.y; y <= last.y; ++y)
  {
    for (int x = first.x; x <= last.x; ++x)
    {
      z = max(z, texelFetch(fullDepth, ivec2(x, y), 0).r);
    }
  }
  gl_FragDepth = z;
  fragOutput0 = vec4(0.0, 0.0, 0.0, 1.0);
}
