#include "atpPositionWelder.h"

#include <stdexcept>

namespace atp
{

PositionWelder::PositionWelder(std::size_t maxVertices, float* positions)
{
  Reset(maxVertices, positions);
}

void PositionWelder::Reset(std::size_t maxVertices, float* positions)
{
  Positions = positions;
  MaxVertices = maxVertices;
  Vertices = 0;
  std::size_t capacity = 16;
  while (capacity < 2 * maxVertices)
  {
    capacity *= 2;
  }
  Slots.assign(capacity, 0);
  Mask = capacity - 1;
}

std::uint32_t PositionWelder::Weld(const float p[3], bool& added)
{
  std::uint32_t bits[3];
  std::memcpy(bits, p, sizeof(bits));
  std::size_t s = PositionHash(bits) & Mask;
  for (; Slots[s] != 0; s = (s + 1) & Mask)
  {
    if (std::memcmp(&Positions[3 * (Slots[s] - 1)], bits, sizeof(bits)) == 0)
    {
      added = false;
      return Slots[s] - 1;
    }
  }
  if (Vertices == MaxVertices)
  {
    throw std::logic_error("PositionWelder: more distinct positions than it was made for");
  }
  std::memcpy(&Positions[3 * Vertices], bits, sizeof(bits));
  Slots[s] = std::uint32_t(++Vertices);
  added = true;
  return Slots[s] - 1;
}

} // namespace atp
