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
    /// When its latest two frames started, counted in Starts.
    std::uint64_t LatestStart = 0, PreviousStart = 0;
    /// VTK culls an actor whose bounds lie wholly outside the view, and calls no Render.
    bool DrewInLatestFrame = true;
    /// What its latest drawn frame missed and is coming (the fetcher decodes for every
    /// renderer), of the model of that generation.
    std::vector<std::uint32_t> Wanted;
    std::uint64_t ModelGeneration = 0;
  };
  std::vector<WatchedRenderer> Watched;
  std::uint64_t Starts = 0; ///< frames started by the renderers watched
  /// What GetStatistics gives: the last drawn frame's, or nothing drawn (AllCulled), and
  /// converged as Converged says.
  atp::RenderStatistics Reported;

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

  /// The renderers of the latest round of frames: those that started one since the renderer
  /// that started last had started its frame before. A loop that renders some windows over and
  /// over finds exactly the renderers those windows draw; one no longer rendered drops out.
  template <typename Visit>
  void ForEachCurrent(Visit visit)
  {
    Watched.erase(std::remove_if(Watched.begin(), Watched.end(),
                    [](const WatchedRenderer& w) { return !w.Renderer; }),
      Watched.end());
    if (Watched.empty())
    {
      return;
    }
    const auto latest = std::max_element(Watched.begin(), Watched.end(),
      [](const WatchedRenderer& a, const WatchedRenderer& b) { return a.LatestStart < b.LatestStart; });
    for (WatchedRenderer& w : Watched)
    {
      if (w.LatestStart > latest->PreviousStart)
      {
        visit(w);
      }
    }
  }

  /// Whether every renderer of the latest round culled the model's actor: nothing is on
  /// screen, and the figures of the last frame that drew must not say otherwise.
  bool AllCulled()
  {
    bool culled = !Watched.empty();
    ForEachCurrent([&](const WatchedRenderer& w) { culled = culled && !w.DrewInLatestFrame; });
    return culled;
  }

  /// Whether every renderer of the latest round has drawn all its cut asks for, or culled the
  /// model: one frame's figures say it for one renderer, and a loop over a window of two views
  /// ended while the other was still coarse.
  bool Converged()
  {
    if (Watched.empty())
    {
      return Stats.Converged;
    }
    bool converged = true;
    ForEachCurrent(
      [&](const WatchedRenderer& w) { converged = converged && !(w.DrewInLatestFrame && !w.Wanted.empty()); });
    return converged;
  }

  /// Watches the renderer's frames, once; notes that it draws the model in this one.
  WatchedRenderer& Watch(vtkRenderer* renderer)
  {
    for (WatchedRenderer& w : Watched)
    {
      if (w.Renderer == renderer)
      {
        w.DrewInLatestFrame = true;
        return w;
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
      Internals& in = *static_cast<Internals*>(self);
      ++in.Starts;
      for (WatchedRenderer& w : in.Watched)
      {
        if (w.Renderer == renderer)
        {
          w.PreviousStart = w.LatestStart;
          w.LatestStart = in.Starts;
          w.DrewInLatestFrame = false;
        }
      }
    });
    WatchedRenderer w;
    w.Renderer = renderer;
    w.Tag = renderer->AddObserver(vtkCommand::StartEvent, starting);
    w.LatestStart = ++Starts; // this frame started before the watch
    Watched.push_back(std::move(w));
    return Watched.back();
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
  return this->Impl->Converged();
}

const atp::RenderStatistics& vtkATPMapper::GetStatistics() const
{
  Internals& in = *this->Impl;
  in.Reported = in.Stats;
  if (in.AllCulled())
  {
    in.Reported.Patches = 0;
    in.Reported.Triangles = 0;
    in.Reported.CacheHits = 0;
    in.Reported.CacheMisses = 0;
    in.Reported.Uploads = 0;
    in.Reported.UploadBytes = 0;
    in.Reported.CutNodes = 0;
    in.Reported.CutSeconds = in.Reported.UploadSeconds = in.Reported.DrawSeconds = 0;
  }
  in.Reported.Converged = in.Converged();
  return in.Reported;
}

const std::vector<unsigned>& vtkATPMapper::GetDrawnNodes() const
{
  static const std::vector<unsigned> none;
  return this->Impl->AllCulled() ? none : this->Impl->Cut.Drawn;
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
  // This renderer's wish list, filled below when the frame gets that far (an early return
  // draws nothing and needs nothing).
  Internals::WatchedRenderer& watched = in.Watch(renderer);
  watched.Wanted.clear();
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
  for (const std::uint32_t node : in.Cut.Missing)
  {
    if (!in.Corrupt[node] && !cache.NoRoom[node])
    {
      watched.Wanted.push_back(node);
      cache.WantedFrame[node] = stats.Frame;
    }
  }
  watched.ModelGeneration = in.ModelGeneration;
  if (in.Watched.size() == 1)
  {
    in.Fetcher->Request(watched.Wanted);
  }
  else
  {
    // This renderer's first, then what the others asked for in their latest frames and has not
    // been handed to their windows yet, each node once: the fetcher's queue is replaced by
    // every request, and views of one window, or several windows, take turns.
    in.Requests = watched.Wanted;
    in.Requested.assign(model->NodeCount(), 0);
    for (const std::uint32_t node : watched.Wanted)
    {
      in.Requested[node] = 1;
    }
    // A window that has not drawn since the model changed holds another model's nodes.
    for (const auto& [other, otherCache] : in.Windows)
    {
      for (std::size_t i = 0; otherCache->ModelGeneration == in.ModelGeneration && i < otherCache->Pending.size(); ++i)
      {
        in.Requested[otherCache->Pending[i].Node] = 1;
      }
    }
    for (const auto& w : in.Watched)
    {
      if (w.ModelGeneration != in.ModelGeneration || !w.DrewInLatestFrame)
      {
        continue;
      }
      for (const std::uint32_t node : w.Wanted)
      {
        if (!in.Requested[node])
        {
          in.Requested[node] = 1;
          in.Requests.push_back(node);
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
  stats.Converged = watched.Wanted.empty();
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
