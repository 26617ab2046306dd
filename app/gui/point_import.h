#pragma once
// Reading a point file off the UI thread (issue 17, part 6). la::readStrokes parses on a
// worker (QtConcurrent::run) while a local event loop runs, so the window repaints, the
// background fits land and timers fire; after kShowProgressAfterMs a window-modal
// QProgressDialog (a busy indicator: the reader reports no progress) offers Cancel, which
// drops the result: the caller leaves the document as it was. The reader cannot be
// interrupted, so a cancelled read finishes on its worker and is thrown away there.
//
// Every import goes this way, small or large: a thread hop costs well under a
// millisecond, while the file size does not tell the parse time (an SVG's flattening, a
// network drive), and one path for every import is one path tested by every import test.

#include <QString>
#include <optional>
#include <string>
#include <vector>

#include "app/gui/import_placement.h"
#include "fitting/stroke.h"

class QWidget;

namespace la::gui {

/// The progress dialog appears only for a read that takes longer than this: a quick
/// import does not flash a window (Qt's own default is 4 s, too long to look alive).
constexpr int kShowProgressAfterMs = 300;

/// What a read gives: the strokes (placed), or the reader's error ("file:line: what"),
/// or that the user cancelled. Defaults to failure.
struct ReadPointsResult {
  enum class Status { kFailed, kRead, kCancelled };
  Status status = Status::kFailed;
  std::vector<Stroke> strokes;
  std::string error;
  std::optional<Similarity> placed;  // the fit-to-view transform applied, if one was asked for
};

/// Reads `path` with la::readStrokes on a worker thread and, with `fit_into`, fits the
/// strokes into that box (import_placement.h) there too; returns when the read is done
/// or cancelled. `parent` owns the progress dialog (objectName "import-progress").
ReadPointsResult readPointsOffThread(QWidget* parent, const QString& path, std::optional<WorldBox> fit_into);

}  // namespace la::gui
