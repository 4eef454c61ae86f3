// The side panel's rows (contract in panel.h).
#include "kiosk/author/panel.h"

namespace body::kiosk::author {

namespace {

struct Builder {
    const PanelLayout& l;
    std::vector<PanelRow> rows;
    float y;

    explicit Builder(const PanelLayout& layout) : l(layout), y(layout.y - layout.scroll) {}

    PanelRow& add(RowKind kind, std::string text, int indent = 0) {
        PanelRow r;
        r.kind = kind;
        r.text = std::move(text);
        r.indent = indent;
        r.rect = Rect{l.x, y, l.width, l.row_height};
        y += l.row_height;
        rows.push_back(std::move(r));
        return rows.back();
    }

    // Buttons side by side in one row.
    void buttons(std::initializer_list<std::pair<const char*, Command>> list) {
        const float w = l.width / static_cast<float>(list.size());
        float x = l.x;
        for (const auto& [text, command] : list) {
            PanelRow r;
            r.kind = RowKind::Button;
            r.text = text;
            r.command = command;
            r.rect = Rect{x + 1, y + 1, w - 2, l.row_height - 2};
            x += w;
            rows.push_back(std::move(r));
        }
        y += l.row_height;
    }

    // One button across the row, acting on `target` (a pin, a tour).
    PanelRow& button(std::string text, Command command, const FieldTarget& target = {}) {
        PanelRow& r = add(RowKind::Button, std::move(text));
        r.command = command;
        r.target = target;
        r.rect = Rect{r.rect.x + 1, r.rect.y + 1, r.rect.w - 2, r.rect.h - 2};
        return r;
    }

