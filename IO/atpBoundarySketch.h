// Finds the boundary edges of a triangle mesh (edges used by an odd number of triangles) with
// 8 bytes per vertex and no edge table, so it works out of core for meshes of any size.
//
// Every triangle (u, v, w) XORs its two other corners into a per-vertex sketch: X[u] ^= v ^ w and
// Y[u] ^= H(v) ^ H(w), the same at v and w. An edge used twice cancels out, so X[u] ends up as the
// XOR of u's boundary neighbours and Y[u] as the XOR of their hashes. For a manifold boundary
// vertex with boundary neighbours a and b, X[u] = a ^ b: edge (u, v) is a boundary edge at u iff
// o = X[u] ^ v is another vertex and H(v) ^ H(o) == Y[u] (a false match has odds 2^-32). An edge
// counts as boundary when the test passes at both ends. A vertex where the boundary pinches (four
// or more boundary neighbours) fails the test: its edges read as interior, which is the safe side
// because edges not known to be boundary edges get locked later.
#ifndef atpBoundarySketch_h
#define atpBoundarySketch_h

#include "atpScratchArray.h"
#include "vtkATPIOModule.h" // export macro

#include <cstdint>
#include <string>

namespace atp
{

class VTKATPIO_EXPORT BoundarySketch
{
public:
  /// The sketch lives in a ScratchArray in `scratchDirectory`.
  BoundarySketch(std::uint64_t vertexCount, const std::string& scratchDirectory);

  void AddTriangle(std::uint32_t u, std::uint32_t v, std::uint32_t w)
  {
    this->Add(u, v, w);
    this->Add(v, w, u);
    this->Add(w, u, v);
  }

  /// Whether the edge (u, v), in either direction, is used by an odd number of the triangles
  /// added (exact for vertices with at most two boundary neighbours; see the file comment).
  bool IsBoundaryEdge(std::uint32_t u, std::uint32_t v) const
  {
    return this->EndPasses(u, v) && this->EndPasses(v, u);
  }

  /// Whether an edge of u is used an odd number of times (the test of IsBoundaryEdge can pass
  /// at u only then).
  bool OnOpenEdge(std::uint32_t u) const
  {
    return this->Entries[u].NeighbourXor != 0 || this->Entries[u].HashXor != 0;
  }

  /// Forgets every triangle added.
  void Clear() { this->Entries.Assign(this->Entries.Size(), Entry{ 0, 0 }); }

  /// Lets the sketch's pages leave resident memory (they stay in its scratch file): all of
  /// them, or those of vertices [first, first + count).
  void ReleaseResidentPages() const;
  void ReleaseResidentPages(std::uint64_t first, std::uint64_t count) const;

private:
  struct Entry
  {
    std::uint32_t NeighbourXor;
    std::uint32_t HashXor;
  };

  /// A bijective 32-bit mixer (Wellons' lowbias32): neighbours' XOR must not predict the XOR of
  /// their hashes.
  static std::uint32_t Hash(std::uint32_t x)
  {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
  }

  void Add(std::uint32_t at, std::uint32_t a, std::uint32_t b)
  {
    Entry& e = this->Entries[at];
    e.NeighbourXor ^= a ^ b;
    e.HashXor ^= Hash(a) ^ Hash(b);
  }

  bool EndPasses(std::uint32_t at, std::uint32_t other) const
  {
    const Entry& e = this->Entries[at];
    const std::uint32_t otherNeighbour = e.NeighbourXor ^ other;
    return otherNeighbour != other && (Hash(other) ^ Hash(otherNeighbour)) == e.HashXor;
  }

  ScratchArray<Entry> Entries;
};

} // namespace atp

#endif
