// The one path from a format reader's polygons to soup triangles, shared by every format:
// triangulation (TriangleCursor), dropping degenerate triangles, moving corners to the model's
// grid, marking boundary edges with a BoundarySketch (checked by grid position with a
// BoundaryEdgeCheck) and giving corners their vertex normals. Opening makes a first pass over
// the faces (sketch, normal sums, counts, errors); Read makes the second.
#ifndef atpMeshTriangleSource_h
#define atpMeshTriangleSource_h

#include "atpBoundaryEdgeCheck.h"
#include "atpBoundarySketch.h"
#include "atpPolygonMesh.h"
#include "atpQuantizationGrid.h"
#include "atpTriangleCursor.h"
#include "atpTriangleSource.h"

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace atp
{

class MeshTriangleSource final : public TriangleSource
{
public:
  /// Checks the vertices, makes the first pass over the faces and bounds the vertices they use.
  /// Throws InputError naming `path` (bad input, or no triangle left).
  MeshTriangleSource(std::unique_ptr<PolygonMesh> mesh, const std::string& path,
    const std::string& scratchDirectory);

  Box Bounds() const override { return this->VertexBounds; }
  std::uint64_t ExpectedTriangles() const override { return this->KeptTriangles; }
  std::size_t Read(SoupTriangle* out, std::size_t max) override;
  const InputStats& Stats() const override { return this->Statistics; }
  bool HasColors() const override { return this->Statistics.HasColors; }
  std::shared_ptr<const BoundaryEdgeCheck> BoundaryCheck() const override { return this->Check; }

private:
  void CheckVerticesAndBound();
  /// Lets the pages of vertices [first, first + count) that a scan has read leave resident
  /// memory, when the vertex array is a file's mapping.
  void ReleaseVertexPages(std::uint64_t first, std::uint64_t count) const;
  /// The first pass: boundary sketch, area-weighted vertex normal sums, the triangles per
  /// vertex and the box of the vertices the faces use.
  void FirstPass();
  /// Gives the check the positions of the vertices on edges the sketch found open, and joins
  /// those that share a grid position (JoinVerticesAtOnePosition).
  void CollectOpenEdgeEnds();
  /// Vertices on edges open by index that share a grid position (a seam of copied vertices, an
  /// unwelded mesh; `atPosition` holds them with their grid points) are one vertex of the model,
  /// which the leaves weld: each gets the normal sum and triangle count of them all, and the
  /// color of the first, so the model has one normal and one color there in every patch, the
  /// normal of the whole fan. Only with at most MaxJoinedVertices vertices on open edges:
  /// beyond, each keeps its own.
  void JoinVerticesAtOnePosition(std::vector<std::pair<std::array<std::uint32_t, 3>, std::uint32_t>>& atPosition);
  static constexpr std::size_t MaxJoinedVertices = std::size_t(1) << 22;
  /// (vertex, the joined vertex whose color it takes), by vertex.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> ColorFrom;
  /// Counts the triangle's edges between two such positions in the check, and marks the
  /// triangle (BoundaryEdgeCheck::CountedBit) when it has one.
  void CountEdgesBetweenEnds(SoupTriangle& soup);
  void SetCornerNormals(const std::uint32_t triangle[3], SoupTriangle& soup) const;
  void SetCornerColors(const std::uint32_t triangle[3], SoupTriangle& soup) const;
  /// Gets the corner positions; false for a triangle with a repeated corner.
  bool GetCorners(const std::uint32_t triangle[3], float corners[3][3]) const;
  /// False for a degenerate triangle, also one the model's grid makes degenerate
  /// (VanishesOnTheGrid).
  bool HasArea(const float corners[3][3]) const;
  /// Whether the model's grid (QuantizationGrid::ForBounds of the input's box), on which the
  /// leaves store the triangle, leaves it no area: a needle thinner than the step, which the
  /// largest coordinate sets.
  bool VanishesOnTheGrid(const float corners[3][3]) const;
  bool StartNextBatch();
  /// At the end of the faces: the boundary statistics from the check.
  void FinishBoundaryCheck();
  /// Called per triangle visited: every few million, releases the resident pages of the
  /// vertex array and the sketch, so a mesh of any size streams in bounded memory.
  void BoundResidentMemory();

  std::string Path;
  std::unique_ptr<PolygonMesh> Mesh;
  VertexView Vertices;
  Box VertexBounds; ///< of every vertex, then of those the faces use (UsedBounds)
  Box UsedBounds;
  QuantizationGrid Grid{}; ///< the model's, once the bounds are known
  BoundarySketch Sketch;
  std::shared_ptr<BoundaryEdgeCheck> Check = std::make_shared<BoundaryEdgeCheck>();
  ScratchArray<std::array<float, 3>> NormalSums;
  /// Per vertex: the kept triangles that use it, up to ManyInputUses (SoupTriangle::InputUses).
  ScratchArray<std::uint8_t> InputUses;
  InputStats Statistics;
  std::uint64_t KeptTriangles = 0;
  TriangleCursor Triangles{ this->Vertices };
  bool FacesDone = false;
  std::uint64_t VisitedSinceRelease = 0;
};

} // namespace atp

#endif
