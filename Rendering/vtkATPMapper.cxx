#include "vtkATPMapper.h"

#include "atpBufferArena.h"
#include "atpCameraView.h"
#include "atpCut.h"
#include "atpPatchCache.h"
#include "atpPatchFetcher.h"
#include "atpPatchShaders.h"
#include "atpPrefetcher.h"
#include "atpRenderPatch.h"
#include "atpRenderStatistics.h"
#include "atpTetra.h"
#include "vtkATPModel.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkInformation.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLActor.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLCamera.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkProperty.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"
#include "vtk_glew.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <thread>

vtkStandardNewMacro(vtkATPMapper);

namespace
{
using Clock = std::chrono::steady_clock;

/// Renderers of one window take turns with the mapper: what any of the last few frames asked
/// for is still worth uploading when it arrives.
constexpr std::uint64_t RecentFrames = 4;

double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// One patch in its window's arena: its vertices, then its indices, in one range.
struct GpuPatch
{
  std::size_t Offset = 0;      ///< of its range in the arena, in bytes
  std::size_t Bytes = 0;       ///< what it asked of the arena
  GLint BaseVertex = 0;        ///< its first vertex, as a vertex index into the arena
  std::size_t IndexOffset = 0; ///< of its first index, in bytes
  GLsizei IndexCount = 0;
  GLenum IndexType = GL_UNSIGNED_SHORT;
  std::uint32_t Triangles = 0;
  std::uint64_t UploadFrame = 0; ///< the frame that uploaded it
};

/// A new buffer object of `bytes` bytes, its contents undefined; null when the GPU has no room.
vtkSmartPointer<vtkOpenGLBufferObject> NewArenaBuffer(std::size_t bytes)
{
  auto buffer = vtkSmartPointer<vtkOpenGLBufferObject>::New();
  buffer->GenerateBuffer(vtkOpenGLBufferObject::ArrayBuffer);
  buffer->Bind();
  for (int pending = 0; pending < 16 && glGetError() != GL_NO_ERROR; ++pending)
  {
    // errors of earlier calls, not this one's (bounded: a lost context repeats its error)
  }
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(bytes), nullptr, GL_STATIC_DRAW);
  if (glGetError() == GL_OUT_OF_MEMORY)
  {
    buffer->ReleaseGraphicsResources();
    return nullptr;
  }
  return buffer;
}

/// Where an arena starts: its buffer grows by doubling from here up to the cache budget, so a
/// small model holds little GPU memory.
constexpr std::size_t FirstArenaBytes = std::size_t(1) << 20;

/// What one render window holds: GPU resources live in its context. All of its patches share
/// one buffer (the arena) and one vertex layout, so a frame binds once and draws every patch
/// of an index type in one call.
struct WindowCache
{
  /// The frame that last asked for each patch: an arrival no recent frame asked for is not
  /// worth an upload (the view moved on).
  std::vector<std::uint64_t> WantedFrame;
  /// Did not fit beside what the view pins: not asked for again until the view changes
  /// (asking would only decode them again and again for nothing).
  std::vector<std::uint8_t> NoRoom;
  /// Its last frame's requests: with several windows, the fetcher decodes for all of them.
  std::vector<std::uint32_t> Wanted;
  /// Patches it asked for that arrived while another window drew: uploaded in its own context
  /// when it draws next.
  std::vector<atp::RenderPatch> Pending;
  atp::ViewPoint LastView;
  std::size_t Stride = atp::RenderPatchStride(false);
  atp::BufferArena Arena{ Stride };
  vtkSmartPointer<vtkOpenGLBufferObject> Buffer; ///< the arena on the GPU; null while empty
  vtkNew<vtkOpenGLVertexArrayObject> Layout;
  vtkShaderProgram* LayoutProgram = nullptr; ///< the program and buffer Layout was made for
  /// Finds a node's patch through a flat array: the cut's residency test costs a load or two.
  atp::PatchCache<GpuPatch> Patches{ [this](GpuPatch& p) { Arena.Free(p.Offset, p.Bytes); } };
  std::uint64_t ModelGeneration = 0;
  /// A frame's draws of each index type (16 and 32 bits): counts, index offsets, first vertices.
  struct DrawList
  {
    std::vector<GLsizei> Counts;
    std::vector<const void*> Indices;
    std::vector<GLint> BaseVertices;
  } Draws[2];

