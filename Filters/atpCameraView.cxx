#include "atpCameraView.h"

#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObject.h"

#include <algorithm>
#include <cmath>

namespace atp
{
namespace
{
/// The largest singular value of the 3 x 3 matrix `l` (row-major): the square root of the
/// largest eigenvalue of l^T l, in closed form (symmetric 3 x 3, trigonometric).
double LargestStretch(const double l[9])
{
  double a[3][3];
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      a[i][j] = l[i] * l[j] + l[3 + i] * l[3 + j] + l[6 + i] * l[6 + j];
    }
  }
  const double offDiagonal = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
  double largest = std::max({ a[0][0], a[1][1], a[2][2] });
  if (offDiagonal > 0)
  {
    const double q = (a[0][0] + a[1][1] + a[2][2]) / 3;
    const double p = std::sqrt(((a[0][0] - q) * (a[0][0] - q) + (a[1][1] - q) * (a[1][1] - q) +
                                 (a[2][2] - q) * (a[2][2] - q) + 2 * offDiagonal) / 6);
    double b[3][3];
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        b[i][j] = (a[i][j] - (i == j ? q : 0)) / p;
      }
    }
    const double halfDeterminant = (b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1]) -
                                     b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0]) +
                                     b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0])) / 2;
    const double angle = std::acos(std::clamp(halfDeterminant, -1.0, 1.0)) / 3;
    largest = std::max(largest, q + 2 * p * std::cos(angle));
  }
  // Rounding may fall short of the exact value by a few ulps: the measure must not.
  return std::sqrt(largest) * (1 + 1e-12);
}
} // namespace

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
  vtkMatrix4x4* projection = camera->GetProjectionTransformMatrix(aspect, -1, 1);
  // Vertical scale of the projection: 1 / tan(half view angle), or 1 / parallel scale.
  const double yScale = projection->GetElement(1, 1);
  if (modelToWorld)
  {
    for (int row = 0; row < 3; ++row)
    {
      for (int column = 0; column < 3; ++column)
      {
        view.Linear[3 * row + column] = modelToWorld->GetElement(row, column);
      }
    }
    view.Stretch = LargestStretch(view.Linear);
  }
  double position[4] = { 0, 0, 0, 1 };
  camera->GetPosition(position);
  worldToModel->MultiplyPoint(position, position);
  std::copy(position, position + 3, view.Eye);
  // Orthographic when the projection does not divide by depth: a parallel camera, or an
  // explicit projection matrix without perspective.
  if (projection->GetElement(3, 2) == 0)
  {
    view.Parallel = true;
    view.ParallelScale = 1 / yScale; // in the camera's units, as errors are measured
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
