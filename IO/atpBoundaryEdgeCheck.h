// Which of the edges the boundary sketch flags are boundary edges by position.
//
// The sketch (atpBoundarySketch.h) works on vertex indices and parity. An input whose coincident
// vertices are not welded (a triangle soup, a seam of duplicated vertices) has shared edges that
// read as boundary there, and so has an edge used three times (a repeated triangle, three sheets
// on one edge). Simplification may move a boundary vertex along the boundary, which opens a
// crack when another patch holds the same edge: so an edge stays a boundary edge only if one
// triangle uses it, counted by the positions of its ends. Edges that are not boundary edges are
// locked where they cross a patch's border, which never cracks.
//
// Every edge the sketch flags joins two vertices on an open edge, so only edges between two of
// their positions need counting: between the passes over the input, the sketch's open-edge
// vertices give their positions (AddEndPosition); the second pass counts every use of an edge
// between two such positions (Count), flagged or not.
#ifndef atpBoundaryEdgeCheck_h
#define atpBoundaryEdgeCheck_h

#include "atpTriangleSource.h"
#include "vtkATPIOModule.h" // export macro

#include <cstddef>
#include <cstdint>
#include <vector>

namespace atp
{

class VTKATPIO_EXPORT BoundaryEdgeCheck
{
public:
  /// Edges, and end positions, the check holds at most: 9 bytes a slot, at most two slots each,
  /// so up to 144 MiB per table, and 216 MiB while the full table grows into its last size (the
  /// end positions go once the input is read). A welded mesh's boundary takes a sliver of it;
  /// an unwelded soup of over about 3M triangles overflows it.
  static constexpr std::size_t DefaultMaxEdges = std::size_t(1) << 23;

  explicit BoundaryEdgeCheck(std::size_t maxEdges = DefaultMaxEdges);

  /// The position of a vertex on an edge the sketch found open.
  void AddEndPosition(const float p[3]);
  bool HasEndPositions() const { return this->Ends.Count > 0; }
  bool IsEndPosition(const float p[3]) const;
  /// Marks the end position p as lying within a grid step of another one (after every end
  /// position is added): the two sides of a seam whose copies rounded to neighbouring grid
  /// points, which the model keeps apart by a step.
  void MarkNearAnother(const float p[3]);
  /// Once the input is read: the end positions are no longer needed.
  void DropEndPositions() { this->Ends = Table(); }

  /// Bit 6 of SoupTriangle::BoundaryEdges: an edge of the triangle was counted.
  static constexpr std::uint8_t CountedBit = 64;

  /// One use of the edge between the positions a and b, in either direction; `open` when the
  /// sketch flagged this use. Past maxEdges distinct edges (or end positions) the tables are
  /// dropped and no edge is a boundary edge any more (all are locked: no crack, only less
  /// simplification along the true boundary; edges of three or more sheets are then not
  /// marked).
  void Count(const float a[3], const float b[3], bool open);

  /// For the triangles with an edge counted (CountedBit): clears the BoundaryEdges bits of the
  /// edges not used exactly once, and marks as edges whose ends never move (bit 3 + i) those used
  /// three times or more, flagged by the sketch or not (a vertex where the boundary pinches fails
  /// the sketch's test), and those used once with an end near another (MarkNearAnother): each
  /// side of such a seam simplified on its own would move away from the other. Clears
  /// CountedBit.
  void Apply(SoupTriangle* triangles, std::size_t count) const;

  /// Distinct edges counted once: the input's boundary edges by position.
  std::uint64_t EdgesUsedOnce() const;
  /// Distinct edges the sketch flagged that more than one triangle uses.
  std::uint64_t EdgesShared() const;
  bool Overflowed() const { return this->TooMany; }

private:
  /// Open addressing with linear probing over 64-bit hashes; key 0 marks an empty slot. Keys
  /// are hashes: two edges (or positions) that share one count as one, which shares or marks
  /// more edges than there are and locks them (the safe side).
  struct Table
  {
    std::vector<std::uint64_t> Keys;
    /// Low bits: 1, 2, or 3 for "three times or more"; OpenBit: a use was flagged open.
    std::vector<std::uint8_t> Uses;
    std::size_t Count = 0;

    std::size_t Slot(std::uint64_t key) const;
    bool Holds(std::uint64_t key) const;
    /// One more use of `key` (`flags` or'ed in); false (nothing added) when it is new and `max`
    /// keys are held.
    bool Add(std::uint64_t key, std::size_t max, std::uint8_t flags = 0);
  };

  void Overflow();
  /// Uses: the count in the low bits; OpenBit: a use was flagged open; NearBit: an end
  /// position near another (Ends), an edge with such an end (Edges).
  static constexpr std::uint8_t UseCount = 3, NearBit = 64, OpenBit = 128;
  /// The edge's Uses byte: 0 when never counted.
  std::uint8_t EdgeUses(const float a[3], const float b[3]) const;
  bool IsNearAnother(const float p[3]) const;

  std::size_t MaxEdges;
  bool TooMany = false;
  Table Edges, Ends;
};

} // namespace atp

#endif
