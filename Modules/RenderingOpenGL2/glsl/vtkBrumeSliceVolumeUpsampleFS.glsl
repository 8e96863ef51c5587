//VTK::System::Dec
#extension GL_ARB_explicit_attrib_location : enable
#extension GL_ARB_blend_func_extended : enable
// Media at a reduced resolution, last pass: each full-resolution pixel takes
// the media's radiance L (rgb) and transmittance T (a) from the 2 x 2
// nearest coarse pixels: bilinearly among those whose depth agrees with its
// own (within 1 % of the distance; across an object's silhouette some do
// not), else from the one nearest in depth; and composites them over what
// is drawn as the slices do: C = L + T C_behind (dual-source blending).
in vec2 texCoord;
uniform sampler2D fullDepth;
uniform sampler2D coarseDepth;
uniform sampler2D coarseMedia;
uniform ivec2 fullSize;
uniform ivec2 coarseSize;
uniform float sampleDistance;
uniform vec2 clippingRange; // near, far (world units)
uniform int perspective;

layout(location = 0, index = 0) out vec4 fragColor;
layout(location = 0, index = 1) out vec4 fragTransmittance;

// Distance along the view of a window depth.
float viewDepth(float z)
{
  float n = clippingRange.x;
  float f = clippingRange.y;
  if (perspective != 0)
  {
    return 2.0 * n * f / ((f + n) - (2.0 * z - 1.0) * (f - n));
  }
  return n + z * (f - n);
}

void main()
{
  ivec2 p = min(ivec2(texCoord * vec2(fullSize)), fullSize - 1);
  float depth = viewDepth(texelFetch(fullDepth, p, 0).r);
  vec2 c = (vec2(p) + 0.5) / sampleDistance - 0.5;
  ivec2 base = ivec2(floor(c));
  vec2 f = c - floor(c);
  vec4 agreeing = vec4(0.0);
  float weight = 0.0;
  vec4 nearest = vec4(0.0, 0.0, 0.0, 1.0);
  float best = 3.0e38;
  for (int j = 0; j < 2; ++j)
  {
    for (int i = 0; i < 2; ++i)
    {
      ivec2 q = clamp(base + ivec2(i, j), ivec2(0), coarseSize - 1);
      vec4 media = texelFetch(coarseMedia, q, 0);
      float gap = abs(viewDepth(texelFetch(coarseDepth, q, 0).r) - depth);
      float w = (i == 0 ? 1.0 - f.x : f.x) * (j == 0 ? 1.0 - f.y : f.y) + 1e-4;
      if (gap <= 0.01 * depth)
      {
        agreeing += w * media;
        weight += w;
      }
      if (gap < best)
      {
        best = gap;
        nearest = media;
      }
    }
  }
  vec4 media = weight > 0.0 ? agreeing / weight : nearest;
  fragColor = vec4(media.rgb, 1.0 - media.a);
  fragTransmittance = vec4(media.a);
}
