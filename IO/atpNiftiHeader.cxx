#include "atpNiftiHeader.h"

#include "vtk_zlib.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <iomanip>
#include <sstream>
#include <string>

#include <sys/stat.h>

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
/// The voxels a header declares must be in the file (VTK allocates them before it finds them
/// missing, and prints its own allocation error on the way): after the header in a .nii, at most
/// deflate's ratio (about 1032:1) of the compressed bytes in a .nii.gz.
std::string VoxelBytesProblem(const std::string& path, bool gzipped, const unsigned char* header,
  bool nifti1, bool bigEndian, double voxOffset, int bits)
{
  const std::size_t dimAt = nifti1 ? 40 : 16;
  const int wordBytes = nifti1 ? 2 : 8;
  const auto dim = [&](int i) {
    const unsigned char* p = header + dimAt + std::size_t(i * wordBytes);
    if (nifti1)
    {
      return double(std::int16_t(Read(p, 2, bigEndian)));
    }
    const std::uint64_t low = Read(p + (bigEndian ? 4 : 0), 4, bigEndian);
    const std::uint64_t high = Read(p + (bigEndian ? 0 : 4), 4, bigEndian);
    return double(std::int64_t(high << 32 | low));
  };
  const int dimensions = int(std::min(7.0, std::max(0.0, dim(0))));
  double voxels = 1;
  std::string shape;
  for (int i = 1; i <= dimensions; ++i)
  {
    voxels *= std::max(1.0, dim(i));
    shape += (i > 1 ? "x" : "") + std::to_string(std::int64_t(std::max(1.0, dim(i))));
  }
  struct stat file{};
  if (::stat(path.c_str(), &file) != 0)
  {
    return std::string();
  }
  const double held = gzipped ? 1032.0 * double(file.st_size) : double(file.st_size) - voxOffset;
  const double bytes = voxels * bits / 8;
  if (bytes > held)
  {
    std::ostringstream message;
    message << (gzipped ? "" : "truncated: ") << "its NIfTI header declares " << shape << " voxels (" << std::fixed << std::setprecision(0)
            << bytes << " bytes), more than the file "
            << (gzipped ? "can hold compressed" : "holds");
    return message.str();
  }
  return std::string();
}
} // namespace

std::string NiftiHeaderProblem(const std::string& path)
{
  unsigned char header[Nifti1Bytes];
  // gzread reads uncompressed files as they are.
  gzFile file = gzopen(path.c_str(), "rb");
  const int got = file ? gzread(file, header, sizeof header) : -1;
  bool gzipped = false;
  if (file)
  {
    gzipped = gzdirect(file) == 0; // known once something has been read
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
      return type.Bits == bits ? VoxelBytesProblem(path, gzipped, header, nifti1, bigEndian, voxOffset, bits)
                               : "NIfTI datatype " + std::to_string(code) + " has " +
          std::to_string(type.Bits) + " bits per voxel, the header says " + std::to_string(bits);
    }
  }
  return "NIfTI datatype " + std::to_string(code) +
    " is not one scalar per voxel of a type atp reads (8 to 64-bit integers, 32 or 64-bit floats)";
}

} // namespace atp
