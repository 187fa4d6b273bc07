// The volume input: slab-by-slab contouring welds into the surface of one whole-volume contour
// (same vertices and triangles, watertight across seams wherever the whole surface is), raw
// files of every voxel type and byte order, NIfTI and VTI files, and a clear InputError for
// every kind of bad volume. Volumes are small fields made by the tests.
#include "atpPolyDataTriangleSource.h"
#include "atpSlabContour.h"
#include "atpTriangleSource.h"
#include "atpVolumeSlabs.h"
#include "atpVolumeTriangleSource.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkFloatArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNIFTIImageReader.h>
#include <vtkNIFTIImageWriter.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTrivialProducer.h>
#include <vtkXMLImageDataWriter.h>

#include "CompressedXmlFile.h"
#include "FileTestFixture.h"

#include "vtk_zlib.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>

namespace
{
namespace fs = std::filesystem;
using Field = std::function<double(double x, double y, double z)>;

/// An nx by ny by nz image of `field` sampled at the voxel positions, as `scalarType`.
vtkSmartPointer<vtkImageData> Sample(const std::array<int, 3>& dims, const Field& field,
  int scalarType = VTK_FLOAT, std::array<double, 3> spacing = { { 1, 1, 1 } },
  std::array<double, 3> origin = { { 0, 0, 0 } })
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(dims.data());
  image->SetSpacing(spacing.data());
  image->SetOrigin(origin.data());
  image->AllocateScalars(scalarType, 1);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  vtkIdType t = 0;
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      for (int i = 0; i < dims[0]; ++i)
      {
        scalars->SetTuple1(t++, field(i, j, k));
      }
    }
  }
  return image;
}

/// Distance from a point, in voxels: its isosurfaces are spheres.
Field Sphere(double cx, double cy, double cz)
{
  return [=](double x, double y, double z) {
    return std::sqrt((x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz));
  };
}

/// A gyroid: a surface with many handles, crossing every slab seam in many places.
double Gyroid(double x, double y, double z)
{
  const double s = 0.45;
  return std::sin(s * x) * std::cos(s * y) + std::sin(s * y) * std::cos(s * z) +
    std::sin(s * z) * std::cos(s * x);
}

/// An indexed triangle mesh and what the tests compare.
struct Surface
{
  std::vector<std::array<double, 3>> Points;
  std::vector<std::array<std::uint32_t, 3>> Triangles;

  /// Edges used by exactly one triangle, and by more than two; triangles with a repeated
  /// vertex are left out, as the builder drops them.
  std::pair<std::size_t, std::size_t> BoundaryAndNonManifoldEdges() const
  {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
    for (const auto& t : this->Triangles)
    {
      if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      {
        continue;
      }
      for (int c = 0; c < 3; ++c)
      {
        ++uses[std::minmax(t[c], t[(c + 1) % 3])];
      }
    }
    std::size_t boundary = 0, nonManifold = 0;
    for (const auto& edge : uses)
    {
      boundary += edge.second == 1;
      nonManifold += edge.second > 2;
    }
    return { boundary, nonManifold };
  }

  double Area() const
  {
    double area = 0;
    for (const auto& t : this->Triangles)
    {
      const auto &a = this->Points[t[0]], &b = this->Points[t[1]], &c = this->Points[t[2]];
      const double e[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
      const double f[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
      const double n[3] = { e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2],
        e[0] * f[1] - e[1] * f[0] };
      area += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
    return area;
  }

  std::array<double, 6> Bounds() const
  {
    std::array<double, 6> box{ { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 } };
    for (const auto& p : this->Points)
    {
      for (int a = 0; a < 3; ++a)
      {
        box[2 * a] = std::min(box[2 * a], p[a]);
        box[2 * a + 1] = std::max(box[2 * a + 1], p[a]);
      }
    }
    return box;
  }
};

/// What one whole-volume vtkFlyingEdges3D gives: the reference.
Surface WholeContour(vtkImageData* image, double iso)
{
  vtkNew<vtkFlyingEdges3D> contour;
  contour->SetInputData(image);
  contour->SetValue(0, iso);
  contour->ComputeNormalsOff();
  contour->ComputeScalarsOff();
  contour->Update();
  vtkPolyData* mesh = contour->GetOutput();
  Surface surface;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    surface.Points.push_back({ { p[0], p[1], p[2] } });
  }
  auto cells = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell())
  {
    vtkIdType size;
    const vtkIdType* ids;
    cells->GetCurrentCell(size, ids);
    surface.Triangles.push_back(
      { { std::uint32_t(ids[0]), std::uint32_t(ids[1]), std::uint32_t(ids[2]) } });
  }
  return surface;
}

