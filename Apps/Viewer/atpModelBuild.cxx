#include "atpModelBuild.h"

#include "atpErrorCapture.h"
#include "atpVolumeSlabs.h"
#include "vtkATPBuilder.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"

#include <QFileInfo>
#include <QProgressDialog>

namespace atp
{

ModelBuild::ModelBuild(const QString& input, double isoValue, const QString& model, QWidget* parent)
  : QObject(parent)
  , Progress(new QProgressDialog(parent))
{
  Progress->setObjectName("buildProgress");
  Progress->setWindowTitle(tr("Building %1").arg(QFileInfo(model).fileName()));
  Progress->setLabelText(tr("Reading %1").arg(QFileInfo(input).fileName()));
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
  Worker = std::thread([this, input, isoValue, model] { Run(input, isoValue, model); });
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

void ModelBuild::Run(const QString& input, double isoValue, const QString& model)
{
  // Progress events fire on this thread: the dialog is updated on the GUI thread, and a
  // cancel request goes to the algorithm from here (the builder checks it at each report).
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetClientData(this);
  onProgress->SetCallback([](vtkObject* caller, unsigned long, void* client, void* call) {
    auto* self = static_cast<ModelBuild*>(client);
    auto* running = static_cast<vtkAlgorithm*>(caller);
    if (self->Cancelled)
    {
      running->SetAbortExecute(1);
      return;
    }
    const int value = int(*static_cast<double*>(call) * 1000);
    const QString phase = tr("Building the model: %1")
                            .arg(running->GetProgressText() ? running->GetProgressText() : "");
    QMetaObject::invokeMethod(self->Progress, [dialog = self->Progress, value, phase] {
      if (!dialog->wasCanceled())
      {
        dialog->setValue(value);
        dialog->setLabelText(phase);
      }
    }, Qt::QueuedConnection);
  });

  vtkNew<vtkATPBuilder> builder;
  builder->SetFileName(model.toLocal8Bit().constData());
  const QByteArray inputName = input.toLocal8Bit();
  builder->SetInputFileName(inputName.constData());
  if (IsVolumeFileName(inputName.toStdString()))
  {
    builder->SetIsoValue(isoValue);
  }
  builder->AddObserver(vtkCommand::ProgressEvent, onProgress);
  vtkNew<vtkCallbackCommand> shownInTheWindow; // a warning goes to a message box, not stderr
  builder->AddObserver(vtkCommand::WarningEvent, shownInTheWindow);
  const ErrorCapture errors({ builder });
  const bool ok = builder->Build();
  const bool cancelled = !ok && Cancelled;
  QString error = ok ? QString()
    : QString::fromLocal8Bit(errors.Message().empty() ? builder->GetErrorMessage() : errors.Message().c_str());
  const QString warning = ok ? QString::fromLocal8Bit(builder->GetWarningMessage()) : QString();
  QMetaObject::invokeMethod(this, [this, model, error, warning, cancelled] {
    if (Worker.joinable())
    {
      Worker.join();
    }
    Progress->hide();
    emit Finished(model, error, warning, cancelled);
  }, Qt::QueuedConnection);
}

}
