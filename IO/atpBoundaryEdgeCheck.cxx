#include "atpBoundaryEdgeCheck.h"

#include "atpPositionWelder.h"

#include <algorithm>
#include <cstring>

namespace atp
{
namespace
{
std::uint64_t Mix(std::uint64_t h, std::uint64_t word)
{
  // splitmix64's finalizer over a running sum: every input bit reaches every output bit.
  h += word + 0x9e3779b97f4a7c15ULL;
  h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ULL;
  h = (h ^ (h >> 27)) * 0x94d049bb133111ebULL;
  return h ^ (h >> 31);
}

std::uint64_t NonZero(std::uint64_t h)
{
  return h == 0 ? 1 : h;
}

std::uint64_t PositionKey(const float p[3])
{
  std::uint32_t bits[3];
  PositionBits(p, bits);
  return NonZero(Mix(Mix(0, std::uint64_t(bits[0]) << 32 | bits[1]), bits[2]));
}

/// The same key in either direction.
std::uint64_t EdgeKey(const float a[3], const float b[3])
{
  std::uint32_t p[3], q[3];
  PositionBits(a, p);
  PositionBits(b, q);
  if (std::lexicographical_compare(q, q + 3, p, p + 3))
  {
    std::swap_ranges(p, p + 3, q);
  }
  std::uint64_t h = 0;
  for (int k = 0; k < 3; ++k)
  {
    h = Mix(h, std::uint64_t(p[k]) << 32 | q[k]);
  }
  return NonZero(h);
}
} // namespace

std::size_t BoundaryEdgeCheck::Table::Slot(std::uint64_t key) const
{
  const std::size_t mask = this->Keys.size() - 1;
  std::size_t slot = std::size_t(key) & mask;
  while (this->Keys[slot] != 0 && this->Keys[slot] != key)
  {
    slot = (slot + 1) & mask;
  }
  return slot;
}

bool BoundaryEdgeCheck::Table::Holds(std::uint64_t key) const
{
  return !this->Keys.empty() && this->Keys[this->Slot(key)] == key;
}

bool BoundaryEdgeCheck::Table::Add(std::uint64_t key, std::size_t max, std::uint8_t flags)
{
  if (2 * (this->Count + 1) > this->Keys.size() && this->Count < max)
  {
    Table grown;
    grown.Keys.assign(std::max<std::size_t>(1024, 2 * this->Keys.size()), 0);
    grown.Uses.assign(grown.Keys.size(), 0);
    for (std::size_t i = 0; i < this->Keys.size(); ++i)
    {
      if (this->Keys[i] != 0)
      {
        const std::size_t slot = grown.Slot(this->Keys[i]);
        grown.Keys[slot] = this->Keys[i];
        grown.Uses[slot] = this->Uses[i];
      }
    }
    grown.Count = this->Count;
    *this = std::move(grown);
  }
  const std::size_t slot = this->Keys.empty() ? 0 : this->Slot(key); // empty: max is 0
  if (this->Keys.empty() || this->Keys[slot] == 0)
  {
    if (this->Count == max)
    {
      return false;
    }
    this->Keys[slot] = key;
    ++this->Count;
  }
  const int uses = std::min(int(UseCount), (this->Uses[slot] & UseCount) + 1);
  this->Uses[slot] = std::uint8_t((this->Uses[slot] & ~UseCount) | uses | flags);
  return true;
}

BoundaryEdgeCheck::BoundaryEdgeCheck(std::size_t maxEdges)
  : MaxEdges(maxEdges)
{
}

void BoundaryEdgeCheck::Overflow()
{
  this->TooMany = true;
  this->Edges = Table();
  this->Ends = Table();
}

void BoundaryEdgeCheck::AddEndPosition(const float p[3])
{
  if (!this->TooMany && !this->Ends.Add(PositionKey(p), this->MaxEdges))
  {
    this->Overflow();
  }
}

bool BoundaryEdgeCheck::IsEndPosition(const float p[3]) const
{
  return this->Ends.Holds(PositionKey(p));
}

void BoundaryEdgeCheck::MarkNearAnother(const float p[3])
{
  if (!this->Ends.Keys.empty())
  {
    const std::size_t slot = this->Ends.Slot(PositionKey(p));
    if (this->Ends.Keys[slot] != 0)
    {
      this->Ends.Uses[slot] |= NearBit;
    }
  }
}

bool BoundaryEdgeCheck::IsNearAnother(const float p[3]) const
{
  if (this->Ends.Keys.empty())
  {
    return false;
  }
  const std::size_t slot = this->Ends.Slot(PositionKey(p));
  return this->Ends.Keys[slot] != 0 && (this->Ends.Uses[slot] & NearBit);
}

void BoundaryEdgeCheck::Count(const float a[3], const float b[3], bool open)
{
  const std::uint8_t flags =
    std::uint8_t((open ? OpenBit : 0) | (this->IsNearAnother(a) || this->IsNearAnother(b) ? NearBit : 0));
  if (!this->TooMany && !this->Edges.Add(EdgeKey(a, b), this->MaxEdges, flags))
  {
    this->Overflow();
  }
}

std::uint8_t BoundaryEdgeCheck::EdgeUses(const float a[3], const float b[3]) const
{
  if (this->Edges.Keys.empty())
  {
    return 0;
  }
  const std::size_t slot = this->Edges.Slot(EdgeKey(a, b));
  return this->Edges.Keys[slot] != 0 ? this->Edges.Uses[slot] : 0;
}

void BoundaryEdgeCheck::Apply(SoupTriangle* triangles, std::size_t count) const
{
  for (std::size_t t = 0; t < count; ++t)
  {
    SoupTriangle& triangle = triangles[t];
    if (this->TooMany)
    {
      triangle.BoundaryEdges &= std::uint8_t(~(7u | CountedBit)); // counting stopped part way
      continue;
    }
    if (!(triangle.BoundaryEdges & CountedBit))
    {
      continue; // no edge counted: none flagged either (a flagged edge joins two end positions)
    }
    triangle.BoundaryEdges &= std::uint8_t(~CountedBit);
    for (int c = 0; c < 3; ++c)
    {
      const std::uint8_t bit = std::uint8_t(1u << c);
      const std::uint8_t edge = this->EdgeUses(triangle.V[c], triangle.V[(c + 1) % 3]);
      const int uses = edge & UseCount;
      if (uses != 1)
      {
        triangle.BoundaryEdges &= std::uint8_t(~bit);
      }
      if (uses >= 3 || (uses == 1 && (edge & NearBit)))
      {
        triangle.BoundaryEdges |= std::uint8_t(8u << c);
      }
    }
  }
}

std::uint64_t BoundaryEdgeCheck::EdgesUsedOnce() const
{
  return std::uint64_t(std::count_if(this->Edges.Uses.begin(), this->Edges.Uses.end(),
    [](std::uint8_t uses) { return (uses & UseCount) == 1; }));
}

std::uint64_t BoundaryEdgeCheck::EdgesShared() const
{
  return std::uint64_t(std::count_if(this->Edges.Uses.begin(), this->Edges.Uses.end(),
    [](std::uint8_t uses) { return (uses & OpenBit) && (uses & UseCount) >= 2; }));
}

} // namespace atp
