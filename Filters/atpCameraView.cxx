#include "atpCameraView.h"

#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObject.h"

#include <algorithm>
#include <cmath>

namespace atp
{

std::string CameraProblem(vtkCamera* camera)
{
  const auto finite = [](const double* values, int count) {
    return std::all_of(values, values + count, [](double x) { return std::isfinite(x); });
  };
  if (!finite(camera->GetPosition(), 3))
  {
    return "its position is not finite";
  }
  if (!finite(camera->GetFocalPoint(), 3))
  {
    return "its focal point is not finite";
  }
  if (camera->GetParallelProjection() && !camera->GetUseExplicitProjectionTransformMatrix() &&
    !(camera->GetParallelScale() > 0))
  {
    return "its parallel scale is not positive";
  }
  vtkMatrix4x4* projection = camera->GetCompositeProjectionTransformMatrix(1, -1, 1);
  if (!finite(projection->GetData(), 16))
  {
    return "its projection is not finite";
  }
  return std::string();
}

void SetTolerancePixels(vtkObject* owner, double& tolerance, double requested)
{
  if (std::isnan(requested))
  {
    vtkErrorWithObjectMacro(owner, "TolerancePixels NaN refused: it stays " << tolerance);
    return;
  }
  const double usable = std::clamp(requested, 1e-3, 1e6);
  if (usable != tolerance)
  {
    tolerance = usable;
    owner->Modified();
  }
}

ViewPoint ViewFromCamera(vtkCamera* camera, int width, int height, vtkMatrix4x4* modelToWorld,
  double tolerancePixels, bool backfaceCulling)
{
  const double aspect = double(std::max(width, 1)) / double(std::max(height, 1));
  vtkNew<vtkMatrix4x4> modelToClip, worldToModel;
  vtkMatrix4x4* worldToClip = camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
  if (modelToWorld)
  {
    vtkMatrix4x4::Multiply4x4(worldToClip, modelToWorld, modelToClip);
    vtkMatrix4x4::Invert(modelToWorld, worldToModel);
  }
  else
  {
    modelToClip->DeepCopy(worldToClip);
  }

  ViewPoint view;
  view.ViewportHeight = std::max(height, 1);
  view.TolerancePixels = tolerancePixels;
  view.BackfaceCulling = backfaceCulling;
  // Vertical scale of the projection: 1 / tan(half view angle), or 1 / parallel scale.
  const double yScale = camera->GetProjectionTransformMatrix(aspect, -1, 1)->GetElement(1, 1);
  // Uniform part of the actor's scale, to express the parallel scale in model units.
  const double modelScale = modelToWorld ? std::cbrt(std::abs(modelToWorld->Determinant())) : 1.0;
  double position[4] = { 0, 0, 0, 1 };
  camera->GetPosition(position);
  worldToModel->MultiplyPoint(position, position);
  std::copy(position, position + 3, view.Eye);
  if (camera->GetParallelProjection())
  {
    view.Parallel = true;
    view.ParallelScale = 1 / (yScale * modelScale);
    double direction[4] = { 0, 0, 0, 0 };
    camera->GetDirectionOfProjection(direction);
    worldToModel->MultiplyPoint(direction, direction);
    const double length = std::sqrt(
      direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
    for (int a = 0; a < 3; ++a)
    {
      view.Direction[a] = direction[a] / length;
    }
  }
  else
  {
    view.ViewAngleDegrees = 360 / M_PI * std::atan(1 / yScale);
  }

  // Side planes from the rows of the model-to-clip matrix: w + x >= 0, w - x >= 0, and so on.
  view.PlaneCount = 4;
  for (int p = 0; p < 4; ++p)
  {
    const int row = p / 2;
    const double sign = p % 2 == 0 ? 1 : -1;
    double length = 0;
    for (int c = 0; c < 4; ++c)
    {
      view.Planes[p][c] = modelToClip->GetElement(3, c) + sign * modelToClip->GetElement(row, c);
      length += c < 3 ? view.Planes[p][c] * view.Planes[p][c] : 0;
    }
    length = std::sqrt(length);
    for (double& c : view.Planes[p])
    {
      c /= length;
    }
  }
  return view;
}

} // namespace atp
