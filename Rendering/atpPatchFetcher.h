// Decodes patches on background threads, so that the render thread never waits for the disk or
// the codec: it asks for what its cut is missing and, frame after frame, takes what is ready.
// Plain C++: no VTK, no OpenGL.
#ifndef atpPatchFetcher_h
#define atpPatchFetcher_h

#include "atpModelFile.h"
#include "atpRenderPatch.h"

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>
#include <unordered_set>
#include <vector>

namespace atp
{

class PatchFetcher
{
public:
  PatchFetcher(std::shared_ptr<const ModelFile> model, int threads);
  ~PatchFetcher();
  PatchFetcher(const PatchFetcher&) = delete;
  PatchFetcher& operator=(const PatchFetcher&) = delete;

  /// Replaces the patches still waiting with `nodes`, decoded in that order. Patches being
  /// decoded, or decoded and not taken yet, are not asked for twice.
  void Request(const std::vector<std::uint32_t>& nodes);
  /// Moves out decoded patches, oldest first, until `maxBytes` is reached (always at least one
  /// when any is ready). Corrupt patches come out too, with their Error set.
  void TakeFinished(std::size_t maxBytes, std::vector<RenderPatch>& out);
  /// Decodes on the calling thread (checksum first): for the few patches a first frame cannot
  /// be drawn without.
  RenderPatch DecodeNow(std::uint32_t node) const;

  /// Totals since construction: patches decoded and seconds the threads spent decoding.
  std::uint64_t DecodedPatches() const;
  double DecodeSeconds() const;

private:
  void Work();

  std::shared_ptr<const ModelFile> Model;
  mutable std::mutex Mutex;
  std::condition_variable Wake;
  std::deque<std::uint32_t> Queue;
  std::unordered_set<std::uint32_t> Busy; ///< being decoded, or decoded and not taken
  std::deque<RenderPatch> Finished;
  std::uint64_t Decoded = 0;
  double Seconds = 0;
  bool Stopping = false;
  std::vector<std::thread> Threads;
};

} // namespace atp

#endif
