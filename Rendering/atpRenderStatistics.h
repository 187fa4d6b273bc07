// What vtkATPMapper did in its last frame, for HUDs, benchmarks and tests.
#ifndef atpRenderStatistics_h
#define atpRenderStatistics_h

#include <cstddef>
#include <cstdint>

namespace atp
{

struct RenderStatistics
{
  std::uint64_t Frame = 0;
  std::size_t Patches = 0;          ///< drawn
  std::uint64_t Triangles = 0;      ///< drawn
  std::size_t CacheHits = 0;        ///< drawn patches that were already on the GPU
  std::size_t CacheMisses = 0;      ///< patches the view needed that were not (now fetched)
  std::size_t Uploads = 0;          ///< patches uploaded this frame
  std::uint64_t UploadBytes = 0;
  std::size_t CacheEntries = 0;
  std::uint64_t CacheBytes = 0;
  std::uint64_t CacheBufferBytes = 0; ///< GPU memory the cache's buffer holds (CacheBytes and free)
  std::uint64_t Evictions = 0;      ///< since the cache was made
  std::size_t CutNodes = 0;         ///< nodes the cut visited
  double CutSeconds = 0;
  double UploadSeconds = 0;
  double DrawSeconds = 0;           ///< CPU time issuing the draw calls
  double DecodeSeconds = 0;         ///< background decoding, since the model was opened
  std::uint64_t DecodedPatches = 0; ///< since the model was opened
  std::uint64_t PrefetchPasses = 0;
  std::uint64_t PrefetchAdvisedPages = 0;
  bool Converged = false;           ///< drew the whole cut the view asks for
};

} // namespace atp

#endif
