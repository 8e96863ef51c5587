//VTK::System::Dec
// Slice volume mapper (Jimenez & Pueyo 2003, section 4): each slice is a slab
// of thickness Delta along the viewing ray, radiating its source radiance S
// with opacity 1 - exp(-sigma_t Delta), composited back to front with
// premultiplied "over" blending (ONE, ONE_MINUS_SRC_ALPHA).
in vec3 positionWC;
in vec3 texcoord;

// rgb: source radiance S = J / sigma_t; a: extinction sigma_t.
uniform sampler3D mediumTexture;
uniform vec3 eyeWC;
uniform vec3 viewDirectionWC;
uniform float sliceSpacing;
uniform int perspective;

//VTK::Output::Dec

void main()
{
  vec4 voxel = texture(mediumTexture, texcoord);
  // Distance between two slice planes along this fragment's viewing ray:
  // it grows as 1/cos(angle to the view direction) in perspective.
  float delta = sliceSpacing;
  if (perspective != 0)
  {
    vec3 ray = positionWC - eyeWC;
    delta = sliceSpacing * length(ray) / max(dot(ray, viewDirectionWC), 1e-6);
  }
  float alpha = 1.0 - exp(-voxel.a * delta);
  gl_FragData[0] = vec4(voxel.rgb * alpha, alpha);
}
