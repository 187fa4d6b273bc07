// The cut's ViewPoint for a VTK camera: the one place where VTK's camera conventions (view
// angle, parallel projection, actor transforms) turn into the plain view the cut works with.
#ifndef atpCameraView_h
#define atpCameraView_h

#include "atpCut.h"
#include "vtkATPFiltersModule.h"

#include <string>

class vtkCamera;
class vtkMatrix4x4;
class vtkObject;

namespace atp
{

/// The view of `camera` for a viewport of width x height pixels, in the model's coordinates:
/// `modelToWorld` is the actor's matrix (null: identity). The four side planes of the frustum
/// are set (near and far are left out: clipping ranges follow what is drawn, not the reverse).
VTKATPFILTERS_EXPORT ViewPoint ViewFromCamera(vtkCamera* camera, int width, int height,
  vtkMatrix4x4* modelToWorld, double tolerancePixels, bool backfaceCulling);

/// Why `camera` gives no view to cut for (a position, focal point or projection that is not
/// finite, a parallel scale that is not positive), or an empty string. A cut for such a camera
/// is some arbitrary level: no error would show.
VTKATPFILTERS_EXPORT std::string CameraProblem(vtkCamera* camera);

/// The TolerancePixels setter of the VTK classes that cut (`owner`, whose member is `tolerance`):
/// `requested` clamped to [1e-3, 1e6] pixels (finer asks for more than the finest level, coarser
/// for less than the roots), `owner` Modified when that changes the value. NaN, which no clamp
/// can place (every comparison of the cut would fail), is reported as `owner`'s error and
/// leaves the tolerance as it was.
VTKATPFILTERS_EXPORT void SetTolerancePixels(vtkObject* owner, double& tolerance, double requested);

} // namespace atp

#endif
