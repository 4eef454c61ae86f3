// The authoring document (contract in document.h).
#include "kiosk/author/document.h"

#include <filesystem>

#include "shared/scene/scene_write.h"

namespace body::kiosk::author {

namespace fs = std::filesystem;

Status validate_scene(const scene::Scene& scene) {
    auto parsed = scene::parse_scene(scene::scene_to_json(scene), "scene", scene.base_dir);
    if (!parsed) return parsed.error();
    return ok_status();
}

Document::Document(scene::Scene scene, std::string path) : scene_(std::move(scene)), path_(std::move(path)) {
    scene_json_ = saved_json_ = scene::scene_to_json(scene_);
}

void Document::changed(std::string json) {
    ++revision_;
    scene_json_ = json.empty() ? scene::scene_to_json(scene_) : std::move(json);
}

Status Document::apply(const std::string& label, const std::function<Status(scene::Scene&)>& edit,
                       const std::string& merge_key) {
    scene::Scene next = scene_;
    if (auto s = edit(next); !s) return s;
    const std::string text = scene::scene_to_json(next);
    if (text == scene_json_) return ok_status();
    auto parsed = scene::parse_scene(text, path_.empty() ? "scene.json" : path_, next.base_dir);
    if (!parsed) return parsed.error();
    // The parser fills defaults (a label's language): keep what it read, with the paths as edited.
    for (size_t i = 0; i < next.models.size(); ++i) parsed.value().models[i].path = next.models[i].path;
    parsed.value().source = next.source;
    if (!merge_key.empty() && !undo_.empty() && undo_.back().merge_key == merge_key && redo_.empty()) {
        undo_.back().after = parsed.value();
    } else {
        undo_.push_back(Step{label, merge_key, scene_, parsed.value()});
    }
    redo_.clear();
    scene_ = std::move(parsed).value();
    changed(text);  // the parser's defaults are already in the text it read
    return ok_status();
}

bool Document::undo() {
    if (undo_.empty()) return false;
    Step step = std::move(undo_.back());
    undo_.pop_back();
    scene_ = step.before;
    step.merge_key.clear();  // a step undone and redone never absorbs later edits
    redo_.push_back(std::move(step));
    changed();
    return true;
}

bool Document::redo() {
    if (redo_.empty()) return false;
    Step step = std::move(redo_.back());
    redo_.pop_back();
    scene_ = step.after;
    undo_.push_back(std::move(step));
    changed();
    return true;
}

Status Document::save(const std::string& path) {
    const std::string target = path.empty() ? path_ : path;
    if (target.empty()) return input_error("save: no file name (bodyview --author NEW_DIR/ or scene.json)");
    // Files are written relative to the target's directory: re-base them when it moved.
    scene::Scene out = scene_;
    if (fs::absolute(target).parent_path() != fs::absolute(path_.empty() ? target : path_).parent_path()) {
        Document moved(scene_, target);
        for (scene::Model& m : out.models) m.file = moved.manifest_file(m.path);
    }
    std::error_code ec;
    if (const fs::path dir = fs::path(target).parent_path(); !dir.empty()) fs::create_directories(dir, ec);
    if (auto s = scene::save_scene(out, target); !s) return s;
    path_ = target;
    saved_revision_ = revision_;
    saved_json_ = scene_json_;
    return ok_status();
}

std::string Document::manifest_file(const std::string& file) const {
    std::error_code ec;
    const fs::path abs = fs::weakly_canonical(fs::absolute(file), ec);
    const fs::path dir =
        fs::weakly_canonical(fs::absolute(path_.empty() ? fs::path(".") : fs::path(path_).parent_path()), ec);
    const fs::path rel = abs.lexically_relative(dir);
    if (!rel.empty() && *rel.begin() != "..") return rel.generic_string();
    return abs.generic_string();
}

}  // namespace body::kiosk::author
