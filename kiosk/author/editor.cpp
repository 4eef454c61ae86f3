// The authoring mode's editor: input to commands (contract in editor.h).
#include "kiosk/author/editor.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "kiosk/author/model_convert.h"
#include "shared/scene/scene_pack.h"

namespace body::kiosk::author {

namespace fs = std::filesystem;

const std::vector<std::string>& help_lines() {
    static const std::vector<std::string> lines = {
        "Keys",
        "Ctrl+S  save scene.json          Ctrl+Q  quit",
        "Ctrl+P  pack the bundle (saves first)   G  snap on/off",
        "Ctrl+Z  undo      Ctrl+Shift+Z / Ctrl+Y  redo",
        "P  preview the kiosk (Esc: back)   V  start view = camera",
        "Delete  remove the selected model, group, tour or step",
        "click a model  the point for Add pin",
        "? / F1  this help",
        "Mouse",
        "click  select     left drag  orbit     right drag  pan",
        "wheel  zoom       Shift+drag  move the selected model",
        "Alt+drag  rotate it (arcball)   Alt+Shift+drag  scale it",
        "Ctrl while dragging  snap (grid, 15 degrees, 0.1 scale)",
        "drag a pin  move it on its model's surface",
        "Fields",
        "click a value: type; Enter commits, Tab next, Esc cancels",
        "click a choice: next value (Shift+click: type it)",
    };
    return lines;
}

Editor::Editor(Document document) : document_(std::move(document)) {
    status_ = document_.path().empty() ? "new scene (not saved)" : document_.path();
    if (!document_.path().empty()) {
        const fs::path folder = fs::absolute(document_.path()).parent_path().lexically_normal();
        pack_to_ = (folder.parent_path() / (folder.filename().string() + "-bundle")).string();
    }
}

void Editor::select_model(int model) {
    if (focused_) commit();
    selection_ = Selection{model, -1};
}

void Editor::select_group(int group) {
    if (focused_) commit();
    selection_ = Selection{-1, group};
}

void Editor::select_tour(int tour, int step) {
    if (focused_) commit();
    selection_ = Selection{-1, -1, tour, step};
}

void Editor::set_viewport(int width, int height, float scale) {
    layout_.row_height = std::round(26.0f * scale);
    layout_.width = std::min(std::round(400.0f * scale), static_cast<float>(width) * 0.5f);
    layout_.height = static_cast<float>(height);
}

std::optional<Request> Editor::take_request() {
    if (requests_.empty()) return std::nullopt;
    const Request r = requests_.front();
    requests_.pop_front();
    return r;
}

void Editor::report(const Status& s, const std::string& done) { status_ = s ? done : s.error().message; }

const std::vector<PanelRow>& Editor::rows() {
    std::string status = status_;
    if (document_.dirty()) status = "* " + status;
    rows_ = layout_panel(document_.scene(), selection_, status, layout_, snap_);
    return rows_;
}

const PanelRow* Editor::focused_row() {
    if (!focused_) return nullptr;
    if (rows_.empty()) rows();
    for (const PanelRow& r : rows_) {  // the rows last laid out: pointers into them stay valid while drawing
        if (r.kind != RowKind::Field) continue;
        if (focus_field_ < 0 ? r.command == Command::AddModel : r.field == focus_field_ && r.target == focus_target_)
            return &r;
    }
    return nullptr;
}

// --- edits -------------------------------------------------------------------

Status Editor::move_model(int model, const std::array<float, 3>& delta) {
    return document_.apply("move " + document_.scene().models.at(static_cast<size_t>(model)).name,
                           [&](scene::Scene& s) {
                               auto& t = s.models[static_cast<size_t>(model)].transform.translate;
                               for (size_t i = 0; i < 3; ++i) t[i] += delta[i];
                               return ok_status();
                           });
}

Status Editor::set_transform(int model, const scene::Transform& transform, const std::string& what) {
    const std::string name = document_.scene().models.at(static_cast<size_t>(model)).name;
    Status s = document_.apply(what + " " + name, [&](scene::Scene& sc) {
        sc.models[static_cast<size_t>(model)].transform = transform;
        return ok_status();
    });
    report(s, what + " " + name + (snap_ ? " (snapped)" : ""));
    return s;
}

Status Editor::pack() {
    if (focused_ && !commit()) return input_error(status_);
    if (document_.path().empty()) return input_error("pack: the scene has no file yet");
    Status saved = document_.save();
    if (!saved) {
        report(saved, "");
        return saved;
    }
    auto packed = scene::pack_scene(document_.path(), pack_to_);
    if (!packed) {
        status_ = "pack failed: " + packed.error().message;
        return packed.error();
    }
    status_ = "packed " + std::to_string(packed->models) + " models, " + std::to_string(packed->triangles) +
              " triangles -> " + packed->bundle;
    return ok_status();
}

Status Editor::set_start_view(const scene::HomeCamera& camera) {
    Status s = document_.apply("start view", [&](scene::Scene& sc) {
        sc.camera = camera;
        return ok_status();
    });
    report(s, "start view set from the camera");
    return s;
}

Status Editor::add_model(const std::string& given) {
    std::string file = given;
    std::string ext = fs::path(file).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) return input_error(file + ": not a readable file");
    if (needs_conversion(file)) {
        const fs::path base = document_.path().empty() ? fs::current_path() : fs::path(document_.path()).parent_path();
        auto bpm = convert_to_bpm(file, (base / "models").string());
        if (!bpm) return bpm.error();
        file = bpm.value();
    } else if (ext != ".bpm" && ext != ".obj") {
        return input_error(file + ": not a model (.bpm, .obj, .stl or .ply; bodygen lod converts .gltf)");
    }
    const std::string stem = fs::path(file).stem().string();
    Status s = document_.apply("add " + stem, [&](scene::Scene& sc) {
        std::string name = stem;
        for (int n = 2; sc.model_index(name) >= 0; ++n) name = stem + "-" + std::to_string(n);
        scene::Model m;
        m.name = name;
        m.file = document_.manifest_file(file);
        m.path = fs::absolute(file).string();
        m.labels.push_back(scene::LabelText{sc.kiosk.languages.front(), name, ""});
        if (selection_.group >= 0) m.group = sc.groups[static_cast<size_t>(selection_.group)].name;
        sc.models.push_back(std::move(m));
        return ok_status();
    });
    if (s) selection_ = Selection{static_cast<int>(document_.scene().models.size()) - 1, -1};
    return s;
}

