//VTK::System::Dec
#extension GL_ARB_explicit_attrib_location : enable
#extension GL_ARB_blend_func_extended : enable
// Slice volume mapper (Jimenez & Pueyo 2003, section 4): each slice is a slab
// of thickness Delta along the viewing ray that radiates its source radiance
// S and lets T = exp(-sigma_t Delta) of the light behind through, per colour
// channel. Dual-source blending (ONE, SRC1_COLOR) composites back to front:
// C = S (1 - T) + T C_behind.
//
// The mapper defines, per kind of volume (vtkBrumeSliceVolumeShader):
// BRUME_EXTINCTION 0 (a texture at the source's resolution or of its own),
// 1 (a sparse grid's atlas of bricks) or 2 (constant: a homogeneous medium);
// BRUME_SOURCE_IS_RADIANCE 1 where sourceTexture holds S, not J;
// BRUME_CLASSIFIED 1 where the bricks hold scalars a transfer function
// classifies, and BRUME_ALBEDO 1 where its table gives an albedo too;
// BRUME_SLABS 1 where slabs take several extinction samples, and with it
// BRUME_BENDS 1 where classified bricks the function bends within take
// samples four a fine cell (vtkBrumeSliceVolumeMapper::SetBendSampling). Each kind
// is compiled apart: a software rasterizer runs both sides of a branch on a
// uniform, texture fetches included.
//BRUME::Slice::Defines
in vec3 positionWC;
in vec3 texcoord;

uniform sampler3D sourceTexture;     // J = S sigma_t (W m^-3 sr^-1), or S
uniform sampler3D extinctionTexture; // sigma_t (m^-1), or a sparse grid's atlas of bricks
uniform vec3 eyeWC;
uniform vec3 viewDirectionWC;
uniform float sliceSpacing;
uniform int perspective;
uniform vec3 extinctionScale;        // texcoord to the extinction grid's own box
uniform vec3 extinctionOffset;
uniform vec3 extinctionFactor;       // forward peak drawn as transport: sigma_t's factor
uniform float radianceScale;         // an exposure: the emitted radiance only, not T
#if BRUME_SLABS
// The slab's extinction (and albedo) is the mean of slabSamples samples
// along this fragment's ray, evenly across the slab's thickness: an
// extinction grid of its own finer than the slices' spacing (one voxel
// sheets) is then integrated across the slab, not sampled at its slice
// (where a thin structure falls between slices or is drawn a slab thick).
// textureFromWorld* are the rows of the world-to-texture-coordinate map.
uniform int slabSamples;
uniform vec3 textureFromWorldX;
uniform vec3 textureFromWorldY;
uniform vec3 textureFromWorldZ;
#endif
#if BRUME_EXTINCTION == 1
// A sparse extinction grid (vtkBrumeSliceVolumeMapper::SetExtinctionData):
// bricks of 8^3 cells, 7 apart, so that the cells a point interpolates lie
// in one brick. The table gives a brick's value (x, y < 0), or its slot in
// the atlas (x + 2048 y and z, in slots) and the grid's value of a texel t
// there, z t + w (a 16-bit normalized atlas holds integers less their
// least, or each slot's values over its own interval).
uniform sampler3D brickTable;
uniform vec3 gridCells;
uniform vec3 brickCount;
uniform vec3 atlasSize;
uniform vec3 brickScale;             // sigma_t per unit of the grid's values
#endif
#if BRUME_EXTINCTION == 1 && BRUME_CLASSIFIED
// The bricks hold scalars: a transfer function's extinction, sampled evenly
// over transferRange in one row, classifies them after interpolation, as the
// light tracer does (vtkBrumeSliceVolumeMapper::SetExtinctionData).
// With BRUME_ALBEDO the row's green, blue and alpha hold the albedo there.
uniform sampler2D transferTexture;
uniform vec2 transferRange;
uniform float transferSamples;
vec4 classify(float s)
{
  float x = clamp((s - transferRange.x) / (transferRange.y - transferRange.x), 0.0, 1.0);
  return texture(transferTexture, vec2((x * (transferSamples - 1.0) + 0.5) / transferSamples, 0.5));
}
#else
vec4 classify(float s)
{
  return vec4(s, 1.0, 1.0, 1.0);
}
#endif
#if BRUME_ALBEDO
// The source texture holds X, the radiance of an albedo of 1: drawn as
// sigma_t a X, with the albedo's share of the phase function's forward
// peak (drawn as transport) taken from the extinction.
uniform float forwardFraction;
#endif
#if BRUME_EXTINCTION == 2
uniform vec3 constantExtinction;     // sigma_t of a homogeneous medium
#endif
#if BRUME_BENDS
uniform int bendParts;               // parts of a sample there: four samples a fine cell
// Per brick, a bit for each of its 4^3 parts of 2^3 cells (16 in each
// float) whose scalars span a point of the transfer function steeply.
uniform sampler3D bendMask;
// Whether the part of the brick holding t (as extinctionAt finds it) bends:
// one sample a fine cell does not integrate the classified extinction of a
// structure a cell thin there.
bool bendsAt(vec3 t)
{
  vec3 u = clamp(t * gridCells - 0.5, vec3(0.0), gridCells - 1.0);
  vec3 brick = min(floor(u / 7.0), brickCount - 1.0);
  ivec3 part = ivec3(min(floor((u - 7.0 * brick) * 0.5), vec3(3.0)));
  int bit = part.x + 4 * part.y + 16 * part.z;
  int word = int(texelFetch(bendMask, ivec3(brick), 0)[bit / 16]);
  return ((word >> (bit % 16)) & 1) != 0;
}
#endif