/// Collects what ContourSlabs gives, checking the sink's contract on the way.
class SurfaceSink : public atp::ContourSink
{
public:
  void AddVertices(const float* xyz, std::size_t count) override
  {
    for (std::size_t i = 0; i < count; ++i)
    {
      this->Mesh.Points.push_back({ { xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2] } });
    }
  }
  void AddTriangles(const std::uint32_t* corners, std::size_t count) override
  {
    for (std::size_t i = 0; i < count; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_LT(corners[3 * i + c], this->Mesh.Points.size()) << "a vertex not yet given";
      }
      this->Mesh.Triangles.push_back({ { corners[3 * i], corners[3 * i + 1], corners[3 * i + 2] } });
    }
  }
  Surface Mesh;
};

Surface SlabContour(atp::VolumeSlabReader& volume, double iso, int slabSlices,
  atp::SlabContourStats* stats = nullptr)
{
  SurfaceSink sink;
  const atp::SlabContourStats figures = atp::ContourSlabs(volume, iso, slabSlices, sink);
  EXPECT_EQ(figures.Vertices, sink.Mesh.Points.size());
  EXPECT_EQ(figures.Triangles, sink.Mesh.Triangles.size());
  if (stats)
  {
    *stats = figures;
  }
  return sink.Mesh;
}

/// The slab contour of an in-memory image (its producer ignores update extents: the reader
/// crops), `slabSlices` at a time.
Surface SlabContour(vtkImageData* image, double iso, int slabSlices)
{
  vtkNew<vtkTrivialProducer> producer;
  producer->SetOutput(image);
  atp::VolumeSlabReader volume(producer, "image");
  return SlabContour(volume, iso, slabSlices);
}

/// `surface` with its points merged by exact float position, as ContourSlabs numbers them.
Surface WeldedByPosition(const Surface& surface)
{
  Surface welded;
  std::map<std::array<float, 3>, std::uint32_t> ids;
  std::vector<std::uint32_t> newId;
  for (const auto& p : surface.Points)
  {
    const std::array<float, 3> key{ { float(p[0]), float(p[1]), float(p[2]) } };
    const auto inserted = ids.emplace(key, std::uint32_t(welded.Points.size()));
    if (inserted.second)
    {
      welded.Points.push_back(p);
    }
    newId.push_back(inserted.first->second);
  }
  for (const auto& t : surface.Triangles)
  {
    welded.Triangles.push_back({ { newId[t[0]], newId[t[1]], newId[t[2]] } });
  }
  return welded;
}

/// `image`'s voxels with origin 0, spacing 1: the coordinates ContourSlabs welds in.
vtkSmartPointer<vtkImageData> InVoxelCoordinates(vtkImageData* image)
{
  auto copy = vtkSmartPointer<vtkImageData>::New();
  copy->SetExtent(image->GetExtent());
  copy->GetPointData()->SetScalars(image->GetPointData()->GetScalars());
  return copy;
}

/// The surface of one whole-volume contour: the same triangles, the same vertices once welded
/// by position (the same count, boundary and non-manifold edges), the same area and bounds
/// (coordinates agree to float rounding).
void ExpectWholeVolumeSurface(const Surface& slabs, vtkImageData* image, double iso,
  const std::string& what)
{
  SCOPED_TRACE(what);
  const Surface whole = WholeContour(image, iso);
  const Surface welded = WeldedByPosition(WholeContour(InVoxelCoordinates(image), iso));
  ASSERT_GT(whole.Triangles.size(), 0u);
  EXPECT_EQ(slabs.Triangles.size(), whole.Triangles.size());
  EXPECT_EQ(slabs.Points.size(), welded.Points.size());
  EXPECT_EQ(slabs.BoundaryAndNonManifoldEdges(), welded.BoundaryAndNonManifoldEdges());
  EXPECT_NEAR(slabs.Area(), whole.Area(), 1e-5 * whole.Area());
  const auto a = slabs.Bounds(), b = whole.Bounds();
  for (int i = 0; i < 6; ++i)
  {
    EXPECT_NEAR(a[i], b[i], 1e-4 * (std::abs(b[i]) + 1)) << "bound " << i;
  }
}