Status Editor::remove_model(int model) {
    if (document_.scene().models.size() <= 1) return input_error("remove: a scene keeps at least one model");
    Status s = document_.apply("remove " + document_.scene().models.at(static_cast<size_t>(model)).name,
                               [&](scene::Scene& sc) {
                                   sc.models.erase(sc.models.begin() + model);
                                   return ok_status();
                               });
    if (s) selection_ = Selection{};
    return s;
}

void Editor::run(Command command, const PanelRow* row) {
    scene::Scene const& sc = document_.scene();
    switch (command) {
        case Command::None: break;
        case Command::Save: {
            const Status s = document_.save();
            report(s, "saved " + document_.path());
            break;
        }
        case Command::Undo: {
            const std::string label = document_.undo_label();
            status_ = document_.undo() ? "undone: " + label : "nothing to undo";
            break;
        }
        case Command::Redo: {
            const std::string label = document_.redo_label();
            status_ = document_.redo() ? "redone: " + label : "nothing to redo";
            break;
        }
        case Command::Preview: requests_.push_back(Request::Preview); break;
        case Command::StartView: requests_.push_back(Request::StartView); break;
        case Command::Help: help_ = !help_; break;
        case Command::AddGroup: {
            std::string name;
            do name = "group " + std::to_string(++new_groups_);
            while (sc.find_group(name));
            const Status s = document_.apply("add group", [&](scene::Scene& s2) {
                s2.groups.push_back(scene::Group{name, std::nullopt, std::nullopt, true});
                return ok_status();
            });
            report(s, "added " + name + " (choose it as a model's group)");
            if (s) selection_ = Selection{-1, static_cast<int>(document_.scene().groups.size()) - 1};
            break;
        }
        case Command::RemoveSelected: remove_selected(); break;
        case Command::ResetTransform: {
            if (selection_.model < 0) break;
            const Status s = document_.apply("reset transform", [&](scene::Scene& s2) {
                s2.models[static_cast<size_t>(selection_.model)].transform = scene::Transform{};
                return ok_status();
            });
            report(s, "transform reset");
            break;
        }
        case Command::AddModel:
            if (row) focus(*row, row->value_rect.x);
            break;
        case Command::AddPin: {
            if (selection_.model < 0 || !surface_point_ || surface_point_->first != selection_.model) {
                status_ = "Add pin: click the point on the selected model first";
                break;
            }
            report(add_pin(selection_.model, surface_point_->second), "pin added (undo: Ctrl+Z)");
            break;
        }
        case Command::RemovePin:
            if (row) report(remove_pin(row->target.model, row->target.pin), "pin removed");
            break;
        case Command::AddTour: report(add_tour(), "tour added: + step adds the view as a step"); break;
        case Command::AddStep:
            if (!row) break;
            step_request_tour_ = row->target.tour;
            requests_.push_back(Request::AddStep);
            break;
        case Command::StepUp: report(move_step(-1), "step moved"); break;
        case Command::StepDown: report(move_step(+1), "step moved"); break;
        case Command::TourUp: report(move_tour(-1), "tour moved"); break;
        case Command::TourDown: report(move_tour(+1), "tour moved"); break;
        case Command::Pack: (void)pack(); break;
        case Command::SnapToggle:
            snap_ = !snap_;
            status_ = snap_ ? "snap on: grid, 15 degrees, 0.1 scale" : "snap off";
            break;
    }
}

