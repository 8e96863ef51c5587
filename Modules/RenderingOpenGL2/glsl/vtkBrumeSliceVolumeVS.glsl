//VTK::System::Dec
// Slice volume mapper: slices arrive in world coordinates.
in vec3 vertexWC;
in vec3 textureCoordinate;

uniform mat4 WCDCMatrix;

out vec3 positionWC;
out vec3 texcoord;

void main()
{
  positionWC = vertexWC;
  texcoord = textureCoordinate;
  gl_Position = WCDCMatrix * vec4(vertexWC, 1.0);
}
