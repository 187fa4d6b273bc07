// A stream of triangles (a "triangle soup") read from a mesh file, never holding the whole mesh.
// Plain C++: no VTK types. Every reader of an input format implements this interface.
#ifndef atpTriangleSource_h
#define atpTriangleSource_h

#include "atpPatchMesh.h" // ManyInputUses
#include "vtkATPIOModule.h" // export macro

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

namespace atp
{
class BoundaryEdgeCheck;

/// Axis-aligned box, in input coordinates. Empty until the first point is added.
struct VTKATPIO_EXPORT Box
{
  std::array<double, 3> Min{ { 1e300, 1e300, 1e300 } };
  std::array<double, 3> Max{ { -1e300, -1e300, -1e300 } };

  bool IsEmpty() const { return Min[0] > Max[0]; }
  bool operator!=(const Box& other) const { return Min != other.Min || Max != other.Max; }
  void Add(const float p[3])
  {
    for (int a = 0; a < 3; ++a)
    {
      Min[a] = p[a] < Min[a] ? p[a] : Min[a];
      Max[a] = p[a] > Max[a] ? p[a] : Max[a];
    }
  }
};

/// One input triangle with its corner positions, normals and colors copied (soup form), 64 bytes.
struct SoupTriangle
{
  /// Corner positions, on the model's quantization grid (QuantizationGrid::ForBounds of the
  /// source's Bounds()): the positions the model stores.
  float V[3][3];
  /// Corner normals (EncodeNormal of atpNormalEncoding.h): the vertex normals of the whole input
  /// mesh, so a vertex shared by triangles in different buckets has one normal everywhere.
  std::int16_t Normals[3][2];
  /// Bit i set: the edge from corner i to corner (i+1)%3 is a boundary edge of the input mesh
  /// (used by exactly one triangle). Simplification must know these (paper, section 5.2).
  /// Bit 3 + i set: that edge is used by three or more triangles (BoundaryEdgeCheck): its ends
  /// never move, since a patch holding two of them would take it for an inner edge. Bit 6, from
  /// reading until the check is applied: an edge of the triangle was counted by the check.
  std::uint8_t BoundaryEdges;
  /// Per corner: how many of the input's triangles use its vertex, up to ManyInputUses (that
  /// many or more); 0 where not counted. See PatchMesh::InputUses.
  std::uint8_t InputUses[3];
  /// Corner colors, RGBA; opaque white when the input has none (the bytes stay deterministic).
  std::uint8_t Colors[3][4];
};
static_assert(sizeof(SoupTriangle) == 64, "SoupTriangle is an on-disk record: keep it packed");

/// A problem with an input file. The message names the file and says what is wrong.
class VTKATPIO_EXPORT InputError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// What reading the input found, for the user's summary.
struct InputStats
{
  std::uint64_t VerticesRead = 0;
  std::uint64_t FacesRead = 0;           ///< faces in the file (polygons count once)
  std::uint64_t TrianglesEmitted = 0;    ///< after fan triangulation, minus dropped ones
  std::uint64_t DegenerateDropped = 0;   ///< repeated corner or zero area: dropped, not fatal
  std::uint64_t BoundaryEdges = 0;       ///< edges used by exactly one triangle, by position
  /// Edges open by vertex index that more triangles use by position (unwelded vertices, a
  /// repeated triangle, several sheets on an edge): not boundary edges (BoundaryEdgeCheck).
  std::uint64_t SharedOpenEdges = 0;
  /// Too many edges open by vertex index to check by position: none is a boundary edge.
  bool BoundaryUnchecked = false;
  bool HasColors = false;                ///< the input has per-vertex colors
};

class VTKATPIO_EXPORT TriangleSource
{
public:
  virtual ~TriangleSource();

  /// Bounds of the vertices the triangles use (a point no face uses costs the model no
  /// precision); known as soon as the source is open (the partitioner needs the box before
  /// the first triangle).
  virtual Box Bounds() const = 0;

  /// Number of triangles expected, for progress reporting (an estimate: polygons and dropped
  /// degenerate triangles make the real count differ). 0 when unknown.
  virtual std::uint64_t ExpectedTriangles() const = 0;

  /// Fills out[0..max) with the next triangles and returns how many; 0 means the end.
  /// Throws InputError on malformed or truncated input.
  virtual std::size_t Read(SoupTriangle* out, std::size_t max) = 0;

  virtual const InputStats& Stats() const = 0;

  /// Whether the corners carry the input's colors (known as soon as the source is open);
  /// otherwise they are opaque white.
  virtual bool HasColors() const { return false; }

  /// Once every triangle is read: the check of the BoundaryEdges bits by position that the
  /// triangles read need before simplification (Partitioner::ReadLeaf applies it); null when
  /// the bits need none.
  virtual std::shared_ptr<const BoundaryEdgeCheck> BoundaryCheck() const { return nullptr; }
};

/// A model keeps positions, bounds and errors as 32-bit floats: an input reaching near FLT_MAX
/// (3.4e38) would give bounds and errors no reader accepts. Inputs lie within +-MaxCoordinate,
/// far below it and far beyond any real data.
constexpr double MaxCoordinate = 1e36;
/// Throws InputError naming the input when the box reaches beyond +-MaxCoordinate.
VTKATPIO_EXPORT void CheckCoordinateRange(const Box& bounds, const std::string& inputName);

/// Opens PLY (ASCII or binary), OBJ, STL (ASCII or binary) or VTP by file extension.
/// Large inputs (PLY, OBJ, STL) are streamed; VTP is read in memory by VTK.
/// `scratchDirectory` receives temporary arrays (removed when the source is destroyed).
/// Throws InputError naming the file and the problem.
VTKATPIO_EXPORT std::unique_ptr<TriangleSource> OpenTriangleSource(
  const std::string& path, const std::string& scratchDirectory);

} // namespace atp

#endif
