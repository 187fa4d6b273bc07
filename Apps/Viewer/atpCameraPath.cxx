#include "atpCameraPath.h"

#include "atpCommandLine.h"

#include "vtkCamera.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace atp
{
namespace
{

void SetCamera(const CameraKeyframe& k, vtkCamera* camera)
{
  camera->SetPosition(k.Position.data());
  camera->SetFocalPoint(k.FocalPoint.data());
  camera->SetViewUp(k.ViewUp.data());
  camera->SetViewAngle(k.ViewAngle);
}

}

void CameraPath::Record(double time, vtkCamera* camera)
{
  CameraKeyframe k;
  k.Time = time;
  camera->GetPosition(k.Position.data());
  camera->GetFocalPoint(k.FocalPoint.data());
  camera->GetViewUp(k.ViewUp.data());
  k.ViewAngle = camera->GetViewAngle();
  if (!Frames.empty() && time <= Frames.back().Time)
  {
    // Two renders within the clock's resolution: the later camera wins, times stay increasing.
    k.Time = Frames.back().Time;
    Frames.back() = k;
    return;
  }
  Frames.push_back(k);
}

void CameraPath::Apply(double time, vtkCamera* camera) const
{
  if (Frames.empty())
  {
    return;
  }
  if (time <= Frames.front().Time)
  {
    SetCamera(Frames.front(), camera);
    return;
  }
  if (time >= Frames.back().Time)
  {
    SetCamera(Frames.back(), camera);
    return;
  }
  // Keyframes are recorded at every frame, so linear interpolation between the two around
  // `time` follows the flight faithfully (a spline would overshoot where the camera paused).
  std::size_t next = 1;
  while (Frames[next].Time < time)
  {
    ++next;
  }
  const CameraKeyframe& a = Frames[next - 1];
  const CameraKeyframe& b = Frames[next];
  const double t = (time - a.Time) / (b.Time - a.Time);
  const auto mix = [t](const std::array<double, 3>& u, const std::array<double, 3>& v) {
    return std::array<double, 3>{ u[0] + t * (v[0] - u[0]), u[1] + t * (v[1] - u[1]),
      u[2] + t * (v[2] - u[2]) };
  };
  CameraKeyframe k;
  k.Position = mix(a.Position, b.Position);
  k.FocalPoint = mix(a.FocalPoint, b.FocalPoint);
  k.ViewUp = mix(a.ViewUp, b.ViewUp);
  k.ViewAngle = a.ViewAngle + t * (b.ViewAngle - a.ViewAngle);
  SetCamera(k, camera);
  camera->OrthogonalizeViewUp();
}

void CameraPath::Save(const std::string& fileName) const
{
  std::ofstream out(fileName);
  out << "# atp camera path: time  position  focal point  view up  view angle\n";
  char line[512];
  for (const CameraKeyframe& k : Frames)
  {
    std::snprintf(line, sizeof line, "%.17g  %.17g %.17g %.17g  %.17g %.17g %.17g  %.17g %.17g %.17g  %.17g\n",
      k.Time, k.Position[0], k.Position[1], k.Position[2], k.FocalPoint[0], k.FocalPoint[1],
      k.FocalPoint[2], k.ViewUp[0], k.ViewUp[1], k.ViewUp[2], k.ViewAngle);
    out << line;
  }
  out.close();
  if (!out)
  {
    throw std::runtime_error(fileName + ": cannot write the camera path");
  }
}

CameraPath CameraPath::Load(const std::string& fileName)
{
  std::ifstream in(fileName);
  if (!in)
  {
    throw std::runtime_error(fileName + ": cannot open the camera path");
  }
  CameraPath path;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number)
  {
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#')
    {
      continue;
    }
    const auto fail = [&](const std::string& what) {
      return std::runtime_error(fileName + ":" + std::to_string(number) + ": " + what);
    };
    std::istringstream fields(line);
    double v[11];
    for (double& value : v)
    {
      if (!(fields >> value) || !std::isfinite(value))
      {
        throw fail("expected 11 numbers (time, position, focal point, view up, view angle)");
      }
    }
    std::string extra;
    if (fields >> extra)
    {
      throw fail("more than 11 numbers");
    }
    CameraKeyframe k;
    k.Time = v[0];
    k.Position = { v[1], v[2], v[3] };
    k.FocalPoint = { v[4], v[5], v[6] };
    k.ViewUp = { v[7], v[8], v[9] };
    k.ViewAngle = v[10];
    if (!path.Frames.empty() && k.Time <= path.Frames.back().Time)
    {
      throw fail("times must increase from line to line");
    }
    if (k.ViewAngle <= 0 || k.ViewAngle >= 180)
    {
      throw fail("the view angle must be between 0 and 180 degrees");
    }
    switch (CheckCamera(k.Position.data(), k.FocalPoint.data(), k.ViewUp.data()))
    {
      case CameraFault::None:
        break;
      case CameraFault::TooFar:
        throw fail("coordinates must lie within +-1e30");
      case CameraFault::NoDirection:
        throw fail("the position and the focal point are the same point");
      case CameraFault::UpAlongView:
        throw fail("the view up must be a direction that is not along the view direction");
    }
    path.Frames.push_back(k);
  }
  if (path.Frames.empty())
  {
    throw std::runtime_error(fileName + ": no keyframes");
  }
  // Played from its first keyframe, however late a hand-written path starts; and not for days.
  const double start = path.Frames.front().Time;
  for (CameraKeyframe& k : path.Frames)
  {
    k.Time -= start;
  }
  constexpr double LongestSeconds = 24 * 3600;
  if (path.Duration() > LongestSeconds)
  {
    throw std::runtime_error(fileName + ": the path lasts " + std::to_string(path.Duration()) +
      " seconds, more than a day");
  }
  return path;
}

}