void Editor::remove_selected() {
    const scene::Scene& sc = document_.scene();
    // An undo can take the selected tour or step away: nothing to remove then.
    if (selection_.tour >= static_cast<int>(sc.tours.size()) ||
        (selection_.tour >= 0 &&
         selection_.step >= static_cast<int>(sc.tours[static_cast<size_t>(selection_.tour)].steps.size()))) {
        selection_ = Selection{};
        return;
    }
    if (selection_.model >= 0) {
        report(remove_model(selection_.model), "removed");
    } else if (selection_.group >= 0) {
        const std::string name = sc.groups[static_cast<size_t>(selection_.group)].name;
        const Status s = document_.apply("remove group " + name, [&](scene::Scene& s2) {
            for (scene::Model& m : s2.models)
                if (m.group == name) m.group.clear();  // the members stay, ungrouped
            s2.groups.erase(s2.groups.begin() + selection_.group);
            return ok_status();
        });
        report(s, "removed group " + name);
        if (s) selection_ = Selection{};
    } else if (selection_.tour >= 0 && selection_.step >= 0) {
        // The parser refuses a tour without steps: the last one stays, with its reason.
        const Status s = document_.apply("remove step", [&](scene::Scene& s2) {
            auto& steps = s2.tours.at(static_cast<size_t>(selection_.tour)).steps;
            steps.erase(steps.begin() + selection_.step);
            return ok_status();
        });
        report(s, "step removed");
        if (s) selection_.step = -1;
    } else if (selection_.tour >= 0) {
        const std::string name = sc.tours.at(static_cast<size_t>(selection_.tour)).name;
        const Status s = document_.apply("remove tour " + name, [&](scene::Scene& s2) {
            if (s2.kiosk.attract_tour == name) s2.kiosk.attract_tour.clear();  // the attract mode turns again
            s2.tours.erase(s2.tours.begin() + selection_.tour);
            return ok_status();
        });
        report(s, "removed tour " + name);
        if (s) selection_ = Selection{};
    }
}

Status Editor::add_pin(int model, const std::array<float, 3>& anchor) {
    const scene::Scene& sc = document_.scene();
    const scene::Model& m = sc.models.at(static_cast<size_t>(model));
    const std::string& first = sc.kiosk.languages.front();
    // Titled as the model until the author types one: a valid pin at once.
    scene::Pin pin{anchor, {scene::LabelText{first, sc.label(m, first).title, ""}}};
    return document_.apply("add pin to " + m.name, [&](scene::Scene& s) {
        s.models[static_cast<size_t>(model)].pins.push_back(pin);
        return ok_status();
    });
}

