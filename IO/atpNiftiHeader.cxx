#include "atpNiftiHeader.h"

#include "vtk_zlib.h"

#include <cstdint>
#include <cstring>
#include <sstream>

namespace atp
{
namespace
{
/// NIfTI-1 and NIfTI-2 headers start with their own size; the datatype and bits per voxel
/// follow at fixed offsets.
constexpr std::int32_t Nifti1Bytes = 348, Nifti2Bytes = 540;
constexpr std::size_t Nifti1DataType = 70, Nifti2DataType = 12; // bitpix follows it
/// Where a single-file header says its voxels start (NIfTI-1: a float; NIfTI-2: a 64-bit
/// integer), never before the header and its 4 extension flag bytes end.
constexpr std::size_t Nifti1VoxOffset = 108, Nifti2VoxOffset = 168;

/// NIfTI datatype codes of one scalar per voxel, with their bits per voxel.
struct ScalarType
{
  std::int16_t Code;
  std::int16_t Bits;
};
constexpr ScalarType ScalarTypes[] = { { 2, 8 }, { 4, 16 }, { 8, 32 }, { 16, 32 }, { 64, 64 },
  { 256, 8 }, { 512, 16 }, { 768, 32 }, { 1024, 64 }, { 1280, 64 } };

/// The integer of `bytes` bytes at p, little or big-endian, whatever the host's order.
std::uint32_t Read(const unsigned char* p, int bytes, bool bigEndian)
{
  std::uint32_t value = 0;
  for (int i = 0; i < bytes; ++i)
  {
    value |= std::uint32_t(p[bigEndian ? bytes - 1 - i : i]) << (8 * i);
  }
  return value;
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
    return got < 0 ? "cannot read its NIfTI header (a corrupt .gz?)"
                   : "a NIfTI header is 348 bytes or more; the file holds fewer";
  }
  const auto isHeaderSize = [](std::uint32_t size) {
    return size == std::uint32_t(Nifti1Bytes) || size == std::uint32_t(Nifti2Bytes);
  };
  const bool bigEndian = !isHeaderSize(Read(header, 4, false));
  const std::uint32_t size = Read(header, 4, bigEndian);
  if (!isHeaderSize(size))
  {
    return "not a NIfTI header (it does not start with its size, 348 or 540)";
  }
  const bool nifti1 = size == std::uint32_t(Nifti1Bytes);
  double voxOffset = 0;
  if (nifti1)
  {
    const std::uint32_t bits = Read(header + Nifti1VoxOffset, 4, bigEndian);
    float value;
    std::memcpy(&value, &bits, 4);
    voxOffset = value;
  }
  else
  {
    const std::uint64_t low = Read(header + Nifti2VoxOffset + (bigEndian ? 4 : 0), 4, bigEndian);
    const std::uint64_t high = Read(header + Nifti2VoxOffset + (bigEndian ? 0 : 4), 4, bigEndian);
    voxOffset = double(std::int64_t(high << 32 | low));
  }
  const double headerEnd = double(size) + 4;
  if (!(voxOffset >= headerEnd))
  {
    std::ostringstream message;
    message << "its NIfTI header puts the voxels at byte " << voxOffset << ", inside the header ("
            << headerEnd << " bytes with the extension flags)";
    return message.str();
  }
  const std::size_t at = nifti1 ? Nifti1DataType : Nifti2DataType;
  const auto code = std::int16_t(Read(header + at, 2, bigEndian));
  const auto bits = std::int16_t(Read(header + at + 2, 2, bigEndian));
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