class VolumeSource : public FileTestFixture
{
protected:
  /// Opens `path` and contours it, expecting an InputError naming the file and `problem`.
  void ExpectError(const std::string& path, const std::string& problem, double iso = 0.5,
    const atp::RawVolumeLayout* raw = nullptr) const
  {
    try
    {
      atp::VolumeOptions options;
      options.IsoValue = iso;
      options.SlabSlices = 3;
      options.Raw = raw != nullptr;
      if (raw)
      {
        options.RawLayout = *raw;
      }
      atp::OpenVolumeTriangleSource(path, options, this->Dir.string());
      ADD_FAILURE() << path << ": no error, expected one about '" << problem << "'";
    }
    catch (const atp::InputError& error)
    {
      const std::string message = error.what();
      EXPECT_NE(message.find(fs::path(path).filename().string()), std::string::npos) << message;
      EXPECT_NE(message.find(problem), std::string::npos) << message;
    }
  }

};

// ---------------------------------------------------------------------------------------------
// Seams

TEST_F(VolumeSource, SphereCutIntoManySlabsIsClosedAndEqualsTheWholeContour)
{
  const auto image = Sample({ { 23, 20, 31 } }, Sphere(11.3, 9.6, 15.2), VTK_FLOAT,
    { { 0.5, 0.7, 0.3 } }, { { -3, 2, 1 } });
  ASSERT_EQ(WholeContour(image, 8.7).BoundaryAndNonManifoldEdges(),
    std::make_pair(std::size_t(0), std::size_t(0)));
  for (int slab : { 2, 3, 5, 8, 30, 31, 100 })
  {
    const Surface slabs = SlabContour(image, 8.7, slab);
    ExpectWholeVolumeSurface(slabs, image, 8.7, "slab " + std::to_string(slab));
    EXPECT_EQ(slabs.BoundaryAndNonManifoldEdges(), std::make_pair(std::size_t(0), std::size_t(0)))
      << "slab " << slab;
  }
}

TEST_F(VolumeSource, SurfaceCutByTheVolumeKeepsExactlyItsOwnBoundary)
{
  // A sphere larger than the volume: the whole contour is open at the volume's faces.
  const auto image = Sample({ { 18, 21, 25 } }, Sphere(9, 10, 12), VTK_FLOAT);
  ASSERT_GT(WholeContour(image, 11.5).BoundaryAndNonManifoldEdges().first, 0u);
  for (int slab : { 2, 4, 7 })
  {
    ExpectWholeVolumeSurface(SlabContour(image, 11.5, slab), image, 11.5, "slab " + std::to_string(slab));
  }
}

TEST_F(VolumeSource, GyroidWithManyHandlesAcrossEverySeam)
{
  const auto image = Sample({ { 30, 26, 34 } }, Gyroid, VTK_FLOAT);
  for (int slab : { 2, 3, 6 })
  {
    ExpectWholeVolumeSurface(SlabContour(image, 0.1, slab), image, 0.1, "slab " + std::to_string(slab));
  }
}

TEST_F(VolumeSource, StatsGiveDimensionsSlabsAndRange)
{
  const auto image = Sample({ { 5, 6, 11 } }, Sphere(2, 2.5, 5), VTK_FLOAT);
  vtkNew<vtkTrivialProducer> producer;
  producer->SetOutput(image);
  atp::VolumeSlabReader volume(producer, "image");
  atp::SlabContourStats stats;
  SlabContour(volume, 1.7, 4, &stats);
  EXPECT_EQ(stats.Dimensions, (std::array<int, 3>{ { 5, 6, 11 } }));
  EXPECT_EQ(stats.Slabs, 4); // slices 0-3, 3-6, 6-9, 9-10
  EXPECT_DOUBLE_EQ(stats.DataRange[0], 0.5);
  EXPECT_NEAR(stats.DataRange[1], std::sqrt(4 + 6.25 + 25), 1e-6); // a corner
}

