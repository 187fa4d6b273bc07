#include "atpPatchShaders.h"

#include <cmath>
#include <string>

namespace atp
{

std::string PatchVertexShader(bool colors)
{
  std::string s = "//VTK::System::Dec\n"
                  "in vec4 vertexMC;\n"
                  "in vec4 normalMC;\n"
                  "uniform mat4 MCDCMatrix;\n"
                  "uniform mat4 MCVCMatrix;\n"
                  "uniform mat3 normalMatrix;\n"
                  "out vec4 vertexVCVSOutput;\n"
                  "out vec3 normalVCVSOutput;\n";
  if (colors)
  {
    s += "in vec4 colorMC;\nout vec4 colorVSOutput;\n";
  }
  s += "void main()\n{\n"
       "  vertexVCVSOutput = MCVCMatrix * vertexMC;\n"
       "  normalVCVSOutput = normalMatrix * normalMC.xyz;\n"
       "  gl_Position = MCDCMatrix * vertexMC;\n";
  if (colors)
  {
    s += "  colorVSOutput = colorMC;\n";
  }
  return s + "}\n";
}

std::string PatchFragmentShader(
  bool colors, int lightingComplexity, int lightCount, const std::string& lightUniforms)
{
  std::string s = "//VTK::System::Dec\n"
                  "//VTK::Output::Dec\n"
                  "in vec4 vertexVCVSOutput;\n"
                  "in vec3 normalVCVSOutput;\n"
                  "uniform vec3 ambientColorUniform;\n"
                  "uniform vec3 diffuseColorUniform;\n"
                  "uniform vec3 specularColorUniform;\n"
                  "uniform float ambientIntensity;\n"
                  "uniform float diffuseIntensity;\n"
                  "uniform float specularIntensity;\n"
                  "uniform float specularPower;\n"
                  "uniform float opacityUniform;\n"
                  "uniform int colorSource; // 0: the property, 1: vertex colors, 2: patchColor\n"
                  "uniform vec3 patchColor;\n";
  if (colors)
  {
    s += "in vec4 colorVSOutput;\n";
  }
  s += lightUniforms + "\n";
  s += "void main()\n{\n"
       "  vec3 normalVC = normalize(normalVCVSOutput);\n"
       "  if (!gl_FrontFacing) normalVC = -normalVC; // two-sided lighting\n"
       "  vec3 base = diffuseColorUniform;\n"
       "  vec3 ambientBase = ambientColorUniform;\n";
  if (colors)
  {
    s += "  if (colorSource == 1) { base = colorVSOutput.rgb; ambientBase = base; }\n";
  }
  s += "  if (colorSource == 2) { base = patchColor; ambientBase = base; }\n"
       "  vec3 ambientColor = ambientIntensity * ambientBase;\n"
       "  vec3 diffuseColor = diffuseIntensity * base;\n"
       "  vec3 specularColor = specularIntensity * specularColorUniform;\n"
       "  vec3 diffuse = vec3(0.0);\n"
       "  vec3 specular = vec3(0.0);\n"
       "  float df;\n"
       "  float sf;\n";
  if (lightingComplexity == 0)
  {
    s += "  diffuse = vec3(1.0);\n";
  }
  else if (lightingComplexity == 1)
  {
    s += "  df = max(0.0, normalVC.z);\n"
         "  sf = pow(df, specularPower);\n"
         "  diffuse = df * lightColor0;\n"
         "  specular = sf * lightColor0;\n";
  }
  else
  {
    s += "  vec3 viewDirectionVC = normalize(-vertexVCVSOutput.xyz);\n"
         "  vec3 toLight;\n"
         "  float attenuation;\n";
    for (int i = 0; i < lightCount; ++i)
    {
      const std::string n = std::to_string(i);
      s += "  toLight = -lightDirectionVC" + n + ";\n  attenuation = 1.0;\n";
      if (lightingComplexity >= 3)
      {
        s += "  if (lightPositional" + n + " == 1)\n  {\n"
             "    vec3 fromLight = vertexVCVSOutput.xyz - lightPositionVC" + n + ";\n"
             "    float d = length(fromLight);\n"
             "    fromLight = fromLight / d;\n"
             "    toLight = -fromLight;\n"
             "    attenuation = 1.0 / (lightAttenuation" + n + ".x + lightAttenuation" + n +
          ".y * d + lightAttenuation" + n + ".z * d * d);\n"
             "    if (lightConeAngle" + n + " <= 90.0)\n    {\n"
             "      float coneDot = dot(fromLight, lightDirectionVC" + n + ");\n"
             "      attenuation = coneDot >= cos(radians(lightConeAngle" + n +
          ")) ? attenuation * pow(coneDot, lightExponent" + n + ") : 0.0;\n"
             "    }\n  }\n";
      }
      s += "  df = max(0.0, attenuation * dot(normalVC, toLight));\n"
           "  diffuse += df * lightColor" + n + ";\n"
           "  sf = sign(df) * attenuation * pow(max(0.0, dot(reflect(-toLight, normalVC), "
           "viewDirectionVC)), specularPower);\n"
           "  specular += sf * lightColor" + n + ";\n";
    }
  }
  s += "  gl_FragData[0] = vec4(ambientColor + diffuse * diffuseColor + specular * specularColor, "
       "opacityUniform);\n}\n";
  return s;
}

void PatchColor(unsigned node, float rgb[3])
{
  // Golden-ratio hues keep neighbours (close node indices: close Morton codes) apart.
  const double hue = std::fmod(node * 0.618033988749895, 1.0) * 6;
  const int sector = int(hue);
  const double f = hue - sector;
  const double v = 0.95, s = 0.65;
  const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  const double table[6][3] = { { v, t, p }, { q, v, p }, { p, v, t }, { p, q, v }, { t, p, v },
    { v, p, q } };
  for (int a = 0; a < 3; ++a)
  {
    rgb[a] = float(table[sector % 6][a]);
  }
}

} // namespace atp