  /// Empties the cache and the arena for patches of `stride` bytes per vertex.
  void Reset(std::size_t stride)
  {
    ReleaseGraphicsResources();
    Stride = stride;
    Arena = atp::BufferArena(stride);
  }

  void ReleaseGraphicsResources()
  {
    Patches.Clear();
    if (Buffer)
    {
      Buffer->ReleaseGraphicsResources();
      Buffer = nullptr;
    }
    Layout->ReleaseGraphicsResources();
    LayoutProgram = nullptr;
    Arena.Reset(0);
  }

  /// A free range of `bytes` in the arena, growing its buffer (up to `limit` bytes) when none
  /// is left; none when it is as large as it may grow and still has no such range.
  std::optional<std::size_t> Place(std::size_t bytes, std::size_t limit)
  {
    if (std::optional<std::size_t> offset = Arena.Allocate(bytes))
    {
      return offset;
    }
    const std::size_t old = Arena.GetCapacity();
    const std::size_t wanted = std::max({ 2 * old, old + Arena.Rounded(bytes), FirstArenaBytes });
    const std::size_t capacity = std::min(wanted, limit) / Stride * Stride;
    if (capacity <= old)
    {
      return std::nullopt;
    }
    vtkSmartPointer<vtkOpenGLBufferObject> grown = NewArenaBuffer(capacity);
    if (!grown)
    {
      return std::nullopt; // the cache stays as large as it is, the picture coarser
    }
    if (Buffer)
    {
      glBindBuffer(GL_COPY_READ_BUFFER, GLuint(Buffer->GetHandle()));
      glBindBuffer(GL_COPY_WRITE_BUFFER, GLuint(grown->GetHandle()));
      glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, GLsizeiptr(old));
      Buffer->ReleaseGraphicsResources();
    }
    Buffer = grown;
    LayoutProgram = nullptr; // the layout points into the old buffer
    Arena.Grow(capacity);
    return Arena.Allocate(bytes);
  }

  /// Copies a decoded patch into the arena at `offset`.
  GpuPatch Upload(const atp::RenderPatch& patch, std::size_t offset)
  {
    GpuPatch gpu;
    gpu.Offset = offset;
    gpu.Bytes = patch.Bytes();
    gpu.BaseVertex = GLint(offset / Stride);
    gpu.IndexOffset = offset + patch.Vertices.size(); // strides are multiples of 4 bytes
    gpu.IndexCount = GLsizei(3 * patch.TriangleCount);
    gpu.IndexType = patch.ShortIndices ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT;
    gpu.Triangles = patch.TriangleCount;
    Buffer->Bind();
    glBufferSubData(GL_ARRAY_BUFFER, GLintptr(offset), GLsizeiptr(patch.Vertices.size()),
      patch.Vertices.data());
    glBufferSubData(GL_ARRAY_BUFFER, GLintptr(gpu.IndexOffset), GLsizeiptr(patch.Indices.size()),
      patch.Indices.data());
    return gpu;
  }

  /// Binds the vertex layout of the arena for `program`.
  void BindLayout(vtkShaderProgram* program, bool colors)
  {
    if (LayoutProgram != program)
    {
      Layout->ShaderProgramChanged(); // unbinds it
      Layout->Bind();
      Layout->AddAttributeArray(program, Buffer, "vertexMC", int(atp::RenderPatchPositionOffset),
        Stride, VTK_FLOAT, 3, false);
      if (program->IsAttributeUsed("normalMC")) // not by an unlit actor's shader
      {
        Layout->AddAttributeArray(program, Buffer, "normalMC", int(atp::RenderPatchNormalOffset),
          Stride, VTK_SHORT, 4, true);
      }
      if (colors && program->IsAttributeUsed("colorMC"))
      {
        Layout->AddAttributeArray(program, Buffer, "colorMC", int(atp::RenderPatchColorOffset),
          Stride, VTK_UNSIGNED_CHAR, 4, true);
      }
      LayoutProgram = program;
    }
    Layout->Bind();
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, GLuint(Buffer->GetHandle())); // part of the layout
  }
};
} // namespace

