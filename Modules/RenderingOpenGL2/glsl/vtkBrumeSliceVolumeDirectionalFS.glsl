// Directional radiance (brume/SphericalHarmonics.h, in GLSL): the source
// radiance of a medium toward the eye from its voxel's spherical-harmonics
// coefficients, Henyey-Greenstein applied band by band, plus the lobe tail
// beyond the order (brume::EvaluateHgFromSh). Spliced into
// vtkBrumeSliceVolumeFS.glsl at //BRUME::Directional::Dec by the mapper,
// which fills in the tags below: the coefficient textures and SH_ORDER, the
// fetch of the coefficients into v[], and BRUME_SH_Y00 (brume::ShY00).
uniform float phaseG;
uniform vec3 eyeData;
uniform vec3 boundsLower;
uniform vec3 boundsExtent;
//BRUME::Directional::Uniforms
const float Inv4Pi = 0.0795774715;
float legendre(int l, float x)
{
  if (l == 0) return 1.0;
  if (l == 1) return x;
  if (l == 2) return 0.5 * (3.0 * x * x - 1.0);
  return 0.5 * x * (5.0 * x * x - 3.0);
}
vec3 directionalSource()
{
//BRUME::Directional::Fetch
  vec3 d = normalize(eyeData - (boundsLower + texcoord * boundsExtent));
  float y[16];
  y[0] = BRUME_SH_Y00;
  y[1] = 0.488602512 * d.y;
  y[2] = 0.488602512 * d.z;
  y[3] = 0.488602512 * d.x;
#if SH_ORDER >= 2
  y[4] = 1.092548431 * d.x * d.y;
  y[5] = 1.092548431 * d.y * d.z;
  y[6] = 0.315391565 * (3.0 * d.z * d.z - 1.0);
  y[7] = 1.092548431 * d.x * d.z;
  y[8] = 0.546274215 * (d.x * d.x - d.y * d.y);
#endif
#if SH_ORDER >= 3
  y[9] = 0.590043589 * d.y * (3.0 * d.x * d.x - d.y * d.y);
  y[10] = 2.890611442 * d.x * d.y * d.z;
  y[11] = 0.457045799 * d.y * (5.0 * d.z * d.z - 1.0);
  y[12] = 0.373176333 * d.z * (5.0 * d.z * d.z - 3.0);
  y[13] = 0.457045799 * d.x * (5.0 * d.z * d.z - 1.0);
  y[14] = 1.445305721 * d.z * (d.x * d.x - d.y * d.y);
  y[15] = 0.590043589 * d.x * (d.x * d.x - 3.0 * d.y * d.y);
#endif
  // The bands: Henyey-Greenstein scales band l by g^l.
  vec3 sum = vec3(0.0);
  float gl = 1.0;
  for (int l = 0; l <= SH_ORDER; ++l)
  {
    vec3 band = vec3(0.0);
    for (int k = l * l; k < (l + 1) * (l + 1); ++k)
    {
      band += vec3(v[3 * k], v[3 * k + 1], v[3 * k + 2]) * y[k];
    }
    sum += gl * band;
    gl *= phaseG;
  }
  // The bands beyond the order, from an isotropic part plus a lobe fitted
  // to the first two moments (brume::EvaluateHgFromSh).
  for (int c = 0; c < 3; ++c)
  {
    float total = v[c] / BRUME_SH_Y00;
    vec3 moment = vec3(v[9 + c], v[3 + c], v[6 + c]) / 0.488602512;
    float len = length(moment);
    if (!(total > 0.0) || !(len > 0.0))
    {
      continue;
    }
    vec3 axis = moment / len;
    float weight = total;
    float meanCosine = min(len / total, 0.999);
#if SH_ORDER >= 2
    float zonal = v[12 + c] * 1.092548431 * axis.x * axis.y
      + v[15 + c] * 1.092548431 * axis.y * axis.z
      + v[18 + c] * 0.315391565 * (3.0 * axis.z * axis.z - 1.0)
      + v[21 + c] * 1.092548431 * axis.x * axis.z
      + v[24 + c] * 0.546274215 * (axis.x * axis.x - axis.y * axis.y);
    float second = zonal * 4.0 * 3.14159265 / 5.0;
    if (!(second > 1e-4 * len))
    {
      continue;
    }
    meanCosine = min(second / len, 0.999);
    weight = min(len / meanCosine, total);
#endif
    float gg = phaseG * meanCosine;
    float mu = dot(axis, d);
    float truncated = 0.0;
    float power = 1.0;
    for (int l = 0; l <= SH_ORDER; ++l)
    {
      truncated += power * float(2 * l + 1) * Inv4Pi * legendre(l, mu);
      power *= gg;
    }
    float hg = Inv4Pi * (1.0 - gg * gg) / pow(max(1.0 + gg * gg - 2.0 * gg * mu, 1e-6), 1.5);
    sum[c] += weight * (hg - truncated);
  }
  return max(sum, vec3(0.0));
}
