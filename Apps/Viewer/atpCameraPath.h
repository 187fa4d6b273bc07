// A camera path: keyframes recorded while a person flies around a model, saved as text and
// played back with interpolation (atp-view --record / --play).
//
// File format (".camera", UTF-8 text): one keyframe per line, eleven numbers separated by
// blanks:
//   TIME  PX PY PZ  FX FY FZ  UX UY UZ  ANGLE
// TIME in seconds from the start of the path (strictly increasing), the camera's position,
// focal point and view up, and its view angle in degrees. Blank lines and lines starting with
// '#' are ignored.
#ifndef atpCameraPath_h
#define atpCameraPath_h

#include <array>
#include <string>
#include <vector>

class vtkCamera;

namespace atp
{

struct CameraKeyframe
{
  double Time = 0;
  std::array<double, 3> Position{}, FocalPoint{}, ViewUp{};
  double ViewAngle = 30;
};

class CameraPath
{
public:
  /// Appends the camera as it is at `time` (seconds, after the last keyframe's).
  void Record(double time, vtkCamera* camera);
  /// Moves the camera to where the path is at `time`, interpolating linearly between the
  /// keyframes around it; before the first or after the last keyframe, that keyframe exactly.
  void Apply(double time, vtkCamera* camera) const;

  const std::vector<CameraKeyframe>& Keyframes() const { return Frames; }
  bool Empty() const { return Frames.empty(); }
  /// Time of the last keyframe (0 when empty).
  double Duration() const { return Frames.empty() ? 0 : Frames.back().Time; }

  /// Writes the path; throws std::runtime_error naming the file when it cannot.
  void Save(const std::string& fileName) const;
  /// Reads a path; throws std::runtime_error naming the file and line of any mistake.
  static CameraPath Load(const std::string& fileName);

private:
  std::vector<CameraKeyframe> Frames;
};

}

#endif