TEST_F(VolumeSource, IsoValueEqualToVoxelValuesStillGivesAClosedSurface)
{
  // Integer voxels and an integer iso value: flying edges makes coincident points at every
  // voxel equal to the iso value, joined by zero-area triangles; once the builder drops those,
  // its surface is open there by vertex index, though closed by position (the boundary check
  // finds those edges shared). The volume source welds: closed by index too.
  const auto image = Sample({ { 20, 19, 22 } },
    [](double x, double y, double z) { return std::round(10 * Sphere(9.5, 9, 10.4)(x, y, z)); },
    VTK_UNSIGNED_CHAR);
  {
    vtkNew<vtkFlyingEdges3D> contour;
    contour->SetInputData(image);
    contour->SetValue(0, 70);
    contour->Update();
    auto unwelded = atp::OpenPolyDataTriangleSource(contour->GetOutput(), "flying edges");
    std::vector<atp::SoupTriangle> buffer(512);
    while (unwelded->Read(buffer.data(), buffer.size()) > 0)
    {
    }
    ASSERT_GT(unwelded->Stats().SharedOpenEdges, 0u);
    EXPECT_EQ(unwelded->Stats().BoundaryEdges, 0u);
  }
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(this->Path("exact.vti").c_str());
  ASSERT_EQ(writer->Write(), 1);
  for (int slab : { 2, 5, 30 })
  {
    atp::VolumeOptions options;
    options.IsoValue = 70;
    options.SlabSlices = slab;
    auto source = atp::OpenVolumeTriangleSource(this->Path("exact.vti"), options, this->Dir.string());
    std::vector<atp::SoupTriangle> buffer(512);
    while (source->Read(buffer.data(), buffer.size()) > 0)
    {
    }
    EXPECT_GT(source->Stats().DegenerateDropped, 0u) << "the iso value hits voxels";
    EXPECT_EQ(source->Stats().BoundaryEdges, 0u) << "slab " << slab;
    EXPECT_EQ(source->Stats().TrianglesEmitted + source->Stats().DegenerateDropped,
      WholeContour(image, 70).Triangles.size());
  }
}

TEST_F(VolumeSource, ProgressAfterEverySlabAndCancelling)
{
  const auto image = Sample({ { 8, 9, 20 } }, Sphere(4, 4, 9.5), VTK_FLOAT);
  vtkNew<vtkTrivialProducer> producer;
  producer->SetOutput(image);
  atp::VolumeSlabReader volume(producer, "image");
  SurfaceSink sink;
  std::vector<double> fractions;
  atp::ContourSlabs(volume, 3.3, 5, sink, [&](double f) { fractions.push_back(f); });
  EXPECT_EQ(fractions, (std::vector<double>{ 4.0 / 19, 8.0 / 19, 12.0 / 19, 16.0 / 19, 1.0 }));
  SurfaceSink cancelled;
  EXPECT_THROW(atp::ContourSlabs(volume, 3.3, 5, cancelled,
                 [](double f) {
                   if (f > 0.5)
                   {
                     throw std::runtime_error("cancelled");
                   }
                 }),
    std::runtime_error);
  EXPECT_LT(cancelled.Mesh.Triangles.size(), sink.Mesh.Triangles.size());
}

// ---------------------------------------------------------------------------------------------
// Files

struct RawCase
{
  atp::VoxelType Type;
  int VtkType;
  int Bytes;
  double Scale, Offset; ///< voxel value = Scale * distance + Offset
};

/// The voxels of `image` as raw bytes, x fastest, in the given byte order.
std::string RawBytes(vtkImageData* image, int bytes, bool bigEndian)
{
  const auto* data = static_cast<const char*>(image->GetScalarPointer());
  std::string out(data, std::size_t(image->GetNumberOfPoints()) * std::size_t(bytes));
  if (bigEndian)
  {
    for (std::size_t v = 0; v < out.size(); v += std::size_t(bytes))
    {
      std::reverse(out.begin() + long(v), out.begin() + long(v) + bytes);
    }
  }
  return out;
}