// sigma_t at t in [0, 1]^3 over the extinction grid's box, and the albedo
// there (1 unless BRUME_ALBEDO).
vec3 extinctionAt(vec3 t, out vec3 albedo)
{
  albedo = vec3(1.0);
#if BRUME_EXTINCTION == 0
  return texture(extinctionTexture, t).rgb;
#elif BRUME_EXTINCTION == 1
  // u: in cells, their centres at whole numbers, clamped as at the edges.
  vec3 u = clamp(t * gridCells - 0.5, vec3(0.0), gridCells - 1.0);
  vec3 brick = min(floor(u / 7.0), brickCount - 1.0);
  vec4 entry = texelFetch(brickTable, ivec3(brick), 0);
  vec4 classified;
  if (entry.y < 0.0)
  {
    classified = classify(entry.x);
  }
  else
  {
    float row = floor(entry.x / 2048.0);
    vec3 slot = 8.0 * vec3(entry.x - 2048.0 * row, row, entry.y);
    vec3 local = min(u - 7.0 * brick, vec3(7.0));
    float t = texture(extinctionTexture, (slot + local + 0.5) / atlasSize).r;
    classified = classify(entry.z * t + entry.w);
  }
#if BRUME_ALBEDO
  albedo = classified.gba;
#endif
  return classified.r * brickScale;
#else
  return constantExtinction;
#endif
}

//BRUME::Directional::Dec

layout(location = 0, index = 0) out vec4 fragColor;
layout(location = 0, index = 1) out vec4 fragTransmittance;

void main()
{
  vec3 emission = texture(sourceTexture, texcoord).rgb;
  //BRUME::Directional::Impl
  // Distance between two slice planes along this fragment's viewing ray:
  // it grows as 1/cos(angle to the view direction) in perspective.
  float delta = sliceSpacing;
  if (perspective != 0)
  {
    vec3 ray = positionWC - eyeWC;
    delta = sliceSpacing * length(ray) / max(dot(ray, viewDirectionWC), 1e-6);
  }
#if BRUME_SLABS
  // The slab's samples, in texture coordinates, evenly across it along the
  // ray; samples beyond the medium's box hold none of it.
  vec3 ray = perspective != 0 ? normalize(positionWC - eyeWC) : viewDirectionWC;
  vec3 across = delta * vec3(dot(textureFromWorldX, ray), dot(textureFromWorldY, ray),
    dot(textureFromWorldZ, ray));
  int samples = slabSamples;
#else
  const int samples = 1; // at the slice
#endif
  vec3 sigmaT = vec3(0.0);
#if BRUME_ALBEDO
  vec3 scattering = vec3(0.0);
#endif
#if BRUME_BENDS
  // Where the function bends, a slab takes bendParts times as many samples
  // (four a fine cell), evenly across it, each counting 1 / bendParts: a
  // slab any of whose samples' shares (at most a fine cell each) has an end
  // in a bending part. One loop over them all: under llvmpipe a loop over
  // each sample's parts within the loop over the samples cost the shells'
  // frame 0.8 s more.
  vec3 share = across / float(samples);
  bool bends = false;
  for (int k = 0; k <= samples; ++k)
  {
    bends = bends || bendsAt((texcoord + share * (float(k) - 0.5 * float(samples))) *
      extinctionScale + extinctionOffset);
  }
  int parts = bends ? bendParts : 1;
#else
  const int parts = 1;
#endif
  int taken = samples * parts;
  for (int q = 0; q < taken; ++q)
  {
    vec3 t = texcoord;
#if BRUME_SLABS
    t += across * ((float(q) + 0.5) / float(taken) - 0.5);
    if (taken > 1 && (any(lessThan(t, vec3(0.0))) || any(greaterThan(t, vec3(1.0)))))
    {
      continue;
    }
#endif
    vec3 albedo;
    vec3 sigma = extinctionAt(t * extinctionScale + extinctionOffset, albedo) / float(parts);
#if BRUME_ALBEDO
    // J = sigma_t a X; the peak's share a Forward of sigma_t is transport.
    scattering += sigma * albedo;
    sigmaT += sigma * (vec3(1.0) - albedo * forwardFraction);
#else
    sigmaT += sigma;
#endif
  }
  sigmaT /= float(samples);
#if BRUME_ALBEDO
  emission *= scattering / float(samples);
#else
  sigmaT *= extinctionFactor;
#endif
#if BRUME_ALBEDO
#elif BRUME_SOURCE_IS_RADIANCE
  // Extinction at its own resolution: J = S sigma_t with the fine sigma_t.
  emission *= sigmaT;
#else
  // J = S sigma_t was filtered with sigma_t unreduced.
  emission *= extinctionFactor;
#endif
  vec3 transmittance = exp(-sigmaT * delta);
  float meanTransmittance = dot(transmittance, vec3(1.0 / 3.0));
  // S (1 - T) with S = J / sigma_t; J Delta where sigma_t Delta is tiny.
  vec3 thick = emission * (vec3(1.0) - transmittance) / max(sigmaT, vec3(1e-30));
  vec3 thin = emission * delta;
  vec3 radiance = mix(thin, thick, step(vec3(1e-4), sigmaT * delta));
  fragColor = vec4(radiance * radianceScale, 1.0 - meanTransmittance);
  fragTransmittance = vec4(transmittance, meanTransmittance);
}
