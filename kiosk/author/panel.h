#pragma once
// The authoring window's side panel as rows (no GL; panel_draw.cpp draws them):
// a toolbar, the status line, the tree of groups and their models, the add and
// remove commands, the tours and their steps, then the editors (fields.h) of
// the selection: a model's fields, its label per kiosk language and its pins, a
// group's fields, a tour's or a step's, or with nothing selected the scene's
// camera and kiosk settings. Pixels, origin top-left; the
// rows scroll as one list.
#include <string>
#include <vector>

#include "kiosk/app/ui.h"
#include "kiosk/author/fields.h"
#include "shared/scene/scene.h"

namespace body::kiosk::author {

enum class RowKind { Button, Status, Heading, TreeGroup, TreeModel, TreeTour, TreeStep, Field };

enum class Command {
    None,
    Save,
    Undo,
    Redo,
    Preview,
    StartView,
    Help,
    AddGroup,
    RemoveSelected,
    ResetTransform,
    AddModel,   // the row's field holds the path typed
    AddPin,     // at the surface point last clicked on the selected model
    RemovePin,  // the row's target.pin
    AddTour,
    AddStep,  // to the row's target.tour: the view, the visible models and the model selected
    StepUp,
    StepDown,
    Pack,        // save, then pack the bundle (Editor::pack)
    SnapToggle,  // the manipulation sphere's snapping on or off
    TourUp,
    TourDown,
};

struct PanelRow {
    RowKind kind = RowKind::Status;
    Rect rect;        // the whole row
    Rect value_rect;  // Field: the value box
    std::string text;
    std::string value;    // Field: the current value
    bool active = false;  // selected tree entry, pressed toggle
    int indent = 0;
    int model = -1, group = -1;
    int field = -1;  // index into scene_fields(); -1 for the add-model path field
    FieldTarget target;
    Command command = Command::None;
    bool editable = false;
};

struct Selection {
    int model = -1;
    int group = -1;
    int tour = -1;  // a tour, or with `step` one of its steps
    int step = -1;
    bool operator==(const Selection&) const = default;
};

struct PanelLayout {
    float x = 0, y = 0, width = 380, height = 800;
    float row_height = 26;
    float scroll = 0;  // pixels the rows are moved up
};

// The rows for `scene` with `selection`, placed by `layout`. `status`: the status line's text.
// `snap`: the snap toggle's state (shown on its button).
std::vector<PanelRow> layout_panel(const scene::Scene& scene, const Selection& selection, const std::string& status,
                                   const PanelLayout& layout, bool snap = false);
// The row at (x, y), or nullptr.
const PanelRow* hit_row(const std::vector<PanelRow>& rows, float x, float y);
// The height all rows need (for scrolling limits).
float panel_content_height(const std::vector<PanelRow>& rows, const PanelLayout& layout);

}  // namespace body::kiosk::author