TEST_F(VolumeSource, RawFilesOfEveryTypeAndByteOrder)
{
  const std::array<int, 3> dims{ { 17, 14, 19 } };
  const std::array<double, 3> spacing{ { 0.25, 2, 1.5 } }, origin{ { 10, -4, 3 } };
  for (const RawCase& c : { RawCase{ atp::VoxelType::UInt8, VTK_UNSIGNED_CHAR, 1, 20, 0 },
         RawCase{ atp::VoxelType::Int16, VTK_SHORT, 2, 300, -2000 },
         RawCase{ atp::VoxelType::UInt16, VTK_UNSIGNED_SHORT, 2, 3000, 1000 },
         RawCase{ atp::VoxelType::Float32, VTK_FLOAT, 4, -0.5, 3 } })
  {
    const Field sphere = Sphere(8.2, 6.9, 9.4);
    const auto image = Sample(dims,
      [&](double x, double y, double z) { return std::round(c.Scale * sphere(x, y, z) + c.Offset); },
      c.VtkType, spacing, origin);
    const double iso = c.Scale * 5.3 + c.Offset + 0.5;
    for (bool bigEndian : { false, true })
    {
      atp::RawVolumeLayout layout;
      layout.Dimensions = dims;
      layout.Type = c.Type;
      layout.Spacing = spacing;
      layout.Origin = origin;
      layout.BigEndian = bigEndian;
      const std::string name = std::string(atp::VoxelTypeName(c.Type)) + (bigEndian ? "be" : "le");
      const std::string path = this->Write(name + ".raw", RawBytes(image, c.Bytes, bigEndian));
      atp::VolumeSlabReader volume = atp::VolumeSlabReader::Open(path, &layout);
      EXPECT_EQ(volume.WholeExtent(), (std::array<int, 6>{ { 0, 16, 0, 13, 0, 18 } }));
      ExpectWholeVolumeSurface(SlabContour(volume, iso, 4), image, iso, name);
    }
  }
}

TEST_F(VolumeSource, VoxelTypeNames)
{
  atp::VoxelType type;
  EXPECT_TRUE(atp::ParseVoxelType("int16", type));
  EXPECT_EQ(type, atp::VoxelType::Int16);
  EXPECT_FALSE(atp::ParseVoxelType("int64", type));
  EXPECT_FALSE(atp::ParseVoxelType("UINT8", type));
  EXPECT_TRUE(atp::IsVolumeFileName("a/b.NII.GZ"));
  EXPECT_TRUE(atp::IsVolumeFileName("b.vti"));
  EXPECT_FALSE(atp::IsVolumeFileName("b.nii.ply"));
  EXPECT_FALSE(atp::IsVolumeFileName("b.raw"));
}

TEST_F(VolumeSource, NiftiAndVtiFilesAsTriangleSources)
{
  const auto image = Sample({ { 21, 18, 24 } }, Sphere(10.1, 8.4, 11.9), VTK_FLOAT,
    { { 0.5, 0.5, 0.8 } });
  const Surface whole = WholeContour(image, 6.2);
  vtkNew<vtkNIFTIImageWriter> nifti;
  nifti->SetInputData(image);
  vtkNew<vtkXMLImageDataWriter> vti;
  vti->SetInputData(image);
  for (const std::string name : { "sphere.nii", "sphere.nii.gz", "sphere.vti" })
  {
    if (name == "sphere.vti")
    {
      vti->SetFileName(this->Path(name).c_str());
      ASSERT_EQ(vti->Write(), 1);
    }
    else
    {
      nifti->SetFileName(this->Path(name).c_str());
      nifti->Write();
      ASSERT_EQ(nifti->GetErrorCode(), 0u);
    }
    atp::VolumeOptions options;
    options.IsoValue = 6.2;
    options.SlabSlices = 5;
    auto source = atp::OpenVolumeTriangleSource(this->Path(name), options, this->Dir.string());
    EXPECT_EQ(source->ExpectedTriangles(), whole.Triangles.size()) << name;
    std::vector<atp::SoupTriangle> buffer(1000);
    std::uint64_t read = 0;
    while (std::size_t n = source->Read(buffer.data(), buffer.size()))
    {
      read += n;
    }
    EXPECT_EQ(read, whole.Triangles.size()) << name;
    EXPECT_EQ(source->Stats().BoundaryEdges, 0u) << name << ": closed across seams";
    EXPECT_EQ(source->Stats().VerticesRead, whole.Points.size()) << name;
    const atp::Box box = source->Bounds();
    const auto b = whole.Bounds();
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_NEAR(box.Min[a], b[2 * a], 1e-4) << name;
      EXPECT_NEAR(box.Max[a], b[2 * a + 1], 1e-4) << name;
    }
  }
}

