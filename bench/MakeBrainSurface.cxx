// Writes the brain isosurface benchmark mesh: the MRI volume ch2better.nii.gz (mricron-data),
// resampled (2x by default) and contoured at 60, as binary PLY. At 2x this is the
// 9.1M-triangle real-world surface the construction and rendering figures are quoted on.
// The contour is the builder's own (ContourSlabs, the volume input of atp build): the
// resampled volume streams through it a slab at a time, and its vertices are welded.
#include "atpSlabContour.h"
#include "atpTriangleSource.h"
#include "atpVolumeSlabs.h"

#include "vtkCellArray.h"
#include "vtkImageResample.h"
#include "vtkNIFTIImageReader.h"
#include "vtkNew.h"
#include "vtkPLYWriter.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <cstdio>
#include <cstdlib>
#include <string>

namespace
{
/// Collects the welded surface into a vtkPolyData for VTK's PLY writer.
class PolyDataSink : public atp::ContourSink
{
public:
  void AddVertices(const float* xyz, std::size_t count) override
  {
    for (std::size_t i = 0; i < count; ++i)
    {
      this->Points->InsertNextPoint(xyz + 3 * i);
    }
  }
  void AddTriangles(const std::uint32_t* corners, std::size_t count) override
  {
    for (std::size_t i = 0; i < count; ++i)
    {
      const vtkIdType triangle[3] = { corners[3 * i], corners[3 * i + 1], corners[3 * i + 2] };
      this->Triangles->InsertNextCell(3, triangle);
    }
  }
  vtkNew<vtkPoints> Points;
  vtkNew<vtkCellArray> Triangles;
};
}

int main(int argc, char** argv)
{
  if (argc < 2)
  {
    std::fprintf(stderr,
      "usage: atp-bench-brain-surface OUT.ply [RESAMPLE=2] [ISO=60] [VOLUME=%s]\n",
      "/usr/share/mricron/templates/ch2better.nii.gz");
    return 2;
  }
  const double resample = argc > 2 ? std::atof(argv[2]) : 2.0;
  const double iso = argc > 3 ? std::atof(argv[3]) : 60.0;
  const std::string volume = argc > 4 ? argv[4] : "/usr/share/mricron/templates/ch2better.nii.gz";

  vtkNew<vtkNIFTIImageReader> reader;
  reader->SetFileName(volume.c_str());
  vtkNew<vtkImageResample> resampler;
  resampler->SetInputConnection(reader->GetOutputPort());
  for (int axis = 0; axis < 3; ++axis)
  {
    resampler->SetAxisMagnificationFactor(axis, resample);
  }
  resampler->SetInterpolationModeToLinear();
  PolyDataSink sink;
  atp::SlabContourStats stats;
  try
  {
    atp::VolumeSlabReader slabs(resampler, volume);
    stats = atp::ContourSlabs(slabs, iso, atp::DefaultSlabSlices, sink);
  }
  catch (const atp::InputError& e)
  {
    std::fprintf(stderr, "atp-bench-brain-surface: %s\n", e.what());
    return 1;
  }
  vtkNew<vtkPolyData> surface;
  surface->SetPoints(sink.Points);
  surface->SetPolys(sink.Triangles);
  vtkNew<vtkPLYWriter> writer;
  writer->SetInputData(surface);
  writer->SetFileName(argv[1]);
  writer->SetFileTypeToBinary();
  if (writer->Write() != 1)
  {
    std::fprintf(stderr, "atp-bench-brain-surface: cannot write %s\n", argv[1]);
    return 1;
  }
  std::printf("wrote %s: %llu triangles, %llu vertices (resample %g, iso %g, %dx%dx%d voxels in "
              "%d slabs)\n",
    argv[1], static_cast<unsigned long long>(stats.Triangles),
    static_cast<unsigned long long>(stats.Vertices), resample, iso, stats.Dimensions[0],
    stats.Dimensions[1], stats.Dimensions[2], stats.Slabs);
  return 0;
}
