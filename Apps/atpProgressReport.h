// Progress for the command line: a redrawn bar with rate and ETA on a terminal, a plain line
// every 10% otherwise (logs, CI), so piped output stays readable.
#ifndef atpProgressReport_h
#define atpProgressReport_h

#include <chrono>
#include <cstdint>
#include <string>

namespace atp
{

class ProgressReport
{
public:
  /// `total` work units (e.g. triangles) and their name, for the rate; 0 when unknown.
  ProgressReport(std::string task, std::uint64_t total, std::string unit);
  void Update(double fraction);
  /// For tasks whose size is known only once they start.
  void SetTotal(std::uint64_t total) { Total = total; }
  /// Names the current phase of the task.
  void SetTask(const std::string& task) { Task = task; }
  /// Ends the bar line (terminal) or prints the last line.
  void Finish();

private:
  std::string Task, Unit;
  std::uint64_t Total;
  bool Terminal;
  int LastDecile = -1;
  double LastDrawn = -1;
  std::chrono::steady_clock::time_point Start;
};

/// Seconds as "1:05" or "1:02:03".
std::string FormatDuration(double seconds);
/// 1234567 as "1.23M".
std::string FormatCount(double count);

}

#endif
