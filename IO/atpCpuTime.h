// CPU time of the calling thread and of the whole process, for the build's report of where its
// time went. Plain C++ over POSIX clocks, header only.
#ifndef atpCpuTime_h
#define atpCpuTime_h

#include <ctime>

namespace atp
{

namespace detail
{

inline double ClockSeconds(clockid_t clock)
{
  timespec now{};
  ::clock_gettime(clock, &now);
  return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
}

} // namespace detail

/// CPU seconds the calling thread has used: a step timed with it on a worker thread is not
/// charged for the time other threads ran meanwhile.
inline double ThreadCpuSeconds()
{
  return detail::ClockSeconds(CLOCK_THREAD_CPUTIME_ID);
}

/// CPU seconds the process has used, all threads together.
inline double ProcessCpuSeconds()
{
  return detail::ClockSeconds(CLOCK_PROCESS_CPUTIME_ID);
}

/// Adds the calling thread's CPU time between laps to counters: `Lap(total)` adds the time
/// since the last lap (or since construction) to total.
class ThreadCpuLap
{
public:
  ThreadCpuLap()
    : Last(ThreadCpuSeconds())
  {
  }
  void Lap(double& total)
  {
    const double now = ThreadCpuSeconds();
    total += now - Last;
    Last = now;
  }

private:
  double Last;
};

} // namespace atp

#endif