TEST_F(VolumeSource, NiftiWithNegativeQfacGivesTheWholeVolumeSurface)
{
  // vtkNIFTIImageReader reverses the slices of each request when qfac is -1: slabs must come
  // out as parts of the whole, reversed volume. Written here with qfac -1.
  const auto image = Sample({ { 15, 16, 23 } }, [](double x, double y, double z) {
    return Sphere(7, 7.5, 6)(x, y, z) + 0.3 * z; // not symmetric along z
  });
  vtkNew<vtkNIFTIImageWriter> writer;
  writer->SetInputData(image);
  vtkNew<vtkMatrix4x4> identity; // a qform, without which the reader ignores qfac
  writer->SetQFormMatrix(identity);
  writer->SetQFac(-1);
  writer->SetFileName(this->Path("flipped.nii").c_str());
  writer->Write();
  vtkNew<vtkNIFTIImageReader> reader;
  reader->SetFileName(this->Path("flipped.nii").c_str());
  reader->Update();
  ASSERT_LT(reader->GetQFac(), 0);
  atp::VolumeSlabReader volume = atp::VolumeSlabReader::Open(this->Path("flipped.nii"));
  for (int slab : { 2, 4, 9 })
  {
    ExpectWholeVolumeSurface(
      SlabContour(volume, 5.5, slab), reader->GetOutput(), 5.5, "slab " + std::to_string(slab));
  }
}

TEST_F(VolumeSource, NiftiIsoValueAndRangeAreInRescaledValues)
{
  // scl_slope 2 and scl_inter 10: stored value 5 stands for 20.
  const auto image = Sample({ { 12, 13, 14 } }, Sphere(5.5, 6.1, 6.9), VTK_FLOAT);
  vtkNew<vtkNIFTIImageWriter> writer;
  writer->SetInputData(image);
  writer->SetRescaleSlope(2);
  writer->SetRescaleIntercept(10);
  writer->SetFileName(this->Path("scaled.nii").c_str());
  writer->Write();
  atp::VolumeSlabReader volume = atp::VolumeSlabReader::Open(this->Path("scaled.nii"));
  EXPECT_EQ(volume.ValueSlope(), 2);
  EXPECT_EQ(volume.ValueIntercept(), 10);
  atp::SlabContourStats stats;
  ExpectWholeVolumeSurface(SlabContour(volume, 20, 4, &stats), image, 5, "scaled");
  EXPECT_NEAR(stats.DataRange[0], 2 * image->GetPointData()->GetScalars()->GetRange()[0] + 10, 1e-5);
  EXPECT_NEAR(stats.DataRange[1], 2 * image->GetPointData()->GetScalars()->GetRange()[1] + 10, 1e-5);
}

// ---------------------------------------------------------------------------------------------
// Bad input

/// An ASCII .vti of 3x3x3 voxels (or `last` + 1 along each axis) whose ImageData element has
/// `attributes` and whose point data is one array of `type` holding `values`.
std::string AsciiVti(const std::string& attributes, const std::string& type, const std::string& values,
  int last = 2)
{
  const std::string n = std::to_string(last);
  const std::string extent = "\"0 " + n + " 0 " + n + " 0 " + n + "\"";
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"0.1\">\n"
         "<ImageData WholeExtent=" +
    extent + " " + attributes + ">\n<Piece Extent=" + extent + "><PointData Scalars=\"s\">"
                 "<DataArray type=\"" +
    type + "\" Name=\"s\" format=\"ascii\">" + values +
    "</DataArray></PointData></Piece></ImageData></VTKFile>\n";
}

TEST_F(VolumeSource, VtiStructureIsCheckedBeforeVtkReadsTheData)
{
  std::string voxels;
  for (int v = 0; v < 27; ++v)
  {
    voxels += v == 13 ? "1 " : "0 ";
  }
  const std::string geometry = "Origin=\"0 0 0\" Spacing=\"1 1 1\"";
  atp::VolumeOptions options;
  options.IsoValue = 0.5;
  EXPECT_GT(atp::OpenVolumeTriangleSource(this->Write("ok.vti", AsciiVti(geometry, "UInt8", voxels)),
              options, this->Dir.string())
              ->ExpectedTriangles(),
    0u);
  // VTK 9.1 crashes reading a string array as the scalars.
  this->ExpectError(this->Write("text.vti", AsciiVti(geometry, "String", voxels)),
    "its array 's' has type 'String'");
  // VTK puts an origin or spacing it cannot parse at 0 or 1 and says nothing.
  this->ExpectError(this->Write("origin.vti", AsciiVti("Origin=\"inf 0 0\" Spacing=\"1 1 1\"", "UInt8", voxels)),
    "its Origin 'inf 0 0' is not finite numbers");
  this->ExpectError(this->Write("spacing.vti", AsciiVti("Origin=\"0 0 0\" Spacing=\"1 nan 1\"", "UInt8", voxels)),
    "its Spacing '1 nan 1' is not finite numbers");
  this->ExpectError(this->Write("huge.vti", AsciiVti(geometry, "UInt8", voxels, 99999)),
    "its extent holds 1000000000000000 points, more than its");

  // A compressed array whose header claims 2^28 blocks: VTK would allocate 2 GiB for them.
  vtkNew<vtkImageData> image;
  image->SetDimensions(4, 4, 4);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(image);
  atp::testing::CompressedXmlFile written = atp::testing::WriteCompressed(writer, this->Path("good.vti"), false);
  ASSERT_NE(written.Header, std::string::npos);
  std::string& bytes = written.Bytes;
  const std::uint32_t blocks = 1u << 28;
  std::memcpy(&bytes[written.Header], &blocks, 4);
  this->ExpectError(this->Write("blocks.vti", bytes), "claims 268435456 blocks, more than the file holds");
}

