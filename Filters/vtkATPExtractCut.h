/**
 * @class   vtkATPExtractCut
 * @brief   one level of detail of an ATP model as ordinary vtkPolyData
 *
 * Runs the diamond cut of a vtkATPModel for a camera, a viewport size and a screen-space
 * tolerance in pixels (the cut vtkATPMapper draws, with the same frustum and optional backface
 * culling), or takes a whole level of the hierarchy (Level >= 0), and outputs the patches as
 * one welded triangle mesh with point normals, RGBA point colors when the model has them, and,
 * with PatchIds on, a cell array "PatchId" holding the node each triangle came from (the
 * paper's colored-patch view).
 *
 * A corrupt patch is reported as a VTK error naming it, and the output is empty.
 */
#ifndef vtkATPExtractCut_h
#define vtkATPExtractCut_h

#include "vtkATPFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <memory>

namespace atp
{
class CutIndex;
class ModelFile;
}
class vtkCamera;

class VTKATPFILTERS_EXPORT vtkATPExtractCut : public vtkPolyDataAlgorithm
{
public:
  static vtkATPExtractCut* New();
  vtkTypeMacro(vtkATPExtractCut, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The viewer. Without one (and with Level < 0), the finest level is extracted.
  void SetCamera(vtkCamera* camera);
  vtkGetObjectMacro(Camera, vtkCamera);

  /// Viewport in pixels (default 800 x 600). A size under 1 pixel is refused with an error and
  /// leaves the viewport as it was.
  void SetViewportSize(int width, int height);
  void SetViewportSize(const int size[2]) { this->SetViewportSize(size[0], size[1]); }
  vtkGetVector2Macro(ViewportSize, int);

  /// Largest screen-space error in pixels (default 1), clamped to [1e-3, 1e6]; NaN is refused
  /// with an error and leaves the tolerance as it was.
  void SetTolerancePixels(double tolerance);
  vtkGetMacro(TolerancePixels, double);

  /// Drop patches facing away from the camera (default off: keeps open surfaces whole).
  vtkSetMacro(BackfaceCulling, bool);
  vtkGetMacro(BackfaceCulling, bool);
  vtkBooleanMacro(BackfaceCulling, bool);

  /// Drop patches outside the camera's frustum (default on).
  vtkSetMacro(FrustumCulling, bool);
  vtkGetMacro(FrustumCulling, bool);
  vtkBooleanMacro(FrustumCulling, bool);

  /// >= 0: the cut of every node at this level (and the leaves above it) instead of the
  /// camera's. Default -1.
  vtkSetMacro(Level, int);
  vtkGetMacro(Level, int);

  /// Add the "PatchId" cell array (default off).
  vtkSetMacro(PatchIds, bool);
  vtkGetMacro(PatchIds, bool);
  vtkBooleanMacro(PatchIds, bool);

  /// Patches in the last output.
  vtkGetMacro(PatchCount, vtkIdType);

  vtkMTimeType GetMTime() override;

protected:
  vtkATPExtractCut();
  ~vtkATPExtractCut() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkCamera* Camera = nullptr;
  int ViewportSize[2] = { 800, 600 };
  double TolerancePixels = 1;
  bool BackfaceCulling = false;
  bool FrustumCulling = true;
  int Level = -1;
  bool PatchIds = false;
  vtkIdType PatchCount = 0;
  // The diamond index of the last model cut, kept while the input holds the same model: a
  // camera that moves costs a cut, not a new index.
  std::shared_ptr<const atp::ModelFile> IndexedModel;
  std::shared_ptr<const atp::CutIndex> Index;

  vtkATPExtractCut(const vtkATPExtractCut&) = delete;
  void operator=(const vtkATPExtractCut&) = delete;
};

#endif
