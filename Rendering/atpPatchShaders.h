// GLSL for drawing patches laid out as atpRenderPatch.h says, lit like VTK's own polygonal
// mapper: the renderer's lights (headlight, directional, positional and spot lights, through
// vtkOpenGLRenderer's lighting uniforms), the actor's ambient, diffuse and specular terms,
// two-sided lighting, and vertex colors or one color per patch in place of the diffuse color.
#ifndef atpPatchShaders_h
#define atpPatchShaders_h

#include <string>

namespace atp
{

/// `colors`: the vertices carry RGBA.
std::string PatchVertexShader(bool colors);

/// `lightingComplexity` and `lightCount` as vtkOpenGLRenderer reports them (0: unlit,
/// 1: headlight, 2: directional lights, 3: positional lights), `lightUniforms` its
/// GetLightingUniforms() declarations.
std::string PatchFragmentShader(
  bool colors, int lightingComplexity, int lightCount, const std::string& lightUniforms);

/// A distinct, stable color per node for the patch-coloring view (RGB in [0, 1]).
void PatchColor(unsigned node, float rgb[3]);

} // namespace atp

#endif