struct vtkATPMapper::Internals
{
  std::shared_ptr<const atp::ModelFile> Model;
  std::shared_ptr<const atp::ModelFile> Unusable; ///< its diamonds are not whole: reported
  std::uint64_t ModelGeneration = 0;
  std::shared_ptr<const atp::CutIndex> Index;
  std::unique_ptr<atp::CutSelector> Selector;
  std::unique_ptr<atp::PatchFetcher> Fetcher;
  std::unique_ptr<atp::Prefetcher> Prefetch;
  std::vector<std::uint8_t> Corrupt; ///< per node: never drawn
  /// Each distinct error once: a model cut short under the viewer fails every missing patch
  /// with the same message.
  std::set<std::string> ReportedErrors;
  std::map<vtkWindow*, std::unique_ptr<WindowCache>> Windows;
  atp::CutResult Cut;
  std::vector<atp::RenderPatch> Arrived;
  std::vector<std::uint32_t> Requests; ///< every window's, for the fetcher
  std::vector<std::uint8_t> Requested; ///< per node: in Requests
  atp::RenderStatistics Stats;
  Clock::time_point Start = Clock::now();
  vtkNew<vtkMatrix4x4> ModelToDevice, ModelToView;
  vtkNew<vtkMatrix3x3> NormalMatrix;

  /// A renderer the mapper drew in, watched for the start of its frames (Watch).
  struct WatchedRenderer
  {
    vtkWeakPointer<vtkRenderer> Renderer;
    unsigned long Tag = 0;
    bool DrewInLatestFrame = true;
  };
  std::vector<WatchedRenderer> Watched;
  /// What GetStatistics gives while CulledEverywhere: the last frame's, nothing drawn.
  atp::RenderStatistics CulledStats;

  /// No model, or one that cannot be drawn: nothing drawn and nothing coming, so a
  /// render-until-converged loop ends, and no figures of an earlier model linger.
  void NothingToDraw()
  {
    Stats = atp::RenderStatistics();
    Stats.Converged = true;
    Cut.Drawn.clear();
    Cut.Missing.clear();
    Cut.Held.clear();
  }

  /// Whether the latest frame of every renderer it drew in culled the model's actor (the
  /// model wholly outside their views): VTK then does not call Render, and the figures of the
  /// last frame that drew would stand for frames that draw nothing, not converged for ever.
  /// One renderer that still draws it keeps those figures: its cut is what is coming.
  bool CulledEverywhere()
  {
    Watched.erase(std::remove_if(Watched.begin(), Watched.end(),
                    [](const WatchedRenderer& w) { return !w.Renderer; }),
      Watched.end());
    return !Watched.empty() &&
      std::none_of(Watched.begin(), Watched.end(), [](const WatchedRenderer& w) { return w.DrewInLatestFrame; });
  }

  /// Watches the renderer's frames, once; notes that it draws the model in this one.
  void Watch(vtkRenderer* renderer)
  {
    for (WatchedRenderer& w : Watched)
    {
      if (w.Renderer == renderer)
      {
        w.DrewInLatestFrame = true;
        return;
      }
    }
    vtkNew<vtkCallbackCommand> starting;
    starting->SetClientData(this);
    starting->SetCallback([](vtkObject* caller, unsigned long, void* self, void*) {
      auto* renderer = static_cast<vtkRenderer*>(caller);
      if (renderer->GetSelector())
      {
        return; // a picking pass, not a frame
      }
      for (WatchedRenderer& w : static_cast<Internals*>(self)->Watched)
      {
        w.DrewInLatestFrame = w.DrewInLatestFrame && w.Renderer != renderer;
      }
    });
    Watched.push_back({ renderer, renderer->AddObserver(vtkCommand::StartEvent, starting), true });
  }

