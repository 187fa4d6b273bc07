#include "atpModelBuild.h"

#include "atpErrorCapture.h"
#include "vtkATPBuilder.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkFlyingEdges3D.h"
#include "vtkNIFTIImageReader.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkXMLImageDataReader.h"

#include <QFileInfo>
#include <QProgressDialog>

namespace atp
{
namespace
{

/// A reader for the volume at `path`.
vtkSmartPointer<vtkAlgorithm> VolumeReader(const QString& path)
{
  const QByteArray name = path.toLocal8Bit();
  if (path.endsWith(".vti", Qt::CaseInsensitive))
  {
    auto reader = vtkSmartPointer<vtkXMLImageDataReader>::New();
    reader->SetFileName(name.constData());
    return reader;
  }
  auto reader = vtkSmartPointer<vtkNIFTIImageReader>::New();
  reader->SetFileName(name.constData());
  return reader;
}

}

bool ModelBuild::IsVolume(const QString& path)
{
  for (const char* suffix : { ".nii", ".nii.gz", ".vti" })
  {
    if (path.endsWith(suffix, Qt::CaseInsensitive))
    {
      return true;
    }
  }
  return false;
}

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
    const QString phase = running->IsA("vtkATPBuilder")
      ? tr("Building the model: %1").arg(running->GetProgressText() ? running->GetProgressText() : "")
      : tr("Extracting the isosurface");
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
  vtkSmartPointer<vtkAlgorithm> volume;
  vtkNew<vtkFlyingEdges3D> isosurface;
  if (IsVolume(input))
  {
    volume = VolumeReader(input);
    isosurface->SetInputConnection(volume->GetOutputPort());
    isosurface->SetValue(0, isoValue);
    isosurface->ComputeNormalsOff();
    isosurface->ComputeScalarsOff();
    builder->SetInputConnection(isosurface->GetOutputPort());
    isosurface->AddObserver(vtkCommand::ProgressEvent, onProgress);
  }
  else
  {
    builder->SetInputFileName(input.toLocal8Bit().constData());
  }
  builder->AddObserver(vtkCommand::ProgressEvent, onProgress);

  // When a volume cannot be read, its reader's message says why; the builder's would only
  // say that its input is empty.
  std::vector<vtkObject*> reporters{ builder };
  if (volume)
  {
    reporters.insert(reporters.end(),
      { volume, volume->GetExecutive(), isosurface, isosurface->GetExecutive() });
  }
  const ErrorCapture errors(reporters);
  const bool ok = builder->Build();
  const bool cancelled = !ok && Cancelled;
  QString error = ok ? QString()
    : QString::fromLocal8Bit(errors.Message().empty() ? builder->GetErrorMessage() : errors.Message().c_str());
  if (!ok && !error.contains(input))
  {
    error = input + ": " + error; // VTK's volume readers do not name the file
  }
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
