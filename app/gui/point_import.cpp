#include "app/gui/point_import.h"

#include <QEventLoop>
#include <QFileInfo>
#include <QFutureWatcher>
#include <QProgressDialog>
#include <QTimer>
#include <QtConcurrent/QtConcurrentRun>
#include <exception>

#include "app/io/point_file.h"

namespace la::gui {

ReadPointsResult readPointsOffThread(QWidget* parent, const QString& path, std::optional<WorldBox> fit_into) {
  const QFileInfo info(path);
  QProgressDialog progress(QString("Reading %1 (%2 kB)…").arg(info.fileName()).arg((info.size() + 1023) / 1024), "Cancel",
                           0, 0, parent);  // range 0..0: a busy indicator
  progress.setObjectName("import-progress");
  progress.setWindowTitle("Import points");
  progress.setWindowModality(Qt::WindowModal);  // the sketch cannot change under the import
  progress.setAutoClose(false);
  progress.setAutoReset(false);
  progress.setMinimumDuration(kShowProgressAfterMs);
  progress.setValue(0);  // (starts the dialog's own show-after-minimumDuration timer)

  QEventLoop loop;
  bool cancelled = false;
  QFutureWatcher<ReadPointsResult> watcher;
  QObject::connect(&watcher, &QFutureWatcher<ReadPointsResult>::finished, &loop, &QEventLoop::quit);
  QObject::connect(&progress, &QProgressDialog::canceled, &loop, [&] {
    cancelled = true;
    loop.quit();
  });
  // The worker holds copies only: a cancelled read may outlive this function.
  watcher.setFuture(QtConcurrent::run([file = path.toStdString(), fit_into] {
    ReadPointsResult out;
    try {
      out.strokes = readStrokes(file);
    } catch (const std::exception& e) {  // PointFileError ("file:line: what") and I/O errors
      out.error = e.what();
      return out;
    }
    if (fit_into)
      if ((out.placed = fitToView(out.strokes, *fit_into))) applySimilarity(out.strokes, *out.placed);
    out.status = ReadPointsResult::Status::kRead;
    return out;
  }));
  loop.exec();  // quit by the worker's end or by Cancel
  progress.reset();
  progress.hide();
  if (cancelled) {
    ReadPointsResult out;
    out.status = ReadPointsResult::Status::kCancelled;
    return out;  // the worker's result, whenever it comes, goes nowhere
  }
  return watcher.result();
}

}  // namespace la::gui