  ~Internals()
  {
    for (const WatchedRenderer& w : Watched)
    {
      if (w.Renderer)
      {
        w.Renderer->RemoveObserver(w.Tag);
      }
    }
  }

  void Reset()
  {
    Selector.reset();
    Prefetch.reset();
    Fetcher.reset();
    Index.reset();
    Model.reset();
    Corrupt.clear();
    ReportedErrors.clear();
  }
};

vtkATPMapper::vtkATPMapper()
  : Impl(new Internals)
{
}

// Windows release what they hold through ReleaseGraphicsResources before they go; buffer
// objects still alive here are deleted by their own destructors, as VTK's mappers do.
vtkATPMapper::~vtkATPMapper() = default;

void vtkATPMapper::SetTolerancePixels(double tolerance)
{
  atp::SetTolerancePixels(this, this->TolerancePixels, tolerance);
}

void vtkATPMapper::SetInputData(vtkATPModel* model)
{
  this->SetInputDataInternal(0, model);
}

vtkATPModel* vtkATPMapper::GetInput()
{
  return vtkATPModel::SafeDownCast(this->GetExecutive()->GetInputData(0, 0));
}

int vtkATPMapper::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkATPModel");
  return 1;
}

bool vtkATPMapper::GetConverged() const
{
  return this->Impl->CulledEverywhere() || this->Impl->Stats.Converged;
}

const atp::RenderStatistics& vtkATPMapper::GetStatistics() const
{
  Internals& in = *this->Impl;
  if (!in.CulledEverywhere())
  {
    return in.Stats;
  }
  in.CulledStats = in.Stats;
  in.CulledStats.Patches = 0;
  in.CulledStats.Triangles = 0;
  in.CulledStats.CacheHits = 0;
  in.CulledStats.CacheMisses = 0;
  in.CulledStats.Uploads = 0;
  in.CulledStats.UploadBytes = 0;
  in.CulledStats.CutNodes = 0;
  in.CulledStats.CutSeconds = in.CulledStats.UploadSeconds = in.CulledStats.DrawSeconds = 0;
  in.CulledStats.Converged = true;
  return in.CulledStats;
}

const std::vector<unsigned>& vtkATPMapper::GetDrawnNodes() const
{
  static const std::vector<unsigned> none;
  return this->Impl->CulledEverywhere() ? none : this->Impl->Cut.Drawn;
}

double* vtkATPMapper::GetBounds()
{
  if (this->GetNumberOfInputConnections(0) > 0)
  {
    this->GetInputAlgorithm()->Update();
  }
  vtkATPModel* input = this->GetInput();
  if (!input || !input->GetSharedModelFile())
  {
    // Renderers skip a prop without bounds, so Render would never say so.
    this->Impl->NothingToDraw();
  }
  if (input)
  {
    input->GetBounds(this->Bounds);
  }
  else
  {
    vtkMath::UninitializeBounds(this->Bounds);
  }
  return this->Bounds;
}

void vtkATPMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  const auto found = this->Impl->Windows.find(window);
  if (found != this->Impl->Windows.end())
  {
    found->second->ReleaseGraphicsResources();
    this->Impl->Windows.erase(found);
  }
  this->Modified();
}

