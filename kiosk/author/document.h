#pragma once
// The authoring document: a scene manifest being edited, every change a command
// on an undo/redo stack. A command is the scene before and after it (a scene of
// a few hundred models is a few hundred kilobytes; whole snapshots keep undo
// exact whatever the edit). An edit that would make the scene invalid (the
// parser's rules: unique names, known groups, declared languages, ranges) is
// refused with the parser's reason and changes nothing.
#include <functional>
#include <string>
#include <vector>

#include "shared/error.h"
#include "shared/scene/scene.h"

namespace body::kiosk::author {

class Document {
public:
    // `path`: where save() writes (scene.json); may be empty until saved.
    Document(scene::Scene scene, std::string path);

    const scene::Scene& scene() const { return scene_; }
    const std::string& path() const { return path_; }
    // Increments on every change (edit, undo, redo): views rebind when it moves.
    long revision() const { return revision_; }
    // Unsaved changes: the scene differs from the one last saved (or loaded).
    bool dirty() const { return saved_revision_ != revision_ && scene_json_ != saved_json_; }

    // Applies `edit` to a copy of the scene; kept when `edit` succeeds and the
    // copy is a valid scene, else the error says why and nothing changes. An edit
    // that changes nothing adds no step. Consecutive edits with the same
    // non-empty `merge_key` are one undo step (e.g. nudges of one model).
    Status apply(const std::string& label, const std::function<Status(scene::Scene&)>& edit,
                 const std::string& merge_key = {});
    bool can_undo() const { return !undo_.empty(); }
    bool can_redo() const { return !redo_.empty(); }
    bool undo();
    bool redo();
    // The label of the step undo()/redo() would take ("" when none).
    std::string undo_label() const { return undo_.empty() ? std::string() : undo_.back().label; }
    std::string redo_label() const { return redo_.empty() ? std::string() : redo_.back().label; }

    // Writes scene.json atomically (scene/scene_write.h: validated first); `path`
    // empty: the document's path. Clean afterwards.
    Status save(const std::string& path = {});

    // A model file path as the manifest should hold it: relative to the
    // manifest's directory when the file lies under it, else absolute.
    std::string manifest_file(const std::string& file) const;

private:
    struct Step {
        std::string label, merge_key;
        scene::Scene before, after;
    };
    void changed(std::string json = {});

    scene::Scene scene_;
    std::string path_;
    std::vector<Step> undo_, redo_;
    long revision_ = 0, saved_revision_ = 0;
    std::string scene_json_, saved_json_;
};

// Validates a scene as the kiosk would read it (scene_to_json, then parse_scene).
Status validate_scene(const scene::Scene& scene);

}  // namespace body::kiosk::author
