/**
 * @class   vtkATPMapper
 * @brief   view-dependent, out-of-core rendering of an ATP model (OpenGL2 backend)
 *
 * Draws a vtkATPModel with a plain vtkActor: every frame a stateless top-down cut of the
 * tetrahedron forest picks the patches whose saturated screen-space error is below
 * TolerancePixels, culling branches outside the view frustum (and, optionally, facing away),
 * and draws them from the mapper's own least-recently-used cache on the GPU, kept under
 * CacheBudget bytes: per render window one VTK OpenGL buffer object holding every cached
 * patch, one vertex array object and one VTK shader program, so that a frame draws all of its
 * patches with one multi-draw call per index type.
 *
 * A frame never waits for the disk: patches the cut needs and the cache lacks are decoded on
 * background threads while the frame draws the coarser resident level for that region (a
 * diamond refines only when all its children are on the GPU, so the picture stays
 * crack-free); they are uploaded at the start of later frames, at most UploadBudget bytes per
 * frame. Render again until GetConverged() is true to see the full cut of a still camera. A
 * background prefetcher runs the same cut for the camera predicted half a second ahead and
 * asks the kernel to read ahead the file pages it will need.
 *
 * Lighting follows the renderer's lights as vtkPolyDataMapper does (headlight, light kit,
 * positional and spot lights), with the actor's ambient, diffuse, specular and opacity and
 * two-sided lighting; surface, wireframe and points representations. Vertex colors of the
 * model are used when ScalarVisibility is on; PatchColoring shows one color per patch.
 * Not supported: textures, scalar mapping through lookup tables, hardware picking and
 * translucency sorting (opacity below 1 blends without depth peeling).
 *
 * Corrupt patches are reported once each as a VTK error and never drawn (the region stays at
 * the coarser level). A model file truncated or rewritten while it is drawn is reported once
 * and the view keeps what was loaded (the file is memory-mapped: no SIGBUS crash).
 */
#ifndef vtkATPMapper_h
#define vtkATPMapper_h

#include "vtkATPRenderingModule.h"
#include "vtkMapper.h"

#include <memory>
#include <vector>

namespace atp
{
struct RenderStatistics;
}
class vtkATPModel;

class VTKATPRENDERING_EXPORT vtkATPMapper : public vtkMapper
{
public:
  static vtkATPMapper* New();
  vtkTypeMacro(vtkATPMapper, vtkMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void SetInputData(vtkATPModel* model);
  vtkATPModel* GetInput();

  /// Largest screen-space error in pixels (default 1), clamped to [1e-3, 1e6]; NaN is refused
  /// with an error and leaves the tolerance as it was.
  void SetTolerancePixels(double tolerance);
  vtkGetMacro(TolerancePixels, double);

  /// GPU memory for patches, in bytes (default 512 MiB). What one frame draws is never
  /// evicted: with a budget too small for the cut, regions stay coarser.
  vtkSetClampMacro(CacheBudget, vtkTypeInt64, 0, VTK_TYPE_INT64_MAX);
  vtkGetMacro(CacheBudget, vtkTypeInt64);

  /// Bytes uploaded to the GPU per frame at most (default 64 MiB; at least one patch).
  vtkSetClampMacro(UploadBudget, vtkTypeInt64, 0, VTK_TYPE_INT64_MAX);
  vtkGetMacro(UploadBudget, vtkTypeInt64);

  /// Cull patches that face away from the camera (default off: open or two-sided surfaces
  /// need their back faces).
  vtkSetMacro(BackfaceCulling, bool);
  vtkGetMacro(BackfaceCulling, bool);
  vtkBooleanMacro(BackfaceCulling, bool);

  /// Speculative prefetching of the predicted view's file pages (default on).
  vtkSetMacro(Prefetching, bool);
  vtkGetMacro(Prefetching, bool);
  vtkBooleanMacro(Prefetching, bool);

  /// One color per patch instead of the actor's or the vertices' (default off).
  vtkSetMacro(PatchColoring, bool);
  vtkGetMacro(PatchColoring, bool);
  vtkBooleanMacro(PatchColoring, bool);

  /// Background decoding threads (default 0: one per core but one, at least one). Takes
  /// effect when the model is next opened.
  vtkSetClampMacro(DecodeThreads, int, 0, 256);
  vtkGetMacro(DecodeThreads, int);

  /// True when every renderer of the latest round of frames (each renderer the mapper drew
  /// in that started a frame since the renderer that started last had started its previous
  /// one) drew the complete cut its view asks for, or all of it that the CacheBudget holds
  /// (nothing more is coming until a view or the budget changes), or culled the actor (the
  /// model wholly outside its view: nothing drawn, nothing needed). Before the mapper first
  /// draws, false. A window captured in tiles (vtkWindowToImageFilter with a scale above 1)
  /// renders each tile once: render the zoomed view until converged instead.
  bool GetConverged() const;
  /// What the last frame that drew the model did (nothing drawn when every renderer of the
  /// latest round culled it), with Converged as GetConverged says.
  const atp::RenderStatistics& GetStatistics() const;
  /// Nodes drawn by that frame, in drawing order (for tests and tools).
  const std::vector<unsigned>& GetDrawnNodes() const;

  void Render(vtkRenderer* renderer, vtkActor* actor) override;
  double* GetBounds() override;
  void GetBounds(double bounds[6]) override { this->Superclass::GetBounds(bounds); }
  void ReleaseGraphicsResources(vtkWindow* window) override;
  bool HasOpaqueGeometry() override { return true; }
  bool HasTranslucentPolygonalGeometry() override { return false; }

protected:
  vtkATPMapper();
  ~vtkATPMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

private:
  double TolerancePixels = 1;
  vtkTypeInt64 CacheBudget = vtkTypeInt64(512) << 20;
  vtkTypeInt64 UploadBudget = vtkTypeInt64(64) << 20;
  bool BackfaceCulling = false;
  bool Prefetching = true;
  bool PatchColoring = false;
  int DecodeThreads = 0;

  struct Internals;
  std::unique_ptr<Internals> Impl;

  vtkATPMapper(const vtkATPMapper&) = delete;
  void operator=(const vtkATPMapper&) = delete;
};

#endif