Status Editor::remove_pin(int model, int pin) {
    return document_.apply("remove pin", [&](scene::Scene& s) -> Status {
        auto& pins = s.models.at(static_cast<size_t>(model)).pins;
        if (pin < 0 || pin >= static_cast<int>(pins.size())) return input_error("remove pin: no such pin");
        pins.erase(pins.begin() + pin);
        return ok_status();
    });
}

Status Editor::move_pin(int model, int pin, const std::array<float, 3>& anchor) {
    Status s = document_.apply("move pin", [&](scene::Scene& sc) -> Status {
        auto& pins = sc.models.at(static_cast<size_t>(model)).pins;
        if (pin < 0 || pin >= static_cast<int>(pins.size())) return input_error("move pin: no such pin");
        pins[static_cast<size_t>(pin)].anchor = anchor;
        return ok_status();
    });
    report(s, "pin moved (undo: Ctrl+Z)");
    return s;
}

Status Editor::add_tour() {
    std::string name;
    for (int n = 1; name.empty() || document_.scene().tour_index(name) >= 0; ++n) name = "tour " + std::to_string(n);
    const Status s = document_.apply("add tour", [&](scene::Scene& sc) {
        scene::Tour t;
        t.name = name;
        t.steps.emplace_back();
        sc.tours.push_back(std::move(t));
        return ok_status();
    });
    if (s) selection_ = Selection{-1, -1, static_cast<int>(document_.scene().tours.size()) - 1, -1};
    return s;
}

Status Editor::add_step(int tour, const scene::HomeCamera& camera, const std::vector<std::string>& visible) {
    const scene::Scene& sc = document_.scene();
    if (tour < 0 || tour >= static_cast<int>(sc.tours.size())) return input_error("add step: no such tour");
    const int count = static_cast<int>(sc.tours[static_cast<size_t>(tour)].steps.size());
    const int at = selection_.tour == tour && selection_.step >= 0 ? std::min(selection_.step + 1, count) : count;
    scene::TourStep st;
    st.camera.target = camera.target;
    st.camera.azimuth_deg = camera.azimuth_deg;
    st.camera.polar_deg = camera.polar_deg;
    st.camera.distance = camera.distance;
    st.visible = visible;
    if (selection_.model >= 0 && selection_.model < static_cast<int>(sc.models.size()))
        st.select = sc.models[static_cast<size_t>(selection_.model)].name;
    const Status s = document_.apply("add step", [&](scene::Scene& s2) {
        auto& steps = s2.tours[static_cast<size_t>(tour)].steps;
        steps.insert(steps.begin() + at, st);
        return ok_status();
    });
    report(s, "step " + std::to_string(at + 1) + " added from the view");
    if (s) selection_ = Selection{-1, -1, tour, at};
    return s;
}

Status Editor::move_step(int delta) {
    if (selection_.tour < 0 || selection_.step < 0) return input_error("move step: select a step first");
    const int to = selection_.step + delta;
    const auto& tours = document_.scene().tours;
    if (selection_.tour >= static_cast<int>(tours.size()) ||
        selection_.step >= static_cast<int>(tours[static_cast<size_t>(selection_.tour)].steps.size()))
        return input_error("move step: select a step first");
    const auto& steps = tours[static_cast<size_t>(selection_.tour)].steps;
    if (to < 0 || to >= static_cast<int>(steps.size())) return input_error("move step: already at the end");
    const Status s = document_.apply("move step", [&](scene::Scene& sc) {
        auto& list = sc.tours[static_cast<size_t>(selection_.tour)].steps;
        std::swap(list[static_cast<size_t>(selection_.step)], list[static_cast<size_t>(to)]);
        return ok_status();
    });
    if (s) selection_.step = to;
    return s;
}