    void field(const scene::Scene& s, int index, const FieldTarget& target, const std::string& suffix = {}) {
        const Field& f = scene_fields()[static_cast<size_t>(index)];
        PanelRow& r = add(RowKind::Field, std::string(f.label) + suffix, 1);
        r.field = index;
        r.target = target;
        r.value = f.get(s, target);
        r.editable = f.kind != FieldKind::Fixed;
        r.value_rect = Rect{l.x + l.width * 0.42f, r.rect.y + 2, l.width * 0.58f - 4, l.row_height - 4};
    }
};

void tree(Builder& b, const scene::Scene& s, const Selection& sel) {
    b.add(RowKind::Heading, "Groups and models");
    auto model_row = [&](size_t i, int indent) {
        PanelRow& r = b.add(RowKind::TreeModel, s.models[i].name, indent);
        r.model = static_cast<int>(i);
        r.active = sel.model == static_cast<int>(i);
    };
    for (size_t g = 0; g < s.groups.size(); ++g) {
        const scene::Group& group = s.groups[g];
        // A group is open while it or one of its models is selected: a 116-model atlas stays one screen.
        const bool open =
            sel.group == static_cast<int>(g) || (sel.model >= 0 && sel.model < static_cast<int>(s.models.size()) &&
                                                 s.models[static_cast<size_t>(sel.model)].group == group.name);
        size_t members = 0;
        for (const scene::Model& m : s.models) members += m.group == group.name;
        PanelRow& r = b.add(RowKind::TreeGroup, std::string(open ? "▾ " : "▸ ") + group.name + " (" +
                                                    std::to_string(members) + ")" + (group.visible ? "" : " hidden"));
        r.group = static_cast<int>(g);
        r.active = sel.group == static_cast<int>(g);
        if (!open) continue;
        for (size_t i = 0; i < s.models.size(); ++i)
            if (s.models[i].group == group.name) model_row(i, 1);
    }
    bool any_loose = false;
    for (const scene::Model& m : s.models) any_loose = any_loose || m.group.empty();
    if (any_loose) b.add(RowKind::TreeGroup, "(no group)").group = -1;  // ungrouped models are always listed
    for (size_t i = 0; i < s.models.size(); ++i)
        if (s.models[i].group.empty()) model_row(i, 1);
    PanelRow& add = b.add(RowKind::Field, "add model (.bpm/.obj/.stl/.ply)");
    add.command = Command::AddModel;
    add.editable = true;
    add.value_rect = Rect{b.l.x + b.l.width * 0.42f, add.rect.y + 2, b.l.width * 0.58f - 4, b.l.row_height - 4};
    b.buttons({{"Add group", Command::AddGroup}, {"Remove", Command::RemoveSelected}});
    // Tours: each with its steps while it or a step is selected, and its "+ step" (which keeps the model selection).
    b.add(RowKind::Heading, "Tours");
    for (size_t i = 0; i < s.tours.size(); ++i) {
        const scene::Tour& t = s.tours[i];
        const bool open = sel.tour == static_cast<int>(i);
        PanelRow& r = b.add(RowKind::TreeTour, std::string(open ? "▾ " : "▸ ") + t.name + " (" +
                                                   std::to_string(t.steps.size()) + " steps)");
        r.target.tour = static_cast<int>(i);
        r.active = open && sel.step < 0;
        for (size_t k = 0; open && k < t.steps.size(); ++k) {
            PanelRow& st = b.add(RowKind::TreeStep, "step " + std::to_string(k + 1), 1);
            st.target.tour = static_cast<int>(i);
            st.target.step = static_cast<int>(k);
            st.active = sel.step == static_cast<int>(k);
        }
        FieldTarget target;
        target.tour = static_cast<int>(i);
        b.button("+ step to " + t.name + " from the view", Command::AddStep, target).indent = 1;
    }
    b.button("Add tour", Command::AddTour);
}

void pins(Builder& b, const scene::Scene& s, int model) {
    const auto& fields = scene_fields();
    FieldTarget t;
    t.model = model;
    const auto& list = s.models[static_cast<size_t>(model)].pins;
    for (size_t k = 0; k < list.size(); ++k) {
        t.pin = static_cast<int>(k);
        t.language.clear();
        const std::string n = " #" + std::to_string(k + 1);
        for (size_t i = 0; i < fields.size(); ++i)
            if (fields[i].scope == FieldScope::Pin) b.field(s, static_cast<int>(i), t, n);
        for (const std::string& lang : s.kiosk.languages) {
            t.language = lang;
            for (size_t i = 0; i < fields.size(); ++i)
                if (fields[i].scope == FieldScope::PinLabel) b.field(s, static_cast<int>(i), t, n + " [" + lang + "]");
        }
        t.language.clear();
        b.button("Remove pin" + n, Command::RemovePin, t);
    }
    b.button("Add pin at the clicked point", Command::AddPin);
}

// A tour's fields and title per language; with a step selected, the step's and its caption per language.
void tour_properties(Builder& b, const scene::Scene& s, const Selection& sel) {
    const auto& fields = scene_fields();
    const scene::Tour& tour = s.tours[static_cast<size_t>(sel.tour)];
    FieldTarget t;
    t.tour = sel.tour;
    const bool step = sel.step >= 0 && sel.step < static_cast<int>(tour.steps.size());
    if (!step) {
        b.add(RowKind::Heading, "Tour: " + tour.name);
        for (size_t i = 0; i < fields.size(); ++i)
            if (fields[i].scope == FieldScope::Tour) b.field(s, static_cast<int>(i), t);
        for (const std::string& lang : s.kiosk.languages) {
            t.language = lang;
            for (size_t i = 0; i < fields.size(); ++i)
                if (fields[i].scope == FieldScope::TourTitle) b.field(s, static_cast<int>(i), t, " [" + lang + "]");
        }
        b.buttons({{"Tour earlier", Command::TourUp}, {"Tour later", Command::TourDown}});
        return;
    }
    t.step = sel.step;
    b.add(RowKind::Heading, "Tour " + tour.name + ": step " + std::to_string(sel.step + 1));
    for (size_t i = 0; i < fields.size(); ++i)
        if (fields[i].scope == FieldScope::Step) b.field(s, static_cast<int>(i), t);
    for (const std::string& lang : s.kiosk.languages) {
        t.language = lang;
        for (size_t i = 0; i < fields.size(); ++i)
            if (fields[i].scope == FieldScope::StepCaption) b.field(s, static_cast<int>(i), t, " [" + lang + "]");
    }
    b.buttons({{"Step earlier", Command::StepUp}, {"Step later", Command::StepDown}});
}

void properties(Builder& b, const scene::Scene& s, const Selection& sel, bool snap) {
    const auto& fields = scene_fields();
    if (sel.model >= 0 && sel.model < static_cast<int>(s.models.size())) {
        b.add(RowKind::Heading, "Model: " + s.models[static_cast<size_t>(sel.model)].name);
        FieldTarget t;
        t.model = sel.model;
        for (size_t i = 0; i < fields.size(); ++i)
            if (fields[i].scope == FieldScope::Model) b.field(s, static_cast<int>(i), t);
        b.buttons(
            {{"Reset transform", Command::ResetTransform}, {snap ? "Snap: on" : "Snap: off", Command::SnapToggle}});
        for (const std::string& lang : s.kiosk.languages) {
            t.language = lang;
            for (size_t i = 0; i < fields.size(); ++i)
                if (fields[i].scope == FieldScope::Label) b.field(s, static_cast<int>(i), t, " [" + lang + "]");
        }
        pins(b, s, sel.model);
        return;
    }
    if (sel.group >= 0 && sel.group < static_cast<int>(s.groups.size())) {
        b.add(RowKind::Heading, "Group: " + s.groups[static_cast<size_t>(sel.group)].name);
        FieldTarget t;
        t.group = sel.group;
        for (size_t i = 0; i < fields.size(); ++i)
            if (fields[i].scope == FieldScope::Group) b.field(s, static_cast<int>(i), t);
        return;
    }
    if (sel.tour >= 0 && sel.tour < static_cast<int>(s.tours.size())) {
        tour_properties(b, s, sel);
        return;
    }
    b.add(RowKind::Heading, "Scene: start view and kiosk");
    for (size_t i = 0; i < fields.size(); ++i)
        if (fields[i].scope == FieldScope::Scene) b.field(s, static_cast<int>(i), FieldTarget{});
}

}  // namespace

std::vector<PanelRow> layout_panel(const scene::Scene& scene, const Selection& selection, const std::string& status,
                                   const PanelLayout& layout, bool snap) {
    Builder b(layout);
    b.buttons({{"Save", Command::Save},
               {"Pack", Command::Pack},
               {"Undo", Command::Undo},
               {"Redo", Command::Redo},
               {"Kiosk", Command::Preview},
               {"View", Command::StartView},
               {"?", Command::Help}});
    b.add(RowKind::Status, status);
    tree(b, scene, selection);
    properties(b, scene, selection, snap);
    return std::move(b.rows);
}

const PanelRow* hit_row(const std::vector<PanelRow>& rows, float x, float y) {
    for (const PanelRow& r : rows)
        if (r.rect.contains(x, y)) return &r;
    return nullptr;
}

float panel_content_height(const std::vector<PanelRow>& rows, const PanelLayout& layout) {
    float bottom = layout.y - layout.scroll;
    for (const PanelRow& r : rows) bottom = std::max(bottom, r.rect.y + r.rect.h);
    return bottom - (layout.y - layout.scroll);
}

}  // namespace body::kiosk::author
