// lafair: the sketching application. Draw with a pen tablet or the mouse; every stroke
// is faired into LA segments with continuous curvature when the pen lifts.

#include <QApplication>
#include <QStringList>

#include "app/gui/main_window.h"

int main(int argc, char** argv) {
  QApplication app(argc, argv);
  QApplication::setApplicationName("lafair");
  QApplication::setOrganizationName("lafair");
  la::gui::MainWindow window;
  const QStringList args = QApplication::arguments();
  for (int i = 1; i < args.size(); ++i) {  // sketches open, point files import
    if (args[i].endsWith(".lafair.json") || args[i].endsWith(".sketch.json")) window.openFile(args[i]);
    // (the sketch is empty and the view is fitted to it: no need to ask where they go)
    else window.importPoints(args[i], la::gui::ImportPlacement::kOwnCoordinates);
  }
  window.show();
  window.offerRecovery();
  return app.exec();
}
