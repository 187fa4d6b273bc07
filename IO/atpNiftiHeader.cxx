#include "atpNiftiHeader.h"

#include "vtk_zlib.h"

#include <cstdint>
#include <cstring>

namespace atp
{
namespace
{
/// NIfTI-1 and NIfTI-2 headers start with their own size; the datatype and bits per voxel
/// follow at fixed offsets.
constexpr std::int32_t Nifti1Bytes = 348, Nifti2Bytes = 540;
constexpr std::size_t Nifti1DataType = 70, Nifti2DataType = 12; // bitpix follows it

/// NIfTI datatype codes of one scalar per voxel, with their bits per voxel.
struct ScalarType
{
  std::int16_t Code;
  std::int16_t Bits;
};
constexpr ScalarType ScalarTypes[] = { { 2, 8 }, { 4, 16 }, { 8, 32 }, { 16, 32 }, { 64, 64 },
  { 256, 8 }, { 512, 16 }, { 768, 32 }, { 1024, 64 }, { 1280, 64 } };

std::uint32_t Swapped32(std::uint32_t v)
{
  return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}
} // namespace

std::string NiftiHeaderProblem(const std::string& path)
{
  unsigned char header[Nifti1Bytes];
  // gzread reads uncompressed files as they are.
  gzFile file = gzopen(path.c_str(), "rb");
  const int got = file ? gzread(file, header, sizeof header) : -1;
  if (file)
  {
    gzclose(file);
  }
  if (got < int(sizeof header))
  {
    return "a NIfTI header is 348 bytes or more; the file holds fewer";
  }
  std::uint32_t size;
  std::memcpy(&size, header, sizeof size);
  const bool swapped = size != std::uint32_t(Nifti1Bytes) && size != std::uint32_t(Nifti2Bytes);
  size = swapped ? Swapped32(size) : size;
  if (size != std::uint32_t(Nifti1Bytes) && size != std::uint32_t(Nifti2Bytes))
  {
    return "not a NIfTI header (it does not start with its size, 348 or 540)";
  }
  const std::size_t at = size == std::uint32_t(Nifti1Bytes) ? Nifti1DataType : Nifti2DataType;
  const auto field = [&](std::size_t offset) {
    const unsigned first = header[offset], second = header[offset + 1];
    return std::int16_t(swapped ? (first << 8 | second) : (second << 8 | first));
  };
  const std::int16_t code = field(at), bits = field(at + 2);
  for (const ScalarType& type : ScalarTypes)
  {
    if (type.Code == code)
    {
      return type.Bits == bits ? std::string()
                               : "NIfTI datatype " + std::to_string(code) + " has " +
          std::to_string(type.Bits) + " bits per voxel, the header says " + std::to_string(bits);
    }
  }
  return "NIfTI datatype " + std::to_string(code) +
    " is not one scalar per voxel of a type atp reads (8 to 64-bit integers, 32 or 64-bit floats)";
}

} // namespace atp