Status Editor::move_tour(int delta) {
    const int count = static_cast<int>(document_.scene().tours.size());
    if (selection_.tour < 0 || selection_.tour >= count || selection_.step >= 0)
        return input_error("move tour: select a tour first");
    const int to = selection_.tour + delta;
    if (to < 0 || to >= count) return input_error("move tour: already at the end");
    const Status s = document_.apply("move tour", [&](scene::Scene& sc) {
        std::swap(sc.tours[static_cast<size_t>(selection_.tour)], sc.tours[static_cast<size_t>(to)]);
        return ok_status();
    });
    if (s) selection_.tour = to;
    return s;
}

// --- the focused field -------------------------------------------------------

void Editor::focus(const PanelRow& row, float click_x) {
    focused_ = true;
    focus_field_ = row.command == Command::AddModel ? -1 : row.field;
    focus_target_ = row.target;
    field_ = TextField(row.value);
    // The cursor goes to the codepoint boundary nearest the click.
    const float x = click_x - (row.value_rect.x + 4.0f);
    size_t best = row.value.size();
    float best_d = 1e9f;
    for (size_t at = 0; at <= row.value.size(); ++at) {
        if (at < row.value.size() && (static_cast<unsigned char>(row.value[at]) & 0xC0) == 0x80) continue;
        const float w = measure_ ? measure_(row.value.substr(0, at)) : 8.0f * static_cast<float>(at);
        if (std::abs(w - x) < best_d) {
            best_d = std::abs(w - x);
            best = at;
        }
    }
    field_.set_cursor(best, false);
}

void Editor::unfocus() { focused_ = false; }

bool Editor::commit() {
    if (!focused_) return true;
    const std::string text = field_.text();
    Status s = ok_status();
    if (focus_field_ < 0) {
        if (text.empty()) {
            unfocus();
            return true;
        }
        s = add_model(text);
        report(s, "added " + text);
    } else {
        const Field& f = scene_fields()[static_cast<size_t>(focus_field_)];
        const FieldTarget target = focus_target_;
        s = document_.apply(std::string("set ") + f.label, [&](scene::Scene& sc) { return f.set(sc, target, text); });
        report(s, std::string(f.label) + " set");
    }
    if (s) unfocus();
    return static_cast<bool>(s);
}

bool Editor::field_key(const InputEvent& e) {
    const bool shift = (e.modifiers & kModShift) != 0;
    switch (e.key) {
        case platform::kKeyBackspace: field_.backspace(); return true;
        case platform::kKeyDelete: field_.erase_forward(); return true;
        case platform::kKeyLeft: field_.left(shift); return true;
        case platform::kKeyRight: field_.right(shift); return true;
        case platform::kKeyHome: field_.home(shift); return true;
        case platform::kKeyEnd: field_.end(shift); return true;
        case platform::kKeyEnter: commit(); return true;
        case platform::kKeyTab: {
            const PanelRow* row = focused_row();
            const float y = row ? row->rect.y : 0.0f;
            if (commit()) {
                for (const PanelRow& r : rows())
                    if (r.kind == RowKind::Field && r.editable && r.rect.y > y) {
                        focus(r, 0.0f);
                        field_.select_all();
                        break;
                    }
            }
            return true;
        }
        case platform::kKeyEscape:
            unfocus();
            status_ = "edit cancelled";
            return true;
        default: break;
    }
    if ((e.modifiers & kModCtrl) && (e.key == 'A' || e.key == 'a')) {
        field_.select_all();
        return true;
    }
    return false;
}

// --- input -------------------------------------------------------------------

void Editor::request_quit() {
    if (!document_.dirty()) {
        quit_confirmed_ = true;
        requests_.push_back(Request::Quit);
        return;
    }
    prompt_ = true;
}

bool Editor::prompt_key(const InputEvent& e) {
    const int k = e.type == InputEvent::Type::Text ? std::toupper(e.key) : e.key;
    if (k == 'S') {
        const Status s = document_.save();
        report(s, "saved " + document_.path());
        if (s) {
            prompt_ = false;
            quit_confirmed_ = true;
            requests_.push_back(Request::Quit);
        }
    } else if (k == 'D') {
        prompt_ = false;
        quit_confirmed_ = true;
        requests_.push_back(Request::Quit);
    } else if (k == platform::kKeyEscape) {
        prompt_ = false;
        status_ = "quit cancelled";
    }
    return true;
}