void vtkATPMapper::Render(vtkRenderer* renderer, vtkActor* actor)
{
  Internals& in = *this->Impl;
  const Clock::time_point frameStart = Clock::now();
  in.Watch(renderer);
  if (this->GetNumberOfInputConnections(0) > 0)
  {
    this->GetInputAlgorithm()->Update();
  }
  vtkATPModel* input = this->GetInput();
  std::shared_ptr<const atp::ModelFile> model = input ? input->GetSharedModelFile() : nullptr;
  if (!model || model == in.Unusable)
  {
    in.NothingToDraw();
    if (!model)
    {
      vtkErrorMacro(<< "no model to draw: the input is empty");
    }
    return; // an unusable model was reported once
  }
  if (model != in.Model)
  {
    in.Reset();
    try
    {
      in.Index = std::make_shared<const atp::CutIndex>(*model);
    }
    catch (const std::exception& e)
    {
      in.Unusable = model;
      in.NothingToDraw();
      vtkErrorMacro(<< e.what());
      return;
    }
    in.Model = model;
    in.Corrupt.assign(model->NodeCount(), 0);
    ++in.ModelGeneration;
    in.Selector.reset(new atp::CutSelector(*model, in.Index));
    const int threads = this->DecodeThreads > 0
      ? this->DecodeThreads
      : std::max(1, int(std::thread::hardware_concurrency()) - 1);
    in.Fetcher.reset(new atp::PatchFetcher(model, threads));
    in.Stats = atp::RenderStatistics();
  }
  if (this->Prefetching && !in.Prefetch)
  {
    in.Prefetch.reset(new atp::Prefetcher(model, in.Index));
  }
  else if (!this->Prefetching)
  {
    in.Prefetch.reset();
  }

  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  std::unique_ptr<WindowCache>& slot = in.Windows[window];
  if (!slot)
  {
    slot.reset(new WindowCache);
  }
  WindowCache& cache = *slot;
  const bool colors = (model->Header().Flags & atp::ModelFlagColors) != 0;
  const std::size_t budget = std::size_t(this->CacheBudget);
  if (cache.ModelGeneration != in.ModelGeneration || budget < cache.Patches.GetBudget())
  {
    cache.Reset(atp::RenderPatchStride(colors)); // a smaller budget gives GPU memory back
    cache.WantedFrame.assign(model->NodeCount(), 0);
    cache.NoRoom.assign(model->NodeCount(), 0);
    cache.Wanted.clear();
    cache.Pending.clear();
    cache.ModelGeneration = in.ModelGeneration;
  }
  else if (budget > cache.Patches.GetBudget())
  {
    std::fill(cache.NoRoom.begin(), cache.NoRoom.end(), 0); // what did not fit may now
  }
  cache.Patches.SetBudget(budget);
  atp::RenderStatistics& stats = in.Stats;
  ++stats.Frame;
  stats.Uploads = 0;
  stats.UploadBytes = 0;

  // What the decoders finished since the last frame goes to the GPU first, so this frame's
  // cut can use it.
  const Clock::time_point uploadStart = Clock::now();
  auto store = [&](const atp::RenderPatch& patch, bool mustFit) {
    if (!patch.Error.empty())
    {
      in.Corrupt[patch.Node] = 1;
      if (in.ReportedErrors.insert(patch.Error).second)
      {
        vtkErrorMacro(<< patch.Error);
      }
      return;
    }
    if (cache.Patches.Contains(patch.Node))
    {
      return;
    }
    std::optional<std::size_t> offset;
    const std::size_t bytes = cache.Arena.Rounded(patch.Bytes());
    const auto place = [&] {
      offset = cache.Place(bytes, cache.Patches.GetBudget());
      return offset.has_value();
    };
    if (!cache.Patches.MakeRoom(bytes, place))
    {
      if (!mustFit)
      {
        cache.NoRoom[patch.Node] = 1; // the region stays coarser
        return;
      }
      offset = cache.Place(bytes, std::numeric_limits<std::size_t>::max()); // over the budget
      if (!offset)
      {
        return;
      }
    }
    cache.Patches.Insert(patch.Node, cache.Upload(patch, *offset), bytes).UploadFrame = stats.Frame;
    ++stats.Uploads;
    stats.UploadBytes += patch.Bytes();
  };
  // Still pinned by the last frame: arrivals may evict only what it neither drew nor held.
  const auto wantedBy = [&](const WindowCache& c, const atp::RenderPatch& patch) {
    return c.ModelGeneration == in.ModelGeneration && !c.WantedFrame.empty() &&
      c.WantedFrame[patch.Node] + RecentFrames >= stats.Frame;
  };
  in.Arrived.clear();
  in.Arrived.swap(cache.Pending);
  const std::size_t fresh = in.Arrived.size();
  in.Fetcher->TakeFinished(std::size_t(this->UploadBudget), in.Arrived);
  for (std::size_t i = 0; i < in.Arrived.size(); ++i)
  {
    const atp::RenderPatch& patch = in.Arrived[i];
    for (auto& [other, otherCache] : in.Windows)
    {
      if (i >= fresh && otherCache.get() != &cache && patch.Error.empty() &&
        wantedBy(*otherCache, patch))
      {
        otherCache->Pending.push_back(patch);
      }
    }
    if (wantedBy(cache, patch) || !patch.Error.empty())
    {
      store(patch, false);
    }
  }
  cache.Patches.NewFrame();

  int width = 0, height = 0, x0 = 0, y0 = 0;
  renderer->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  vtkCamera* camera = renderer->GetActiveCamera();
  const atp::ViewPoint view = atp::ViewFromCamera(camera, width, height,
    actor->GetIsIdentity() ? nullptr : actor->GetMatrix(), this->TolerancePixels,
    this->BackfaceCulling);
  const double errorScale = model->Header().ErrorScale;
  if (!atp::SameView(view, cache.LastView))
  {
    std::fill(cache.NoRoom.begin(), cache.NoRoom.end(), 0); // what fits may have changed
    cache.LastView = view;
  }
  const atp::ResidentFunction resident = [&](std::uint32_t node) {
    return cache.Patches.Contains(node) || model->Node(node).TriangleCount == 0;
  };
  const Clock::time_point cutStart = Clock::now();
  in.Selector->Select(view, errorScale, resident, in.Cut);
  // The roots are all there is to fall back on: the first frame decodes them itself.
  bool rootsLoaded = false;
  for (const std::uint32_t node : in.Cut.Missing)
  {
    if (node < atp::RootCount && !in.Corrupt[node])
    {
      store(in.Fetcher->DecodeNow(node), true);
      rootsLoaded = true;
    }
  }
  if (rootsLoaded)
  {
    in.Selector->Select(view, errorScale, resident, in.Cut);
  }
  stats.CutSeconds = SecondsSince(cutStart);
  cache.Wanted.clear();
  for (const std::uint32_t node : in.Cut.Missing)
  {
    if (!in.Corrupt[node] && !cache.NoRoom[node])
    {
      cache.Wanted.push_back(node);
      cache.WantedFrame[node] = stats.Frame;
    }
  }
  if (in.Windows.size() == 1)
  {
    in.Fetcher->Request(cache.Wanted);
  }
  else
  {
    // This window's first, then what the others asked for last and have not been handed yet,
    // each node once.
    in.Requests = cache.Wanted;
    in.Requested.assign(model->NodeCount(), 0);
    for (const std::uint32_t node : cache.Wanted)
    {
      in.Requested[node] = 1;
    }
    // A window that has not drawn since the model changed holds another model's nodes.
    const auto current = [&](const WindowCache& c) {
      return &c != &cache && c.ModelGeneration == in.ModelGeneration;
    };
    for (const auto& [other, otherCache] : in.Windows)
    {
      for (std::size_t i = 0; current(*otherCache) && i < otherCache->Pending.size(); ++i)
      {
        in.Requested[otherCache->Pending[i].Node] = 1;
      }
    }
    for (const auto& [other, otherCache] : in.Windows)
    {
      if (current(*otherCache))
      {
        for (const std::uint32_t node : otherCache->Wanted)
        {
          if (!in.Requested[node])
          {
            in.Requested[node] = 1;
            in.Requests.push_back(node);
          }
        }
      }
    }
    in.Fetcher->Request(in.Requests);
  }
  for (const std::uint32_t node : in.Cut.Held)
  {
    cache.Patches.Use(node);
  }
  stats.UploadSeconds = SecondsSince(uploadStart) - stats.CutSeconds;

  // Draw.
  const Clock::time_point drawStart = Clock::now();
  auto* openGLRenderer = vtkOpenGLRenderer::SafeDownCast(renderer);
  vtkProperty* property = actor->GetProperty();
  const int complexity = property->GetLighting() ? openGLRenderer->GetLightingComplexity() : 0;
  const int lights = openGLRenderer->GetLightingCount();
  const std::string vertexShader = atp::PatchVertexShader(colors);
  const std::string fragmentShader = atp::PatchFragmentShader(colors, complexity, lights,
    complexity > 0 ? openGLRenderer->GetLightingUniforms() : "");
  vtkShaderProgram* program = window->GetShaderCache()->ReadyShaderProgram(
    vertexShader.c_str(), fragmentShader.c_str(), "");
  if (!program)
  {
    vtkErrorMacro(<< "the patch shaders did not compile");
    return;
  }
  if (complexity > 0)
  {
    openGLRenderer->UpdateLightingUniforms(program);
  }

  vtkMatrix4x4 *worldToView, *viewToDevice, *worldToDevice;
  vtkMatrix3x3* worldNormals;
  static_cast<vtkOpenGLCamera*>(camera)->GetKeyMatrices(
    renderer, worldToView, worldNormals, viewToDevice, worldToDevice);
  if (actor->GetIsIdentity())
  {
    program->SetUniformMatrix("MCDCMatrix", worldToDevice);
    program->SetUniformMatrix("MCVCMatrix", worldToView);
    program->SetUniformMatrix("normalMatrix", worldNormals);
  }
  else
  {
    vtkMatrix4x4* modelToWorld;
    vtkMatrix3x3* modelNormals;
    static_cast<vtkOpenGLActor*>(actor)->GetKeyMatrices(modelToWorld, modelNormals);
    vtkMatrix4x4::Multiply4x4(modelToWorld, worldToDevice, in.ModelToDevice);
    vtkMatrix4x4::Multiply4x4(modelToWorld, worldToView, in.ModelToView);
    vtkMatrix3x3::Multiply3x3(modelNormals, worldNormals, in.NormalMatrix);
    program->SetUniformMatrix("MCDCMatrix", in.ModelToDevice);
    program->SetUniformMatrix("MCVCMatrix", in.ModelToView);
    program->SetUniformMatrix("normalMatrix", in.NormalMatrix);
  }
  const double opacity = property->GetOpacity();
  program->SetUniform3f("ambientColorUniform", property->GetAmbientColor());
  program->SetUniform3f("diffuseColorUniform", property->GetDiffuseColor());
  program->SetUniform3f("specularColorUniform", property->GetSpecularColor());
  program->SetUniformf("ambientIntensity", float(property->GetAmbient()));
  program->SetUniformf("diffuseIntensity", float(property->GetDiffuse()));
  program->SetUniformf("specularIntensity", float(property->GetSpecular()));
  program->SetUniformf("specularPower", float(property->GetSpecularPower()));
  program->SetUniformf("opacityUniform", float(opacity));
  const int colorSource = this->PatchColoring ? 2 : (colors && this->ScalarVisibility ? 1 : 0);
  program->SetUniformi("colorSource", colorSource);

  const int representation = property->GetRepresentation();
  if (representation != VTK_SURFACE)
  {
    glPolygonMode(GL_FRONT_AND_BACK, representation == VTK_WIREFRAME ? GL_LINE : GL_POINT);
  }
  stats.Patches = 0;
  stats.Triangles = 0;
  stats.CacheHits = 0;
  for (WindowCache::DrawList& list : cache.Draws)
  {
    list.Counts.clear();
    list.Indices.clear();
    list.BaseVertices.clear();
  }
  if (cache.Buffer)
  {
    cache.BindLayout(program, colors);
  }
  for (const std::uint32_t node : in.Cut.Drawn)
  {
    const GpuPatch* gpu = cache.Patches.Use(node);
    if (!gpu)
    {
      continue; // cannot happen: the cut draws resident patches only
    }
    const auto indices = reinterpret_cast<const void*>(gpu->IndexOffset);
    if (this->PatchColoring)
    {
      float rgb[3];
      atp::PatchColor(node, rgb);
      program->SetUniform3f("patchColor", rgb);
      glDrawElementsBaseVertex(GL_TRIANGLES, gpu->IndexCount, gpu->IndexType,
        const_cast<void*>(indices), gpu->BaseVertex);
    }
    else
    {
      WindowCache::DrawList& list = cache.Draws[gpu->IndexType == GL_UNSIGNED_INT];
      list.Counts.push_back(gpu->IndexCount);
      list.Indices.push_back(indices);
      list.BaseVertices.push_back(gpu->BaseVertex);
    }
    ++stats.Patches;
    stats.Triangles += gpu->Triangles;
    stats.CacheHits += gpu->UploadFrame != stats.Frame;
  }
  const GLenum indexTypes[2] = { GL_UNSIGNED_SHORT, GL_UNSIGNED_INT };
  for (int type = 0; type < 2; ++type)
  {
    WindowCache::DrawList& list = cache.Draws[type];
    if (!list.Counts.empty())
    {
      glMultiDrawElementsBaseVertex(GL_TRIANGLES, list.Counts.data(), indexTypes[type],
        const_cast<void**>(list.Indices.data()), GLsizei(list.Counts.size()),
        list.BaseVertices.data());
    }
  }
  if (cache.Buffer)
  {
    cache.Layout->Release();
  }
  if (representation != VTK_SURFACE)
  {
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  }
  stats.DrawSeconds = SecondsSince(drawStart);

  stats.CacheMisses = in.Cut.Missing.size();
  stats.CacheEntries = cache.Patches.GetCount();
  stats.CacheBytes = cache.Patches.GetBytes();
  stats.CacheBufferBytes = cache.Arena.GetCapacity();
  stats.Evictions = cache.Patches.GetEvictions();
  stats.CutNodes = in.Cut.Visited;
  stats.DecodeSeconds = in.Fetcher->DecodeSeconds();
  stats.DecodedPatches = in.Fetcher->DecodedPatches();
  // Corrupt patches are never coming, and those without room wait for the view to change or
  // the budget to grow.
  stats.Converged = cache.Wanted.empty();
  if (in.Prefetch)
  {
    in.Prefetch->Observe(view, errorScale, SecondsSince(in.Start));
    stats.PrefetchPasses = in.Prefetch->Passes();
    stats.PrefetchAdvisedPages = in.Prefetch->AdvisedPages();
  }
  this->TimeToDraw = SecondsSince(frameStart);
}

void vtkATPMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const atp::RenderStatistics& s = this->Impl->Stats;
  os << indent << "TolerancePixels: " << this->TolerancePixels << "\n";
  os << indent << "CacheBudget: " << this->CacheBudget << "\n";
  os << indent << "UploadBudget: " << this->UploadBudget << "\n";
  os << indent << "BackfaceCulling: " << this->BackfaceCulling << "\n";
  os << indent << "Prefetching: " << this->Prefetching << "\n";
  os << indent << "PatchColoring: " << this->PatchColoring << "\n";
  os << indent << "DecodeThreads: " << this->DecodeThreads << "\n";
  os << indent << "LastFrame: " << s.Patches << " patches, " << s.Triangles << " triangles, "
     << s.Uploads << " uploads, " << s.CacheMisses << " missing, cache " << s.CacheEntries
     << " patches / " << s.CacheBytes << " bytes in a buffer of " << s.CacheBufferBytes
     << " bytes, converged " << s.Converged << "\n";
}
