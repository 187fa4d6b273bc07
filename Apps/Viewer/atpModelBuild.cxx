#include "atpModelBuild.h"

#include "vtkATPBuilder.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"

#include <QFileInfo>
#include <QProgressDialog>

namespace atp
{

ModelBuild::ModelBuild(const QString& mesh, const QString& model, QWidget* parent)
  : QObject(parent)
  , Progress(new QProgressDialog(parent))
{
  Progress->setObjectName("buildProgress");
  Progress->setWindowTitle(tr("Building %1").arg(QFileInfo(model).fileName()));
  Progress->setLabelText(tr("Reading %1").arg(QFileInfo(mesh).fileName()));
  Progress->setRange(0, 1000);
  Progress->setWindowModality(Qt::WindowModal);
  Progress->setMinimumDuration(0);
  Progress->setAutoClose(false);
  Progress->setAutoReset(false);
  connect(Progress, &QProgressDialog::canceled, this, [this] {
    Cancelled = true;
    Progress->setLabelText(tr("Cancelling..."));
  });
  Progress->show();
  Worker = std::thread([this, mesh, model] { Run(mesh, model); });
}

ModelBuild::~ModelBuild()
{
  Cancelled = true;
  if (Worker.joinable())
  {
    Worker.join();
  }
  delete Progress;
}

void ModelBuild::Run(const QString& mesh, const QString& model)
{
  vtkNew<vtkATPBuilder> builder;
  builder->SetInputFileName(mesh.toLocal8Bit().constData());
  builder->SetFileName(model.toLocal8Bit().constData());
  // The failure is reported by the dialog's owner, not also by VTK's output window.
  vtkNew<vtkCallbackCommand> quiet;
  builder->AddObserver(vtkCommand::ErrorEvent, quiet);
  // Progress events fire on this thread: the dialog is updated on the GUI thread, and the
  // cancel request goes to the builder from here, where it checks it.
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetClientData(this);
  onProgress->SetCallback([](vtkObject* caller, unsigned long, void* client, void* call) {
    auto* self = static_cast<ModelBuild*>(client);
    auto* running = static_cast<vtkATPBuilder*>(caller);
    if (self->Cancelled)
    {
      running->SetAbortExecute(1);
      return;
    }
    const int value = int(*static_cast<double*>(call) * 1000);
    const QString phase = running->GetProgressText() ? running->GetProgressText() : "";
    QMetaObject::invokeMethod(self->Progress, [dialog = self->Progress, value, phase] {
      if (!dialog->wasCanceled())
      {
        dialog->setValue(value);
        dialog->setLabelText(tr("Building the model: %1").arg(phase));
      }
    }, Qt::QueuedConnection);
  });
  builder->AddObserver(vtkCommand::ProgressEvent, onProgress);

  const bool ok = builder->Build();
  const QString error = ok ? QString() : QString::fromLocal8Bit(builder->GetErrorMessage());
  const bool cancelled = !ok && Cancelled;
  QMetaObject::invokeMethod(this, [this, model, error, cancelled] {
    if (Worker.joinable())
    {
      Worker.join();
    }
    Progress->hide();
    emit Finished(model, error, cancelled);
  }, Qt::QueuedConnection);
}

}
