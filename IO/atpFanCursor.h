// Fan triangulation of a batch of polygons: (c0, c1, c2), (c0, c2, c3), ... for each polygon,
// one triangle per call, so a caller can stop anywhere (a full output buffer) and go on later.
#ifndef atpFanCursor_h
#define atpFanCursor_h

#include "atpPolygonMesh.h"

#include <cstdint>

namespace atp
{

class FanCursor
{
public:
  void Reset(const PolygonBatch& batch)
  {
    this->Batch = batch;
    this->Polygon = 0;
    this->FirstCorner = 0;
    this->Corner = 1;
  }

  /// The next triangle's vertex indices; false when the batch is used up.
  bool Next(std::uint32_t triangle[3])
  {
    while (this->Polygon < this->Batch.Count)
    {
      const std::uint32_t size = this->Batch.Sizes[this->Polygon];
      if (this->Corner + 1 < size)
      {
        const std::uint32_t* corners = this->Batch.Indices + this->FirstCorner;
        triangle[0] = corners[0];
        triangle[1] = corners[this->Corner];
        triangle[2] = corners[this->Corner + 1];
        ++this->Corner;
        return true;
      }
      this->FirstCorner += size;
      ++this->Polygon;
      this->Corner = 1;
    }
    return false;
  }

private:
  PolygonBatch Batch;
  std::size_t Polygon = 0;
  std::size_t FirstCorner = 0;
  std::uint32_t Corner = 1;
};

} // namespace atp

#endif
