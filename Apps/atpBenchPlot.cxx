#include "atpBenchPlot.h"

#include "atpFlythrough.h"
#include "atpOffscreenWindow.h"
#include "atpWindowImage.h"

#include "vtkAxis.h"
#include "vtkChartLegend.h"
#include "vtkChartMatrix.h"
#include "vtkChartXY.h"
#include "vtkDataArray.h"
#include "vtkContextScene.h"
#include "vtkContextView.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPlot.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTable.h"
#include "vtkTextProperty.h"
#include "vtkVector.h"

#include <algorithm>
#include <functional>
#include <string>

namespace atp
{

namespace
{
void AddColumn(vtkTable* table, const char* name, std::size_t rows,
  const std::function<double(std::size_t)>& value)
{
  vtkNew<vtkDoubleArray> column;
  column->SetName(name);
  column->SetNumberOfValues(vtkIdType(rows));
  for (std::size_t i = 0; i < rows; ++i)
  {
    column->SetValue(vtkIdType(i), value(i));
  }
  table->AddColumn(column);
}

struct Line
{
  const char* Column;
  unsigned char Color[3];
};

/// A chart of `lines` over the frames, its value axis from zero to the highest value, or to
/// `cap` when that is lower.
void Chart(vtkChartXY* chart, vtkTable* table, const char* title, std::vector<Line> lines,
  double cap = 0)
{
  chart->SetTitle(title);
  chart->GetTitleProperties()->SetFontSize(14);
  chart->GetAxis(vtkAxis::BOTTOM)->SetTitle("frame");
  chart->GetAxis(vtkAxis::LEFT)->SetTitle("");
  chart->SetShowLegend(lines.size() > 1);
  chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
  chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
  double highest = 1; // an all-zero line still gets an axis
  for (const Line& line : lines)
  {
    vtkPlot* plot = chart->AddPlot(vtkChart::LINE);
    plot->SetInputData(table, "frame", line.Column);
    plot->SetColor(line.Color[0], line.Color[1], line.Color[2], 255);
    plot->SetWidth(1.5);
    highest = std::max(
      highest, vtkDataArray::SafeDownCast(table->GetColumnByName(line.Column))->GetRange()[1]);
  }
  // Quantities read from zero, as in the paper's plots, and the frames span the width.
  vtkAxis* left = chart->GetAxis(vtkAxis::LEFT);
  left->SetBehavior(vtkAxis::FIXED);
  left->SetRange(0, 1.05 * (cap > 0 ? std::min(cap, highest) : highest));
  if (highest >= 1e5)
  {
    left->SetNotation(vtkAxis::FIXED_NOTATION); // millions of triangles without exponents
    left->SetPrecision(0);
  }
  vtkAxis* bottom = chart->GetAxis(vtkAxis::BOTTOM);
  bottom->SetBehavior(vtkAxis::FIXED);
  bottom->SetRange(0, std::max(1.0, double(table->GetNumberOfRows() - 1)));
}
} // namespace

vtkSmartPointer<vtkImageData> PlotFlythrough(const std::vector<double>& seconds,
  const std::vector<RenderStatistics>& statistics, const std::vector<double>& fullSeconds,
  int width, int height)
{
  const std::size_t frames = seconds.size();
  vtkNew<vtkTable> table;
  AddColumn(table, "frame", frames, [](std::size_t f) { return double(f); });
  AddColumn(table, "atp", frames, [&](std::size_t f) { return 1e3 * seconds[f]; });
  if (!fullSeconds.empty())
  {
    AddColumn(table, "full resolution", frames, [&](std::size_t f) { return 1e3 * fullSeconds[f]; });
  }
  AddColumn(table, "triangles", frames, [&](std::size_t f) { return double(statistics[f].Triangles); });
  AddColumn(table, "patches", frames, [&](std::size_t f) { return double(statistics[f].Patches); });
  AddColumn(table, "misses", frames, [&](std::size_t f) { return double(statistics[f].CacheMisses); });
  AddColumn(table, "uploads", frames, [&](std::size_t f) { return double(statistics[f].Uploads); });

  vtkNew<vtkContextView> view;
  view->SetRenderWindow(NewOffscreenWindow(width, height));
  view->GetRenderer()->SetBackground(1, 1, 1);
  vtkNew<vtkChartMatrix> matrix;
  view->GetScene()->AddItem(matrix);
  matrix->SetSize(vtkVector2i(1, 4));
  // Room for the axis labels of millions of triangles, and between a chart's "frame" and the
  // title of the chart below.
  matrix->SetGutter(vtkVector2f(30, 70));
  matrix->SetBorders(80, 40, 20, 30);
  // Row 0 is the bottom chart.
  const auto chart = [&](int fromTop) {
    return vtkChartXY::SafeDownCast(matrix->GetChart(vtkVector2i(0, 3 - fromTop)));
  };
  const unsigned char blue[3] = { 31, 119, 180 }, orange[3] = { 255, 127, 14 },
                      green[3] = { 44, 160, 44 }, red[3] = { 214, 39, 40 },
                      purple[3] = { 148, 103, 189 };
  std::vector<Line> times = { { "atp", { blue[0], blue[1], blue[2] } } };
  if (!fullSeconds.empty())
  {
    times.push_back({ "full resolution", { orange[0], orange[1], orange[2] } });
  }
  // The first frames upload what the path starts with, and can take a hundred times the steady
  // frame (4.5 s against 90 ms for 108M triangles on a GPU): the axis stops at twice the
  // slower mapper's 95th percentile, so that the steady frames show.
  double p95 = Percentile(seconds, 0.95);
  if (!fullSeconds.empty())
  {
    p95 = std::max(p95, Percentile(fullSeconds, 0.95));
  }
  const double cap = 2e3 * p95;
  const bool capped = 1e3 * std::max(Percentile(seconds, 1.0), Percentile(fullSeconds, 1.0)) > cap;
  Chart(chart(0), table, capped ? "frame time (ms; the first frames go off the chart)" : "frame time (ms)",
    times, cap);
  Chart(chart(1), table, "triangles per frame", { { "triangles", { green[0], green[1], green[2] } } });
  Chart(chart(2), table, "patches per frame", { { "patches", { purple[0], purple[1], purple[2] } } });
  Chart(chart(3), table, "cache misses and uploads per frame",
    { { "misses", { red[0], red[1], red[2] } }, { "uploads", { blue[0], blue[1], blue[2] } } });
  view->Render();
  return CaptureWindow(view->GetRenderWindow());
}

}
