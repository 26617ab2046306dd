#pragma once
// The canvas tools (Krita, Inkscape and Illustrator have the same three): what a plain
// left drag does. Draw records a stroke; Select picks strokes (click, shift+click,
// rubber band), moves them and drags the joints and control points of the selected ones;
// Pan moves the view. Space held pans in every tool, the middle button too; the older
// modifier shortcuts stay: in Draw, shift+drag pans and ctrl+drag moves a joint.

#include <QIcon>
#include <array>
#include <optional>

namespace la::gui {

enum class Tool { kDraw, kSelect, kPan };

struct ToolSpec {
  Tool tool;
  const char* name;      // the action's text
  const char* shortcut;  // one key, as the reference programs use
  const char* tip;       // what a drag does
};

inline constexpr std::array<ToolSpec, 3> kTools{{
    {Tool::kDraw, "&Draw", "B", "draw a stroke with the pen or mouse; it is fitted when the pen lifts"},
    {Tool::kSelect, "&Select / Edit", "V",
     "click a curve to select it (shift+click adds or removes), drag a box around curves, drag selected "
     "curves to move them, drag a selected curve's joints and control points to edit it"},
    {Tool::kPan, "&Pan", "H", "drag to move the view (Space held pans in every tool)"},
}};

/// The tool's button icon, drawn (no image files to ship): a pen nib, an arrow, a hand's
/// four-way cross; no tool: the construction's control triangle.
QIcon toolIcon(std::optional<Tool> tool);

}  // namespace la::gui
