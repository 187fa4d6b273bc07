#include "atpExtractCommand.h"

#include "atpCommandLine.h"
#include "atpModelFile.h"
#include "atpPendingFile.h"
#include "atpVtkErrorMessage.h"
#include "atpTriangleSource.h"
#include "atpFirstVtkError.h"
#include "vtkATPExtractCut.h"
#include "vtkATPModel.h"

#include "vtkCamera.h"
#include "vtkErrorCode.h"
#include "vtkNew.h"
#include "vtkPLYWriter.h"
#include "vtkPolyData.h"
#include "vtkSTLWriter.h"
#include "vtkSmartPointer.h"
#include "vtkXMLPolyDataWriter.h"
#include "vtkXMLWriter.h"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <filesystem>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <sys/statvfs.h>
#include <vector>

namespace atp
{

namespace
{
/// A writer for the format `path` names by its extension (.ply, .vtp or .stl), writing to
/// `file`.
vtkSmartPointer<vtkAlgorithm> WriterFor(const std::string& path, const std::string& file)
{
  const std::string extension = FileExtension(path);
  if (extension == ".ply")
  {
    auto ply = vtkSmartPointer<vtkPLYWriter>::New();
    ply->SetFileTypeToBinary();
    ply->SetArrayName("Colors"); // the model's vertex colors, when it has them
    ply->SetFileName(file.c_str());
    return ply;
  }
  if (extension == ".vtp")
  {
    auto vtp = vtkSmartPointer<vtkXMLPolyDataWriter>::New();
    vtp->SetFileName(file.c_str());
    return vtp;
  }
  auto stl = vtkSmartPointer<vtkSTLWriter>::New();
  stl->SetFileTypeToBinary();
  stl->SetFileName(file.c_str());
  return stl;
}
/// Faces in `file`, read back by the project's own readers (which reject truncated files) as
/// the format its extension names: VTK's PLY writer does not check its writes, so a full disk
/// would otherwise pass. Throws the reader's error. Its scratch space is the usual one
/// ($TMPDIR or /tmp), not the output's directory, which a large output may just have filled.
long long FacesIn(const std::string& file)
{
  return static_cast<long long>(OpenTriangleSource(file, "")->Stats().FacesRead);
}
} // namespace

int ExtractCommand(const std::vector<std::string>& arguments)
{
  CommandLine cl("extract",
    "Writes one level of detail of a model as an ordinary mesh: the cut a camera sees at a\n"
    "screen-space tolerance (what vtkATPMapper draws), or a whole level of the hierarchy.");
  cl.AddPositional("MODEL", "a .atp model");
  cl.AddOption("output", "o", "OUT", "the mesh to write: .ply (binary), .vtp or .stl");
  cl.AddOption("level", "", "N", "every node of level N (and the leaves above it), no camera");
  cl.AddOption("camera", "", "EX,EY,EZ,FX,FY,FZ",
    "eye and focal point (default: the whole model in view, looking down -z)");
  cl.AddOption("up", "", "UX,UY,UZ", "the camera's view up", "0,1,0");
  cl.AddOption("view-angle", "", "DEGREES", "vertical field of view", "30");
  cl.AddOption("size", "", "WxH", "viewport in pixels", "800x600");
  cl.AddOption("tolerance", "", "PX", "largest screen-space error in pixels", "1");
  cl.AddFlag("backface", "drop patches facing away from the camera (closed surfaces only)");
  cl.AddFlag("patch-ids", "add the PatchId cell array (kept by .vtp)");
  if (!cl.Parse(arguments))
  {
    return 0;
  }
  if (!cl.Has("output"))
  {
    throw UsageError("missing -o OUT");
  }
  const std::string out = cl.Get("output");
  const std::string extension = FileExtension(out);
  if (extension != ".ply" && extension != ".vtp" && extension != ".stl")
  {
    throw UsageError("-o must name a .ply, .vtp or .stl file, got '" + out + "'");
  }
  int width = 0, height = 0;
  cl.GetSize("size", width, height);
  const double tolerance = cl.GetNumber("tolerance", 1e-3, 1e6);
  const double viewAngle = cl.GetNumber("view-angle", 1, 179);
  const std::vector<double> up = cl.GetNumbers("up", 3);
  // The default camera looks down -z; a view needs a direction, and an up not along it.
  const std::vector<double> givenCamera =
    cl.Has("camera") ? cl.GetNumbers("camera", 6) : std::vector<double>{ 0, 0, 1, 0, 0, 0 };
  switch (CheckCamera(&givenCamera[0], &givenCamera[3], up.data()))
  {
    case CameraFault::None:
      break;
    case CameraFault::TooFar:
      throw UsageError("--camera: coordinates must lie within +-1e30");
    case CameraFault::NoDirection:
      throw UsageError("--camera: the eye and the focal point are the same point");
    case CameraFault::UpAlongView:
      throw UsageError("--up must be a direction that is not along the view direction");
  }

  // Written beside OUT and renamed when complete: a failed write leaves no file that looks
  // like a mesh, and an existing OUT untouched.
  PendingFile pending(out, "mesh", { cl.Positional(0) });
  const std::string& partial = pending.PartialPath();
  const vtkSmartPointer<vtkAlgorithm> writer = WriterFor(out, partial);

  auto file = std::make_shared<const ModelFile>(ModelFile::Open(cl.Positional(0)));
  const ModelHeader& h = file->Header();
  vtkNew<vtkATPModel> model;
  model->SetModelFile(file);
  vtkNew<vtkATPExtractCut> extract;
  extract->SetInputData(model);
  extract->SetPatchIds(cl.Has("patch-ids"));
  vtkNew<vtkCamera> camera;
  std::string what;
  if (cl.Has("level"))
  {
    extract->SetLevel(int(cl.GetInteger("level", 0, 60)));
    what = "level " + cl.Get("level");
  }
  else
  {
    double center[3], radius = 0;
    for (int a = 0; a < 3; ++a)
    {
      center[a] = (h.BoxMin[a] + h.BoxMax[a]) / 2;
      radius += (h.BoxMax[a] - h.BoxMin[a]) * (h.BoxMax[a] - h.BoxMin[a]) / 4;
    }
    radius = std::sqrt(radius);
    std::vector<double> eyeAndFocus = { center[0], center[1],
      center[2] + radius / std::sin(viewAngle * M_PI / 360), center[0], center[1], center[2] };
    if (cl.Has("camera"))
    {
      eyeAndFocus = givenCamera;
    }
    camera->SetPosition(eyeAndFocus[0], eyeAndFocus[1], eyeAndFocus[2]);
    camera->SetFocalPoint(eyeAndFocus[3], eyeAndFocus[4], eyeAndFocus[5]);
    camera->SetViewUp(up[0], up[1], up[2]);
    camera->SetViewAngle(viewAngle);
    extract->SetCamera(camera);
    extract->SetViewportSize(width, height);
    extract->SetTolerancePixels(tolerance);
    extract->SetBackfaceCulling(cl.Has("backface"));
    what = "the cut at " + cl.Get("tolerance") + " px for " + cl.Get("size");
  }
  FirstVtkError errors;
  errors.Watch(extract);
  extract->Update();
  if (!errors.Message.empty())
  {
    throw std::runtime_error(errors.Message);
  }

  writer->SetInputConnection(extract->GetOutputPort());
  errors.Watch(writer);
  // VTK's XML writers are not vtkWriters; both kinds have Write().
  auto* xml = vtkXMLWriter::SafeDownCast(writer);
  const int written = xml ? xml->Write() : vtkWriter::SafeDownCast(writer)->Write();
  const vtkIdType triangles = extract->GetOutput()->GetNumberOfPolys();
  const unsigned long code = writer->GetErrorCode();
  // VTK's writers report a full disk as such (STL), with a stale errno (the XML writer, which
  // deletes what it wrote and says "No such file or directory"), or not at all (PLY): a write
  // that failed where less space is free than the triangles' indices alone take was short of it.
  struct statvfs disk{};
  const std::string directory = std::filesystem::path(partial).parent_path().string();
  const bool full = ::statvfs(directory.empty() ? "." : directory.c_str(), &disk) == 0 &&
    std::uint64_t(disk.f_bavail) * disk.f_frsize < 12 * std::uint64_t(triangles);
  if (code != vtkErrorCode::NoError)
  {
    throw pending.Failure(full ? std::strerror(ENOSPC) : VtkErrorCodeText(code));
  }
  if (!written || !errors.Message.empty())
  {
    throw pending.Failure(errors.Message);
  }
  if (triangles > 0)
  {
    long long readBack = -1;
    std::string why;
    try
    {
      readBack = FacesIn(partial);
    }
    catch (const std::exception& e)
    {
      why = std::string(" (") + e.what() + ")";
    }
    if (readBack != static_cast<long long>(triangles))
    {
      throw pending.Failure(std::string(full ? std::strerror(ENOSPC) + std::string(": ") : "") +
        "the file read back is incomplete" + why);
    }
  }
  pending.Commit();
  std::printf("wrote %s: %lld triangles from %lld patches (%s)\n", out.c_str(),
    static_cast<long long>(triangles),
    static_cast<long long>(extract->GetPatchCount()), what.c_str());
  return 0;
}

} // namespace atp
