// The triangles of a batch of polygons, one per call, so a caller can stop anywhere (a full
// output buffer) and go on later: a triangle as it is, a larger polygon as a
// PolygonTriangulator makes it (a fan where that is right).
#ifndef atpTriangleCursor_h
#define atpTriangleCursor_h

#include "atpPolygonMesh.h"
#include "atpPolygonTriangulation.h"

#include <cstdint>
#include <vector>

namespace atp
{

class TriangleCursor
{
public:
  /// `vertices`, the positions the batches' indices refer to, must outlive the cursor.
  explicit TriangleCursor(const VertexView& vertices)
    : Vertices(vertices)
  {
  }

  void Reset(const PolygonBatch& batch)
  {
    this->Batch = batch;
    this->Polygon = 0;
    this->FirstCorner = 0;
    this->Pending.clear();
    this->Taken = 0;
  }

  /// The next triangle's vertex indices; false when the batch is used up.
  bool Next(std::uint32_t triangle[3])
  {
    while (this->Taken == this->Pending.size())
    {
      if (this->Polygon == this->Batch.Count)
      {
        return false;
      }
      const std::uint32_t size = this->Batch.Sizes[this->Polygon];
      const std::uint32_t* corners = this->Batch.Indices + this->FirstCorner;
      this->FirstCorner += size;
      ++this->Polygon;
      if (size == 3) // nearly every polygon of nearly every mesh
      {
        triangle[0] = corners[0];
        triangle[1] = corners[1];
        triangle[2] = corners[2];
        return true;
      }
      this->Pending.clear();
      this->Taken = 0;
      if (size > 3)
      {
        this->Triangulator.Triangulate(corners, size, this->Vertices, this->Pending);
      }
    }
    triangle[0] = this->Pending[this->Taken];
    triangle[1] = this->Pending[this->Taken + 1];
    triangle[2] = this->Pending[this->Taken + 2];
    this->Taken += 3;
    return true;
  }

private:
  const VertexView& Vertices;
  PolygonBatch Batch;
  std::size_t Polygon = 0;
  std::size_t FirstCorner = 0;
  /// The triangles of the current polygon of more than three corners, three indices each.
  std::vector<std::uint32_t> Pending;
  std::size_t Taken = 0;
  PolygonTriangulator Triangulator;
};

} // namespace atp

#endif
