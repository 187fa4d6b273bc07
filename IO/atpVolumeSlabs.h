// A volume (a 3D image of scalars) read a slab of Z slices at a time through a VTK reader's
// update extent, so no more than one slab is in memory: the input side of the isosurface.
#ifndef atpVolumeSlabs_h
#define atpVolumeSlabs_h

#include "vtkATPIOModule.h" // export macro

#include <vtkImageData.h>
#include <vtkSmartPointer.h>

#include <array>
#include <string>

class vtkAlgorithm;

namespace atp
{

class VtkErrorCollector;

/// Voxel types of raw volume files.
enum class VoxelType
{
  UInt8,
  Int16,
  UInt16,
  Float32
};

/// "uint8", "int16", "uint16", "float32".
VTKATPIO_EXPORT const char* VoxelTypeName(VoxelType type);
/// Parses a VoxelTypeName; false for anything else.
VTKATPIO_EXPORT bool ParseVoxelType(const std::string& name, VoxelType& type);

/// How the voxels of a raw file (no header) are laid out: x fastest, then y, then z.
struct RawVolumeLayout
{
  std::array<int, 3> Dimensions{ { 0, 0, 0 } };
  VoxelType Type = VoxelType::UInt8;
  std::array<double, 3> Spacing{ { 1, 1, 1 } };
  std::array<double, 3> Origin{ { 0, 0, 0 } };
  bool BigEndian = false;
};

/// Whether `path` names a volume format known by its extension: .nii, .nii.gz, .vti (any case).
/// Raw volumes have no extension of their own: a RawVolumeLayout says a file is one.
VTKATPIO_EXPORT bool IsVolumeFileName(const std::string& path);

class VTKATPIO_EXPORT VolumeSlabReader
{
public:
  /// Opens a NIfTI (.nii, .nii.gz) or VTK image (.vti) file by extension, or, when `raw` is
  /// given, a raw file of that layout (its size is checked against the layout). Reads only the
  /// header. Throws InputError naming the file and the problem.
  static VolumeSlabReader Open(const std::string& path, const RawVolumeLayout* raw = nullptr);

  /// Any VTK image source, e.g. a reader followed by a resampling filter; `name` stands for it in
  /// error messages. Throws InputError when it gives no image information.
  VolumeSlabReader(vtkAlgorithm* source, const std::string& name);
  ~VolumeSlabReader();
  VolumeSlabReader(VolumeSlabReader&&) noexcept;
  VolumeSlabReader& operator=(VolumeSlabReader&&) = delete;

  const std::string& Name() const { return this->SourceName; }
  /// The whole volume's extent (x0, x1, y0, y1, z0, z1), inclusive.
  const std::array<int, 6>& WholeExtent() const { return this->Whole; }

  /// The values the voxels stand for are slope * stored + intercept (NIfTI's scl_slope and
  /// scl_inter, which VTK's reader leaves unapplied); 1 and 0 for other formats.
  double ValueSlope() const { return this->Slope; }
  double ValueIntercept() const { return this->Intercept; }

  /// Slices [firstSlice, lastSlice] of the whole extent, exactly that extent, laid out as in the
  /// whole volume. Throws InputError with the reader's message when reading fails.
  vtkSmartPointer<vtkImageData> ReadSlab(int firstSlice, int lastSlice);

private:
  vtkSmartPointer<vtkAlgorithm> Source;
  vtkSmartPointer<VtkErrorCollector> Errors;
  std::string SourceName;
  std::array<int, 6> Whole{ { 0, -1, 0, -1, 0, -1 } };
  /// vtkNIFTIImageReader with a negative qfac stores the slices of each request in reverse:
  /// the slices of slab [a, b] are then those it gives for the mirrored request.
  bool MirroredSlices = false;
  double Slope = 1;
  double Intercept = 0;
};

} // namespace atp

#endif
