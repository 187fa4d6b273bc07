#include "atpVolumeSlabs.h"

#include "atpInputFile.h"
#include "atpNiftiHeader.h"
#include "atpTriangleSource.h" // InputError
#include "atpVtkErrors.h"
#include "atpVtkXmlCheck.h"

#include <vtkAlgorithm.h>
#include <vtkExecutive.h>
#include <vtkImageReader2.h>
#include <vtkInformation.h>
#include <vtkNIFTIImageReader.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLReader.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <new>
#include <cctype>

namespace atp
{
namespace
{
std::string Lowercase(std::string text)
{
  std::transform(text.begin(), text.end(), text.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

bool EndsWith(const std::string& text, const std::string& suffix)
{
  return text.size() >= suffix.size() &&
    text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool IsNiftiFileName(const std::string& path)
{
  const std::string lower = Lowercase(path);
  return EndsWith(lower, ".nii") || EndsWith(lower, ".nii.gz");
}

int VtkScalarType(VoxelType type)
{
  switch (type)
  {
    case VoxelType::UInt8:
      return VTK_UNSIGNED_CHAR;
    case VoxelType::Int16:
      return VTK_SHORT;
    case VoxelType::UInt16:
      return VTK_UNSIGNED_SHORT;
    case VoxelType::Float32:
      return VTK_FLOAT;
  }
  return VTK_VOID;
}

std::uint64_t VoxelBytes(VoxelType type)
{
  return type == VoxelType::UInt8 ? 1 : type == VoxelType::Float32 ? 4 : 2;
}

/// A raw file read by vtkImageReader2, which reads only the rows of the requested extent.
vtkSmartPointer<vtkAlgorithm> OpenRaw(const InputFile& file, const RawVolumeLayout& layout)
{
  std::uint64_t expected = VoxelBytes(layout.Type);
  bool overflow = false;
  for (int axis = 0; axis < 3; ++axis)
  {
    if (layout.Dimensions[axis] < 1)
    {
      file.Fail("raw volume dimensions must be positive");
    }
    overflow |= __builtin_mul_overflow(expected, std::uint64_t(layout.Dimensions[axis]), &expected);
  }
  if (overflow || file.Size() != expected)
  {
    file.Fail("is " + std::to_string(file.Size()) + " bytes, but " +
      std::to_string(layout.Dimensions[0]) + "x" + std::to_string(layout.Dimensions[1]) + "x" +
      std::to_string(layout.Dimensions[2]) + " " + VoxelTypeName(layout.Type) + " voxels are " +
      (overflow ? std::string("more than 2^64") : std::to_string(expected)) + " bytes");
  }
  auto reader = vtkSmartPointer<vtkImageReader2>::New();
  reader->SetFileName(file.Path().c_str());
  reader->SetFileDimensionality(3);
  reader->SetHeaderSize(0);
  reader->FileLowerLeftOn(); // rows in file order; VTK's default flips y (image files top-down)
  reader->SetDataExtent(
    0, layout.Dimensions[0] - 1, 0, layout.Dimensions[1] - 1, 0, layout.Dimensions[2] - 1);
  reader->SetDataScalarType(VtkScalarType(layout.Type));
  reader->SetNumberOfScalarComponents(1);
  reader->SetDataSpacing(layout.Spacing.data());
  reader->SetDataOrigin(layout.Origin.data());
  if (layout.BigEndian)
  {
    reader->SetDataByteOrderToBigEndian();
  }
  else
  {
    reader->SetDataByteOrderToLittleEndian();
  }
  return reader;
}
} // namespace

const char* VoxelTypeName(VoxelType type)
{
  switch (type)
  {
    case VoxelType::UInt8:
      return "uint8";
    case VoxelType::Int16:
      return "int16";
    case VoxelType::UInt16:
      return "uint16";
    case VoxelType::Float32:
      return "float32";
  }
  return "?";
}

bool ParseVoxelType(const std::string& name, VoxelType& type)
{
  for (VoxelType candidate :
    { VoxelType::UInt8, VoxelType::Int16, VoxelType::UInt16, VoxelType::Float32 })
  {
    if (name == VoxelTypeName(candidate))
    {
      type = candidate;
      return true;
    }
  }
  return false;
}

bool IsVolumeFileName(const std::string& path)
{
  return IsNiftiFileName(path) || EndsWith(Lowercase(path), ".vti");
}

VolumeSlabReader VolumeSlabReader::Open(const std::string& path, const RawVolumeLayout* raw)
{
  const InputFile file(path); // missing or unreadable files get our message, not VTK's
  if (raw)
  {
    return VolumeSlabReader(OpenRaw(file, *raw), path);
  }
  if (IsNiftiFileName(path))
  {
    const std::string problem = NiftiHeaderProblem(path);
    if (!problem.empty())
    {
      file.Fail(problem);
    }
    auto reader = vtkSmartPointer<vtkNIFTIImageReader>::New();
    reader->SetFileName(path.c_str());
    VolumeSlabReader volume(reader, path);
    volume.MirroredSlices = reader->GetQFac() < 0;
    if (reader->GetRescaleSlope() != 0) // 0: no scaling (NIfTI-1)
    {
      volume.Slope = reader->GetRescaleSlope();
      volume.Intercept = reader->GetRescaleIntercept();
    }
    if (!std::isfinite(volume.Slope) || !std::isfinite(volume.Intercept))
    {
      std::ostringstream message;
      message << "its NIfTI value scaling is not finite (scl_slope " << volume.Slope << ", scl_inter "
              << volume.Intercept << ")";
      file.Fail(message.str());
    }
    return volume;
  }
  if (EndsWith(Lowercase(path), ".vti"))
  {
    auto reader = vtkSmartPointer<vtkXMLImageDataReader>::New();
    reader->SetFileName(path.c_str());
    VolumeSlabReader volume(reader, path);
    CheckVtkXmlFile(reader, file);
    return volume;
  }
  file.Fail("not a volume file (expected .nii, .nii.gz or .vti, or a raw file with its "
            "dimensions and voxel type)");
}

VolumeSlabReader::VolumeSlabReader(vtkAlgorithm* source, const std::string& name)
  : Source(source)
  , Errors(vtkSmartPointer<VtkErrorCollector>::New())
  , SourceName(name)
{
  // The executive repeats a failed reader's error less helpfully: keep it off the console too.
  this->Source->AddObserver(vtkCommand::ErrorEvent, this->Errors);
  this->Source->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, this->Errors);
  if (auto* xml = vtkXMLReader::SafeDownCast(source))
  {
    xml->SetParserErrorObserver(this->Errors); // malformed XML
  }
  this->Source->UpdateInformation();
  vtkInformation* info = this->Source->GetOutputInformation(0);
  if (!this->Errors->FirstError.empty() || this->Source->GetErrorCode() != 0 || !info ||
    !info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    throw InputError(name + ": not a readable volume" +
      (this->Errors->FirstError.empty() ? std::string() : ": " + this->Errors->FirstError));
  }
  info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), this->Whole.data());
}

VolumeSlabReader::~VolumeSlabReader()
{
  if (this->Source)
  {
    this->Source->RemoveObserver(this->Errors);
    this->Source->GetExecutive()->RemoveObserver(this->Errors);
  }
}

VolumeSlabReader::VolumeSlabReader(VolumeSlabReader&&) noexcept = default;

vtkSmartPointer<vtkImageData> VolumeSlabReader::ReadSlab(int firstSlice, int lastSlice)
{
  const int mirror = this->Whole[4] + this->Whole[5];
  int extent[6] = { this->Whole[0], this->Whole[1], this->Whole[2], this->Whole[3], firstSlice,
    lastSlice };
  if (this->MirroredSlices)
  {
    extent[4] = mirror - lastSlice;
    extent[5] = mirror - firstSlice;
  }
  this->Errors->FirstError.clear();
  const std::string cannotRead = this->SourceName + ": cannot read slices " +
    std::to_string(firstSlice) + " to " + std::to_string(lastSlice);
  int ok = 0;
  try
  {
    ok = this->Source->UpdateExtent(extent);
  }
  catch (const std::bad_alloc&)
  {
    // A header can declare any extent; VTK allocates what it says.
    throw InputError(cannotRead + ": not enough memory for slices of " +
      std::to_string(std::int64_t(this->Whole[1]) - this->Whole[0] + 1) + "x" +
      std::to_string(std::int64_t(this->Whole[3]) - this->Whole[2] + 1) + " voxels");
  }
  vtkImageData* output = vtkImageData::SafeDownCast(this->Source->GetOutputDataObject(0));
  if (!ok || !this->Errors->FirstError.empty() || this->Source->GetErrorCode() != 0 || !output)
  {
    throw InputError(cannotRead +
      (this->Errors->FirstError.empty() ? std::string() : ": " + this->Errors->FirstError));
  }
  const int* got = output->GetExtent();
  for (int axis = 0; axis < 3; ++axis)
  {
    if (got[2 * axis] > extent[2 * axis] || got[2 * axis + 1] < extent[2 * axis + 1])
    {
      throw InputError(this->SourceName + ": the reader gave less than the slices " +
        std::to_string(firstSlice) + " to " + std::to_string(lastSlice));
    }
  }
  auto slab = vtkSmartPointer<vtkImageData>::New();
  slab->ShallowCopy(output);
  slab->Crop(extent); // a reader that ignores update extents gives the whole volume
  if (this->MirroredSlices)
  {
    slab->SetExtent(extent[0], extent[1], extent[2], extent[3], firstSlice, lastSlice);
  }
  return slab;
}

} // namespace atp
