// The header of a PLY file: format, and the elements with their properties, in file order.
#ifndef atpPlyHeader_h
#define atpPlyHeader_h

#include "atpInputFile.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace atp
{

enum class PlyFormat
{
  Ascii,
  BinaryLittleEndian,
  BinaryBigEndian
};

enum class PlyType : std::uint8_t
{
  Int8,
  UInt8,
  Int16,
  UInt16,
  Int32,
  UInt32,
  Float32,
  Float64
};

/// Bytes of a binary value (inline: the binary readers ask per value).
inline std::size_t PlyTypeSize(PlyType type)
{
  switch (type)
  {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 0;
}

inline bool IsPlyIntegerType(PlyType type)
{
  return type != PlyType::Float32 && type != PlyType::Float64;
}

struct PlyProperty
{
  std::string Name;
  PlyType Type = PlyType::UInt8; ///< the value type, or the item type of a list
  bool IsList = false;
  PlyType CountType = PlyType::UInt8; ///< lists only
};

struct PlyElement
{
  std::string Name;
  std::uint64_t Count = 0;
  std::vector<PlyProperty> Properties;
};

struct PlyHeader
{
  PlyFormat Format = PlyFormat::Ascii;
  std::vector<PlyElement> Elements;
  std::uint64_t DataOffset = 0; ///< first byte after end_header's line
  std::uint64_t DataLine = 1;   ///< line number there (ASCII messages)
};

/// Throws InputError ("bad PLY header ...", "unsupported PLY property type ...").
PlyHeader ReadPlyHeader(const InputFile& file);

} // namespace atp

#endif
