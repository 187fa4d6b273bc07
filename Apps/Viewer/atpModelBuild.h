// Builds a model from a mesh file in a worker thread (vtkATPBuilder), behind a progress dialog
// that follows the builder's progress events and whose Cancel button aborts the build.
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
  /// Starts building `mesh` into `model`; the dialog is window-modal over `parent`.
  ModelBuild(const QString& mesh, const QString& model, QWidget* parent);
  /// Cancels a build still running and waits for it.
  ~ModelBuild() override;

  QProgressDialog* Dialog() const { return Progress; }

signals:
  /// The build ended: `error` is empty on success; `cancelled` when Cancel stopped it.
  void Finished(const QString& model, const QString& error, bool cancelled);

private:
  void Run(const QString& mesh, const QString& model);

  QProgressDialog* Progress;
  std::atomic<bool> Cancelled{ false };
  std::thread Worker;
};

}

#endif
