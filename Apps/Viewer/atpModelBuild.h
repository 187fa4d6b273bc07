// Builds a model in a worker thread (vtkATPBuilder), behind a progress dialog that follows the
// progress events and whose Cancel button aborts the build. The input is a mesh file, streamed
// by the builder, or a volume (NIfTI .nii/.nii.gz, VTK .vti) whose isosurface is extracted
// first with flying edges (the volume is read whole).
#ifndef atpModelBuild_h
#define atpModelBuild_h

#include <QObject>
#include <QString>

#include <atomic>
#include <thread>

class QProgressDialog;
class QWidget;

namespace atp
{

class ModelBuild : public QObject
{
  Q_OBJECT

public:
  /// Starts building `input` into `model` (`isoValue` is used for volumes only, whose surface
  /// vtkATPBuilder contours slab by slab); the dialog is window-modal over `parent`.
  ModelBuild(const QString& input, double isoValue, const QString& model, QWidget* parent);
  /// Cancels a build still running and waits for it.
  ~ModelBuild() override;

signals:
  /// The build ended: `error` is empty on success, `warning` unless the build succeeded with
  /// one (vtkATPBuilder::GetWarningMessage); `cancelled` when Cancel stopped it.
  void Finished(const QString& model, const QString& error, const QString& warning, bool cancelled);

private:
  void Run(const QString& input, double isoValue, const QString& model);

  QProgressDialog* Progress;
  std::atomic<bool> Cancelled{ false };
  std::thread Worker;
};

}

#endif
