// A PolygonMesh held in memory, for inputs that must be read whole before their faces make sense
// (STL, welded first). Served as a single batch.
#ifndef atpInMemoryMesh_h
#define atpInMemoryMesh_h

#include "atpPolygonMesh.h"

#include <vector>

namespace atp
{

class InMemoryMesh final : public PolygonMesh
{
public:
  std::vector<float> Positions; ///< x, y, z per vertex
  std::vector<std::uint32_t> Indices;
  std::vector<std::uint32_t> Sizes;

  VertexView Vertices() const override
  {
    VertexView view;
    view.Base = reinterpret_cast<const unsigned char*>(this->Positions.data());
    view.Count = this->Positions.size() / 3;
    return view;
  }

  void Rewind() override { this->Delivered = false; }

  bool NextBatch(PolygonBatch& batch) override
  {
    if (this->Delivered || this->Sizes.empty())
    {
      return false;
    }
    batch.Indices = this->Indices.data();
    batch.Sizes = this->Sizes.data();
    batch.Count = this->Sizes.size();
    this->Delivered = true;
    return true;
  }

private:
  bool Delivered = false;
};

} // namespace atp

#endif
