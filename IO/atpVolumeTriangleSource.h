// The isosurface of a volume as a TriangleSource: contoured slab by slab (ContourSlabs) into
// scratch arrays on disk, then read like any mesh (boundary edges, vertex normals, degenerate
// triangles dropped) by the shared triangle path. Memory holds one slab, not the volume.
#ifndef atpVolumeTriangleSource_h
#define atpVolumeTriangleSource_h

#include "atpSlabContour.h"
#include "atpTriangleSource.h"
#include "atpVolumeSlabs.h"
#include "vtkATPIOModule.h"

#include <functional>
#include <memory>
#include <string>

namespace atp
{

struct VolumeOptions
{
  double IsoValue = 0;
  int SlabSlices = DefaultSlabSlices;
  /// Set for a raw file: its layout (then the file's extension does not matter).
  bool Raw = false;
  RawVolumeLayout RawLayout;
};

/// The surface of `volume` at options.IsoValue. Contours the whole volume before returning (the
/// bounds must be known before the first triangle); `contourStats`, when given, receives the
/// figures, `progress` the fraction contoured (see ContourSlabs). Throws InputError naming the
/// volume.
VTKATPIO_EXPORT std::unique_ptr<TriangleSource> OpenVolumeTriangleSource(VolumeSlabReader& volume,
  const VolumeOptions& options, const std::string& scratchDirectory,
  SlabContourStats* contourStats = nullptr,
  const std::function<void(double)>& progress = nullptr);

/// The same for a volume file (VolumeSlabReader::Open).
VTKATPIO_EXPORT std::unique_ptr<TriangleSource> OpenVolumeTriangleSource(const std::string& path,
  const VolumeOptions& options, const std::string& scratchDirectory,
  SlabContourStats* contourStats = nullptr,
  const std::function<void(double)>& progress = nullptr);

} // namespace atp

#endif
