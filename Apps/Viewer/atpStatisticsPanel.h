// The viewer's live statistics: what vtkATPMapper's last frame did (patches, triangles, cache
// hits and misses, uploads, GPU cache size), the frame rate, and the process's memory.
#ifndef atpStatisticsPanel_h
#define atpStatisticsPanel_h

#include <QWidget>

class QLabel;

namespace atp
{
struct RenderStatistics;

class StatisticsPanel : public QWidget
{
  Q_OBJECT

public:
  explicit StatisticsPanel(QWidget* parent = nullptr);

  /// Shows one frame's figures; `frameSeconds` is the renderer's time for it.
  void Show(const RenderStatistics& statistics, double frameSeconds);

  /// The label named `name` ("triangles", "patches", ...), for tests.
  QLabel* Label(const QString& name) const;

private:
  QLabel* AddRow(const QString& name, const QString& title);
};

}

#endif