bool Editor::key(const InputEvent& e) {
    if (!e.pressed) return focused_;
    const bool ctrl = (e.modifiers & kModCtrl) != 0, shift = (e.modifiers & kModShift) != 0;
    if (ctrl && e.key == 'P') {
        (void)pack();
        return true;
    }
    if (ctrl && (e.key == 'S' || e.key == 'Z' || e.key == 'Y' || e.key == 'Q')) {
        if (e.key == 'S') {
            if (commit()) run(Command::Save, nullptr);
        } else {
            unfocus();
            if (e.key == 'Q')
                request_quit();
            else
                run(e.key == 'Y' || shift ? Command::Redo : Command::Undo, nullptr);
        }
        return true;
    }
    if (focused_) return field_key(e) || true;
    switch (e.key) {
        case 'P': run(Command::Preview, nullptr); return true;
        case 'V': run(Command::StartView, nullptr); return true;
        case 'G': run(Command::SnapToggle, nullptr); return true;
        case platform::kKeyF1: help_ = !help_; return true;
        case platform::kKeyDelete: remove_selected(); return true;
        case platform::kKeyEscape:
            if (help_)
                help_ = false;
            else
                selection_ = Selection{};
            return true;
        default: return false;
    }
}

bool Editor::click(float x, float y, uint32_t modifiers) {
    const PanelRow* row = hit_row(rows(), x, y);
    if (focused_) {
        const PanelRow* f = focused_row();
        if (f && row && f->value_rect.contains(x, y)) {
            focus(*f, x);  // a click inside the focused field moves the cursor (the text typed so far stays)
            return true;
        }
        if (!commit()) return true;  // a bad value keeps the focus and says why
        row = hit_row(rows(), x, y);
    }
    if (!row) return true;
    switch (row->kind) {
        case RowKind::Button: run(row->command, row); break;
        case RowKind::TreeGroup: select_group(row->group); break;
        case RowKind::TreeModel: select_model(row->model); break;
        case RowKind::TreeTour:
        case RowKind::TreeStep: select_tour(row->target.tour, row->target.step); break;
        case RowKind::Field: {
            if (!row->editable) break;
            if (row->command == Command::AddModel) {
                focus(*row, x);
                break;
            }
            const Field& f = scene_fields()[static_cast<size_t>(row->field)];
            if (f.kind == FieldKind::Choice && !(modifiers & kModShift)) {
                const std::string next = next_choice(f.choices(document_.scene()), row->value);
                const FieldTarget target = row->target;
                const Status s = document_.apply(std::string("set ") + f.label,
                                                 [&](scene::Scene& sc) { return f.set(sc, target, next); });
                report(s, std::string(f.label) + ": " + next);
            } else {
                focus(*row, x);
            }
            break;
        }
        default: break;
    }
    return true;
}

bool Editor::handle(const InputEvent& e) {
    using T = InputEvent::Type;
    if (prompt_) return e.type == T::Key || e.type == T::Text ? prompt_key(e) : true;
    switch (e.type) {
        case T::Key: return key(e);
        case T::Text:
            if (focused_) {
                if (!(e.modifiers & (kModCtrl | kModAlt))) field_.insert(static_cast<char32_t>(e.key));
                return true;
            }
            if (e.key == '?') help_ = !help_;
            return e.key == '?';
        case T::MouseDown:
        case T::TouchDown:
            if (e.x < layout_.width) {
                if (e.type == T::TouchDown || e.button() == MouseButton::Left) click(e.x, e.y, e.modifiers);
                return true;
            }
            if (help_) help_ = false;
            return false;
        case T::Scroll:
            if (e.x >= layout_.width) return false;
            layout_.scroll = std::clamp(layout_.scroll - e.dy * layout_.row_height * 3.0f, 0.0f,
                                        std::max(0.0f, panel_content_height(rows(), layout_) - layout_.height));
            return true;
        default: return false;
    }
}

}  // namespace body::kiosk::author
