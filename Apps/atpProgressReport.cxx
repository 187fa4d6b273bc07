#include "atpProgressReport.h"

#include <cstdio>
#include <unistd.h>

namespace atp
{

ProgressReport::ProgressReport(std::string task, std::uint64_t total, std::string unit)
  : Task(std::move(task))
  , Unit(std::move(unit))
  , Total(total)
  , Terminal(::isatty(STDERR_FILENO) == 1)
  , Start(std::chrono::steady_clock::now())
{
}

std::string FormatDuration(double seconds)
{
  const long s = long(seconds + 0.5);
  char text[32];
  if (s >= 3600)
  {
    std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  }
  else
  {
    std::snprintf(text, sizeof text, "%ld:%02ld", s / 60, s % 60);
  }
  return text;
}

std::string FormatCount(double count)
{
  char text[32];
  if (count >= 1e9)
  {
    std::snprintf(text, sizeof text, "%.2fG", count / 1e9);
  }
  else if (count >= 1e6)
  {
    std::snprintf(text, sizeof text, "%.2fM", count / 1e6);
  }
  else if (count >= 1e3)
  {
    std::snprintf(text, sizeof text, "%.1fk", count / 1e3);
  }
  else
  {
    std::snprintf(text, sizeof text, "%.0f", count);
  }
  return text;
}

void ProgressReport::Update(double fraction)
{
  const double elapsed =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - Start).count();
  const std::string rate =
    Total > 0 && elapsed > 0 ? FormatCount(fraction * double(Total) / elapsed) + " " + Unit + "/s" : "";
  const std::string eta =
    fraction > 0.01 ? "ETA " + FormatDuration(elapsed * (1 - fraction) / fraction) : "ETA --:--";
  if (Terminal)
  {
    if (fraction - LastDrawn < 0.002 && fraction < 1)
    {
      return; // redraw at most every 0.2%
    }
    LastDrawn = fraction;
    constexpr int Width = 30;
    const int filled = int(fraction * Width + 0.5);
    std::fprintf(stderr, "\r%s [%.*s%*s] %5.1f%%  %s  %s  ", Task.c_str(), filled,
      "##############################", Width - filled, "", 100 * fraction, rate.c_str(),
      eta.c_str());
    std::fflush(stderr);
    return;
  }
  const int decile = int(fraction * 10 + 1e-9);
  if (decile > LastDecile)
  {
    LastDecile = decile;
    std::fprintf(stderr, "%s: %3d%%  %s  elapsed %s\n", Task.c_str(), decile * 10, rate.c_str(),
      FormatDuration(elapsed).c_str());
  }
}

void ProgressReport::Finish()
{
  if (Terminal && LastDrawn >= 0)
  {
    std::fputc('\n', stderr);
  }
}

}
