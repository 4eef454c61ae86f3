#pragma once
// The authoring mode's editor, without GL: the document, the selection, the
// side panel's rows and its focused text field, the help overlay and the
// unsaved-changes prompt. The window loop (author_run.cpp) hands it every input
// event first; what it does not take (the 3-D view's clicks and drags) goes to
// the kiosk app. Requests it cannot serve alone (preview, the camera as the
// start view, quitting) are queued for the loop.
//
// Keys (listed by the help overlay, `?` or F1):
//   Ctrl+S save   Ctrl+Z undo   Ctrl+Shift+Z / Ctrl+Y redo   P preview (Esc back)
//   Ctrl+P pack the bundle (saves first)   G snap on/off   V start view from
//   the camera   Delete remove the selection (model, group, tour or step)
//   Ctrl+Q quit
//   In a field: typing, Backspace, Delete, arrows (Shift extends), Home, End,
//   Ctrl+A, Enter commits, Tab commits and moves on, Esc cancels.
#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "kiosk/app/input.h"
#include "kiosk/author/document.h"
#include "kiosk/author/panel.h"
#include "kiosk/author/text_field.h"

namespace body::kiosk::author {

// AddStep: the loop answers with add_step(step_request_tour(), its camera, the visible models).
enum class Request { Preview, StartView, Quit, AddStep };

// A pin of the selected model where the view shows it (window pixels): the
// painter marks it, a drag moves it (author_run.cpp).
struct PinMarker {
    float x = 0, y = 0;
    int model = -1, pin = -1;
};

// The lines of the help overlay.
const std::vector<std::string>& help_lines();

class Editor {
public:
    explicit Editor(Document document);

    Document& document() { return document_; }
    const Document& document() const { return document_; }
    const Selection& selection() const { return selection_; }
    void select_model(int model);
    void select_group(int group);
    void select_tour(int tour, int step = -1);  // step -1: the tour itself

    // Panel geometry: the panel's width follows `scale` (UI scale, 1 at 800 px).
    void set_viewport(int width, int height, float scale);
    float panel_width() const { return layout_.width; }
    // Text width in pixels for placing the cursor on a click (the loop sets the atlas's).
    void set_measure(std::function<float(const std::string&)> measure) { measure_ = std::move(measure); }

    // True when the event was the editor's (panel, keys, prompt); else it is the view's.
    bool handle(const InputEvent& event);
    std::optional<Request> take_request();

    // Edits the loop asks for: the manipulation sphere's move, the camera as the start view.
    Status move_model(int model, const std::array<float, 3>& delta);
    // The manipulation sphere's rotate or scale (or a snapped move): the whole transform, one command.
    Status set_transform(int model, const scene::Transform& transform, const std::string& what);
    // Snapping of the manipulation sphere's edits (manipulation.h), toggled by G or the panel.
    bool snap() const { return snap_; }
    void set_snap(bool on) { snap_ = on; }
    // Pack: saves, then packs the saved scene into pack_to() (scene/scene_pack.h:
    // validated, atomic); the status line says what was packed or what failed, where.
    Status pack();
    // Default: a sibling of the scene's folder, "<folder>-bundle/" (never inside what it copies).
    const std::string& pack_to() const { return pack_to_; }
    void set_pack_to(std::string dir) { pack_to_ = std::move(dir); }
    Status set_start_view(const scene::HomeCamera& camera);
    // .bpm/.obj are referenced where they lie; .stl/.ply are converted into a
    // .bpm in the scene's models/ folder first (model_convert.h).
    Status add_model(const std::string& file);
    Status remove_model(int model);
    // Pins: the loop reports the surface point a click in the view hit (model
    // file coordinates, before `transform`); Add pin puts one there.
    void set_surface_point(int model, const std::array<float, 3>& anchor) { surface_point_ = {model, anchor}; }
    Status add_pin(int model, const std::array<float, 3>& anchor);
    Status remove_pin(int model, int pin);
    // A pin dragged to another point on its model's surface (model file coordinates).
    Status move_pin(int model, int pin, const std::array<float, 3>& anchor);
    void set_pin_markers(std::vector<PinMarker> markers) { pin_markers_ = std::move(markers); }
    const std::vector<PinMarker>& pin_markers() const { return pin_markers_; }
    // Tours: a new one has one step that changes nothing; a step added from the view
    // holds `camera` (target, azimuth, polar, distance), only `visible` shown and the
    // model selected now; it goes after the selected step of that tour, else last.
    Status add_tour();
    Status add_step(int tour, const scene::HomeCamera& camera, const std::vector<std::string>& visible);
    int step_request_tour() const { return step_request_tour_; }
    Status move_step(int delta);  // the selected step, earlier (-1) or later (+1)
    Status move_tour(int delta);  // the selected tour, earlier (-1) or later (+1) in the list

    // What to draw. rows() lays the panel out again (pointers into the old rows die);
    // focused_row() looks in the rows last laid out.
    const std::vector<PanelRow>& rows();
    const PanelRow* focused_row();  // the row whose field has the focus, or nullptr
    const TextField& field() const { return field_; }
    bool help_visible() const { return help_; }
    bool prompt_visible() const { return prompt_; }
    const std::string& status() const { return status_; }
    // The user asked to quit and the prompt (if any) was answered.
    bool quit_confirmed() const { return quit_confirmed_; }
    // Asks to quit: at once when clean, else the prompt opens.
    void request_quit();

private:
    bool key(const InputEvent& e);
    bool field_key(const InputEvent& e);
    bool prompt_key(const InputEvent& e);
    bool click(float x, float y, uint32_t modifiers);
    void run(Command command, const PanelRow* row);
    void focus(const PanelRow& row, float click_x);
    void unfocus();
    bool commit();
    void report(const Status& s, const std::string& done);

    Document document_;
    Selection selection_;
    PanelLayout layout_;
    std::vector<PanelRow> rows_;
    long rows_revision_ = -1;
    Selection rows_selection_{-2, -2};
    bool rows_dirty_ = true;
    std::string status_;
    // The focus: the field index and target (or the add-model row), and its text.
    bool focused_ = false;
    int focus_field_ = -1;
    FieldTarget focus_target_;
    TextField field_;
    bool help_ = false, prompt_ = false, quit_confirmed_ = false;
    std::deque<Request> requests_;
    std::function<float(const std::string&)> measure_;
    int new_groups_ = 0;
    std::optional<std::pair<int, std::array<float, 3>>> surface_point_;
    int step_request_tour_ = -1;
    bool snap_ = false;
    std::vector<PinMarker> pin_markers_;
    std::string pack_to_;
    void remove_selected();
};

}  // namespace body::kiosk::author