TEST_F(VolumeSource, Errors)
{
  atp::RawVolumeLayout layout;
  layout.Dimensions = { { 4, 4, 4 } };
  layout.Type = atp::VoxelType::UInt16;
  this->ExpectError(this->Path("missing.nii"), "cannot open");
  this->ExpectError(this->Path("missing.raw"), "cannot open", 0.5, &layout);
  this->ExpectError(this->Write("short.raw", std::string(100, '\0')),
    "is 100 bytes, but 4x4x4 uint16 voxels are 128 bytes", 0.5, &layout);
  atp::RawVolumeLayout huge = layout;
  huge.Dimensions = { { 1 << 30, 1 << 30, 1 << 30 } };
  this->ExpectError(this->Path("short.raw"),
    "1073741824x1073741824x1073741824 uint16 voxels are more than 2^64 bytes", 0.5, &huge);
  this->ExpectError(this->Write("volume.img3", "data"), "not a volume file");
  this->ExpectError(this->Write("garbage.nii", std::string(400, 'x')), "not a NIfTI header");
  this->ExpectError(this->Write("short.nii", std::string(100, '\0')), "348 bytes or more");
  this->ExpectError(this->Write("garbage.vti", "<VTKFile type=\"ImageData\">"), "not a readable volume");

  // Iso outside the data: no surface, and the message gives the range.
  std::string ramp;
  for (int v = 0; v < 64; ++v)
  {
    const std::uint16_t value = std::uint16_t(10 * v);
    ramp.append(reinterpret_cast<const char*>(&value), 2);
  }
  const std::string rampPath = this->Write("ramp.raw", ramp);
  this->ExpectError(rampPath, "no surface at iso value 700 (the voxel values range from 0 to 630)",
    700, &layout);

  // Non-finite voxels, found in whichever slab holds them.
  layout.Type = atp::VoxelType::Float32;
  std::vector<float> voxels(64, 1.0f);
  voxels[1 + 4 * 2 + 16 * 3] = std::numeric_limits<float>::quiet_NaN();
  this->ExpectError(this->Write("nan.raw", std::string(reinterpret_cast<const char*>(voxels.data()),
                      voxels.size() * 4)),
    "voxel (1, 2, 3) is NaN", 0.5, &layout);
  voxels[1 + 4 * 2 + 16 * 3] = -std::numeric_limits<float>::infinity();
  this->ExpectError(this->Write("inf.raw", std::string(reinterpret_cast<const char*>(voxels.data()),
                      voxels.size() * 4)),
    "voxel (1, 2, 3) is infinite", 0.5, &layout);

  // Too thin to have cells.
  layout.Dimensions = { { 8, 8, 1 } };
  this->ExpectError(this->Write("flat.raw", std::string(64 * 4, '\0')),
    "at least 2 voxels along each axis, this one is 8x8x1", 0.5, &layout);

  // Color volumes cannot be contoured.
  vtkNew<vtkImageData> rgb;
  rgb->SetDimensions(4, 4, 4);
  rgb->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(rgb);
  writer->SetFileName(this->Path("rgb.vti").c_str());
  ASSERT_EQ(writer->Write(), 1);
  this->ExpectError(this->Path("rgb.vti"), "3 components per voxel");

  // A NIfTI file cut short: VTK's message, through ours.
  const auto image = Sample({ { 8, 8, 8 } }, Sphere(4, 4, 4));
  vtkNew<vtkNIFTIImageWriter> nifti;
  nifti->SetInputData(image);
  nifti->SetFileName(this->Path("whole.nii").c_str());
  nifti->Write();
  fs::copy_file(this->Path("whole.nii"), this->Path("cut.nii"));
  fs::resize_file(this->Path("cut.nii"), fs::file_size(this->Path("whole.nii")) - 600);
  this->ExpectError(this->Path("cut.nii"), "truncated", 2.5);

  // A header that declares more voxels than the file holds: VTK would allocate them (and print
  // its own error) before finding them missing.
  {
    std::ifstream in(this->Path("whole.nii"), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::int16_t widest = 32767;
    std::memcpy(&bytes[42], &widest, 2); // dim[1] and dim[2]
    std::memcpy(&bytes[44], &widest, 2);
    this->ExpectError(this->Write("wide.nii", bytes),
      "truncated: its NIfTI header declares 32767x32767x8 voxels (34357641248 bytes), more than the file holds", 2.5);
    // Compressed, the bound is what deflate can make of the file's bytes.
    gzFile gz = gzopen(this->Path("wide.nii.gz").c_str(), "wb");
    ASSERT_NE(gz, nullptr);
    ASSERT_EQ(gzwrite(gz, bytes.data(), unsigned(bytes.size())), int(bytes.size()));
    ASSERT_EQ(gzclose(gz), Z_OK);
    this->ExpectError(this->Path("wide.nii.gz"),
      "its NIfTI header declares 32767x32767x8 voxels (34357641248 bytes), more than the file can hold compressed", 2.5);
  }

  // Datatypes VTK's reader cannot take (some crash it) or that contradict the bits per voxel
  // (the NIfTI-1 header's datatype at byte 70, bitpix at 72), refused first.
  const auto patched = [&](const std::string& name, std::int16_t datatype, std::int16_t bitpix) {
    std::ifstream in(this->Path("whole.nii"), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::memcpy(&bytes[70], &datatype, 2);
    std::memcpy(&bytes[72], &bitpix, 2);
    return this->Write(name, bytes);
  };
  this->ExpectError(patched("float128.nii", 1536, 128), "NIfTI datatype 1536 is not one scalar per voxel", 2.5);
  this->ExpectError(patched("unknown.nii", 12345, 32), "NIfTI datatype 12345 is not one scalar per voxel", 2.5);
  this->ExpectError(patched("rgb.nii", 128, 24), "NIfTI datatype 128 is not one scalar per voxel", 2.5);
  this->ExpectError(patched("bits.nii", 16, 8), "datatype 16 has 32 bits per voxel, the header says 8", 2.5);
  // A header that puts the voxels inside itself (vox_offset, a float at byte 108), and value
  // scaling that is not finite (scl_slope and scl_inter, floats at bytes 112 and 116).
  const auto withFloat = [&](const std::string& name, std::size_t at, float value) {
    std::ifstream in(this->Path("whole.nii"), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::memcpy(&bytes[at], &value, 4);
    return this->Write(name, bytes);
  };
  this->ExpectError(withFloat("offset.nii", 108, 10),
    "its NIfTI header puts the voxels at byte 10, inside the header (352 bytes", 2.5);
  this->ExpectError(withFloat("offset-nan.nii", 108, std::nanf("")), "puts the voxels at byte nan", 2.5);
  this->ExpectError(withFloat("slope.nii", 112, std::nanf("")),
    "its NIfTI value scaling is not finite (scl_slope nan", 2.5);
  this->ExpectError(withFloat("intercept.nii", 116, std::numeric_limits<float>::infinity()),
    "its NIfTI value scaling is not finite (scl_slope", 2.5);
  // A big-endian header: its size, datatype, bits and voxel offset read the other way round.
  {
    std::ifstream in(this->Path("whole.nii"), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const unsigned char big[] = { 0, 0, 1, 92 /* 348 */, 6, 0 /* 1536 */, 0, 128 /* 128 */,
      0x43, 0xb0, 0, 0 /* 352.0f */ };
    std::memcpy(&bytes[0], big, 4);
    std::memcpy(&bytes[70], big + 4, 4);
    std::memcpy(&bytes[108], big + 8, 4);
    this->ExpectError(this->Write("big.nii", bytes), "NIfTI datatype 1536 is not one scalar per voxel", 2.5);
  }
}

} // namespace
