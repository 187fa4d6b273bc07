// Speculative prefetching (paper, section 4): a background thread runs the same cut for the
// camera predicted half a second ahead (linear prediction from the last two observed views)
// and asks the kernel to read ahead the file pages its patches live in when they are not in
// memory (mincore, then madvise(MADV_WILLNEED)). It never touches the render thread's state:
// the render thread only posts views. Plain C++: no VTK, no OpenGL.
#ifndef atpPrefetcher_h
#define atpPrefetcher_h

#include "atpCut.h"

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>

namespace atp
{

class Prefetcher
{
public:
  Prefetcher(std::shared_ptr<const ModelFile> model, std::shared_ptr<const CutIndex> index,
    double lookAheadSeconds = 0.5);
  ~Prefetcher();
  Prefetcher(const Prefetcher&) = delete;
  Prefetcher& operator=(const Prefetcher&) = delete;

  /// The view being drawn, at `seconds` on any steady clock. Returns at once.
  void Observe(const ViewPoint& view, double errorScale, double seconds);

  /// Where the last prediction put the eye (for tests and statistics).
  void LastPredictedEye(double eye[3]) const;
  /// Totals: prediction passes run, and pages found missing and advised.
  std::uint64_t Passes() const;
  std::uint64_t AdvisedPages() const;
  /// Blocks until every view observed so far has been handled (tests, benchmarks).
  void Wait() const;

private:
  void Run();
  void Advise(const std::vector<std::uint32_t>& nodes);

  std::shared_ptr<const ModelFile> Model;
  CutSelector Selector;
  CutResult Cut;
  const double LookAhead;

  mutable std::mutex Mutex;
  mutable std::condition_variable Changed;
  bool Stopping = false;
  bool HasNew = false;
  bool Busy = false;
  ViewPoint Latest, Previous;
  double LatestSeconds = 0, PreviousSeconds = 0;
  bool HasLatest = false;
  bool HasPrevious = false;
  double Scale = 1;
  double PredictedEye[3] = { 0, 0, 0 };
  ViewPoint LastPredicted; ///< of the last pass, to skip passes that would repeat it
  double LastScale = 0;
  std::uint64_t PassCount = 0;
  std::uint64_t Advised = 0;
  std::thread Thread;
};

} // namespace atp

#endif
