#include "ConformityCheck.h"

#include <tetgen.h>

#include <algorithm>
#include <map>
#include <sstream>

namespace atp
{
namespace testing
{
namespace
{
using Face = std::array<LatticePoint, 3>;

Face SortedFace(const LatticePoint& a, const LatticePoint& b, const LatticePoint& c)
{
  Face f{ { a, b, c } };
  std::sort(f.begin(), f.end());
  return f;
}

bool OnCubeBoundary(const Face& f)
{
  for (int axis = 0; axis < 3; ++axis)
  {
    for (const std::int32_t side : { 0, LatticeSize })
    {
      if (f[0][axis] == side && f[1][axis] == side && f[2][axis] == side)
      {
        return true;
      }
    }
  }
  return false;
}

__int128 SixTimesVolume(const Tetra& t)
{
  __int128 u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k)
  {
    u[k] = t.V[1][k] - t.V[0][k];
    v[k] = t.V[2][k] - t.V[0][k];
    w[k] = t.V[3][k] - t.V[0][k];
  }
  const __int128 d = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
    u[2] * (v[0] * w[1] - v[1] * w[0]);
  return d < 0 ? -d : d;
}

std::vector<Face> FacesOf(const Tetra& t)
{
  const auto& v = t.V;
  return { SortedFace(v[1], v[2], v[3]), SortedFace(v[0], v[2], v[3]),
    SortedFace(v[0], v[1], v[3]), SortedFace(v[0], v[1], v[2]) };
}

std::string Describe(const Face& f)
{
  std::ostringstream s;
  for (const auto& p : f)
  {
    s << "(" << p[0] << "," << p[1] << "," << p[2] << ")";
  }
  return s.str();
}
} // namespace

std::string FaceMatchingProblem(const std::vector<Tetra>& tets)
{
  std::map<Face, int> uses;
  __int128 volume = 0;
  for (const Tetra& t : tets)
  {
    volume += SixTimesVolume(t);
    for (const Face& f : FacesOf(t))
    {
      ++uses[f];
    }
  }
  const __int128 cube = __int128(LatticeSize) * LatticeSize * LatticeSize * 6;
  if (volume != cube)
  {
    return "volumes do not add up to the cube";
  }
  for (const auto& [face, count] : uses)
  {
    const int expected = OnCubeBoundary(face) ? 1 : 2;
    if (count != expected)
    {
      std::ostringstream s;
      s << "face " << Describe(face) << " is used " << count << " times, expected " << expected;
      return s.str();
    }
  }
  return {};
}

std::string TetGenProblem(const std::vector<Tetra>& tets)
{
  std::map<LatticePoint, int> pointIndex;
  for (const Tetra& t : tets)
  {
    for (const auto& v : t.V)
    {
      pointIndex.emplace(v, 0);
    }
  }
  tetgenio in;
  in.numberofpoints = int(pointIndex.size());
  in.pointlist = new REAL[3 * pointIndex.size()];
  int next = 0;
  for (auto& [p, index] : pointIndex)
  {
    index = next;
    for (int k = 0; k < 3; ++k)
    {
      in.pointlist[3 * next + k] = REAL(p[k]);
    }
    ++next;
  }
  in.numberofcorners = 4;
  in.numberoftetrahedra = int(tets.size());
  in.tetrahedronlist = new int[4 * tets.size()];
  for (std::size_t i = 0; i < tets.size(); ++i)
  {
    for (int c = 0; c < 4; ++c)
    {
      in.tetrahedronlist[4 * i + std::size_t(c)] = pointIndex[tets[i].V[std::size_t(c)]];
    }
  }

  // Reconstruct the given tetrahedra (-r), report neighbours (-n), quietly (-Q).
  tetgenio out;
  try
  {
    tetgenbehavior behavior;
    char switches[] = "rnQ";
    if (!behavior.parse_commandline(switches))
    {
      return "TetGen rejected its switches";
    }
    tetrahedralize(&behavior, &in, &out);
  }
  catch (...)
  {
    return "TetGen failed to reconstruct the mesh";
  }
  if (out.numberoftetrahedra != int(tets.size()))
  {
    return "TetGen reconstructed a different number of tetrahedra";
  }
  for (int i = 0; i < out.numberoftetrahedra; ++i)
  {
    for (int f = 0; f < 4; ++f)
    {
      if (out.neighborlist[4 * i + f] >= 0)
      {
        continue;
      }
      // Hull face f of tetrahedron i is opposite its corner f.
      LatticePoint corners[3];
      for (int c = 0, n = 0; c < 4; ++c)
      {
        if (c == f)
        {
          continue;
        }
        const REAL* p = &out.pointlist[3 * out.tetrahedronlist[4 * i + c]];
        corners[n++] = { std::int32_t(p[0]), std::int32_t(p[1]), std::int32_t(p[2]) };
      }
      const Face face = SortedFace(corners[0], corners[1], corners[2]);
      if (!OnCubeBoundary(face))
      {
        return "TetGen finds an unmatched face inside the cube: " + Describe(face);
      }
    }
  }
  return {};
}

}
}
