// The cut's ViewPoint for a VTK camera: the one place where VTK's camera conventions (view
// angle, parallel projection, actor transforms) turn into the plain view the cut works with.
#ifndef atpCameraView_h
#define atpCameraView_h

#include "atpCut.h"
#include "vtkATPFiltersModule.h"

#include <optional>

class vtkCamera;
class vtkMatrix4x4;

namespace atp
{

/// The view of `camera` for a viewport of width x height pixels, in the model's coordinates:
/// `modelToWorld` is the actor's matrix (null: identity). The four side planes of the frustum
/// are set (near and far are left out: clipping ranges follow what is drawn, not the reverse).
VTKATPFILTERS_EXPORT ViewPoint ViewFromCamera(vtkCamera* camera, int width, int height,
  vtkMatrix4x4* modelToWorld, double tolerancePixels, bool backfaceCulling);

/// The tolerance the VTK classes use when `requested` pixels are asked for: clamped to
/// [1e-3, 1e6] pixels (finer asks for more than the finest level, coarser for less than the
/// roots); no value for NaN, which no clamp can place (every comparison of the cut would fail).
VTKATPFILTERS_EXPORT std::optional<double> UsableTolerancePixels(double requested);

} // namespace atp

#endif
