#include "atpStatisticsPanel.h"

#include "atpProgressReport.h"
#include "atpRenderStatistics.h"

#include <QFormLayout>
#include <QLabel>

#include <fstream>
#include <unistd.h>

namespace atp
{
namespace
{

/// Resident memory of this process (Linux: /proc/self/statm), in bytes; 0 when unknown.
double ResidentBytes()
{
  std::ifstream statm("/proc/self/statm");
  double pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * double(::sysconf(_SC_PAGESIZE));
}

QString MiB(double bytes)
{
  return QString("%1 MiB").arg(bytes / (1 << 20), 0, 'f', 1);
}

QString Count(double count)
{
  return QString::fromStdString(FormatCount(count));
}

}

StatisticsPanel::StatisticsPanel(QWidget* parent)
  : QWidget(parent)
{
  auto* form = new QFormLayout(this);
  form->setLabelAlignment(Qt::AlignLeft);
  AddRow("frameRate", tr("Frame rate"));
  AddRow("triangles", tr("Triangles"));
  AddRow("patches", tr("Patches"));
  AddRow("cacheHits", tr("Cache hits"));
  AddRow("cacheMisses", tr("Cache misses"));
  AddRow("uploads", tr("Uploads"));
  AddRow("gpuCache", tr("GPU cache"));
  AddRow("memory", tr("Process memory"));
  AddRow("converged", tr("Converged"));
}

QLabel* StatisticsPanel::AddRow(const QString& name, const QString& title)
{
  auto* value = new QLabel("-");
  value->setObjectName(name);
  value->setTextInteractionFlags(Qt::TextSelectableByMouse);
  static_cast<QFormLayout*>(layout())->addRow(title, value);
  return value;
}

QLabel* StatisticsPanel::Label(const QString& name) const
{
  return findChild<QLabel*>(name);
}

void StatisticsPanel::Show(const RenderStatistics& s, double frameSeconds)
{
  Label("frameRate")->setText(frameSeconds > 0
      ? QString("%1 fps (%2 ms)").arg(1 / frameSeconds, 0, 'f', 1).arg(frameSeconds * 1e3, 0, 'f', 1)
      : QString("-"));
  Label("triangles")->setText(Count(double(s.Triangles)));
  Label("patches")->setText(Count(double(s.Patches)));
  Label("cacheHits")->setText(Count(double(s.CacheHits)));
  Label("cacheMisses")->setText(Count(double(s.CacheMisses)));
  Label("uploads")->setText(QString("%1 (%2)").arg(Count(double(s.Uploads)), MiB(double(s.UploadBytes))));
  Label("gpuCache")->setText(QString("%1 in %2 patches (%3 buffer), %4 evictions")
                               .arg(MiB(double(s.CacheBytes)), Count(double(s.CacheEntries)),
                                 MiB(double(s.CacheBufferBytes)), Count(double(s.Evictions))));
  Label("memory")->setText(MiB(ResidentBytes()));
  Label("converged")->setText(s.Converged ? tr("yes") : tr("streaming patches..."));
}

}
