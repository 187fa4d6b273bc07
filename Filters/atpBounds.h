// Bounding volumes of patches: minimum enclosing balls (CGAL's Min_sphere_of_spheres_d, the
// algorithm the paper cites) and cones of normals, and their conservative float storage.
#ifndef atpBounds_h
#define atpBounds_h

#include "atpPatchMesh.h"
#include "vtkATPFiltersModule.h"

#include <array>
#include <vector>

namespace atp
{

struct Sphere
{
  double Center[3] = { 0, 0, 0 };
  double Radius = -1; ///< negative: empty (encloses nothing)

  bool IsEmpty() const { return Radius < 0; }
};

/// The smallest ball holding every position (xyz triples). Empty for no points.
VTKATPFILTERS_EXPORT Sphere EnclosingSphere(const float* positions, std::size_t count);
/// The smallest ball holding every non-empty sphere given.
VTKATPFILTERS_EXPORT Sphere EnclosingSphere(const std::vector<Sphere>& spheres);

/// Stores a sphere as four floats that still enclose everything it enclosed: the radius grows by
/// the rounding of the center and is rounded up (never 0). An empty sphere stores as radius 0 at
/// the origin.
VTKATPFILTERS_EXPORT void StoreSphere(const Sphere& sphere, float out[4]);
/// StoreSphere's floats as a sphere: radius 0 loads as empty (not as the origin, which an
/// enclosing sphere would then have to hold).
VTKATPFILTERS_EXPORT Sphere LoadSphere(const float in[4]);

/// The directions of a set of normals: every one is within the half angle of the axis.
struct NormalCone
{
  double Axis[3] = { 0, 0, 1 };
  double Cos = 1;      ///< cosine of the half angle; -1: every direction
  bool Empty = true;   ///< holds no normal yet
};

/// Triangle t's edges from its first corner crossed, in double from the float positions: its
/// normal times twice its area; zero for a degenerate face.
VTKATPFILTERS_EXPORT std::array<double, 3> FaceCross(const PatchMesh& patch, std::size_t t);
/// The cone of the face normals of a patch (degenerate faces ignored).
VTKATPFILTERS_EXPORT NormalCone FaceNormalCone(const PatchMesh& patch);
/// A cone holding every non-empty cone given.
VTKATPFILTERS_EXPORT NormalCone EnclosingCone(const std::vector<NormalCone>& cones);
/// Stores axis and cosine as floats, the cosine rounded down (the cone only widens).
VTKATPFILTERS_EXPORT void StoreCone(const NormalCone& cone, float axis[3], float& cosine);
VTKATPFILTERS_EXPORT NormalCone LoadCone(const float axis[3], float cosine);

} // namespace atp

#endif
