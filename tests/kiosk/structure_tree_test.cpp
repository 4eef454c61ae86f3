// The structure tree (kiosk/app/structure_tree.h): the search rule, and the
// kiosk with 40 groups under replays: the tree in place of the group row,
// letter keys and typed letters narrowing the list, rows that show/hide and
// select, paging, large text, right-to-left mirroring.
#include "kiosk/app/structure_tree.h"

#include <gtest/gtest.h>

#include "kiosk/app/replay.h"
#include "kiosk_test_scene.h"
#include "many_models_scene.h"
#include "tests/common/replay_fixture.h"

namespace body::kiosk {
namespace {

std::vector<const Control*> all(const KioskApp& app, ControlId id) {
    std::vector<const Control*> out;
    for (const Control& c : app.controls())
        if (c.id == id) out.push_back(&c);
    return out;
}

// Plays replay text; times from `t`.
void play(KioskApp& app, const std::string& text, double t) {
    auto r = parse_replay(text, "tree.replay");
    ASSERT_TRUE(r) << r.error().message;
    run_replay(app, *r, 60.0, t);
}

std::string tap(const Control& c, double t) {
    return body::test::replay_tap(c.rect.x + c.rect.w / 2, c.rect.y + c.rect.h / 2, t);
}

const Control* first(const KioskApp& app, ControlId id, int group = -1) {
    for (const Control& c : app.controls())
        if (c.id == id && (group < 0 || c.group == group)) return &c;
    return nullptr;
}

TEST(StructureTree, WordsMatchAtTheirStartCaseFolded) {
    EXPECT_TRUE(title_matches("Caudate nucleus", U"nu"));
    EXPECT_TRUE(title_matches("Caudate nucleus", U"cau"));
    EXPECT_FALSE(title_matches("Caudate nucleus", U"uc"));  // not at a word's start
    EXPECT_TRUE(title_matches("Gyrus-Frontal", U"fr"));
    EXPECT_TRUE(title_matches("Ядро", std::u32string(1, fold_letter(U'Я'))));
    EXPECT_TRUE(title_matches("Ωμος", std::u32string(1, fold_letter(U'Ω'))));
    EXPECT_TRUE(title_matches("anything", U""));
}

TEST(StructureTree, RowsListMatchingGroupsAndModels) {
    TreeContent content;
    content.groups = {{"Cortex", true, {{0, "Frontal lobe"}, {1, "Occipital lobe"}}},
                      {"Basal ganglia", true, {{2, "Caudate"}, {3, "Putamen"}}}};
    TreeState st;
    EXPECT_EQ(tree_rows(content, st).size(), 2u);  // the groups only
    st.opened_group = 1;
    EXPECT_EQ(tree_rows(content, st).size(), 4u);  // and the opened group's models
    st.query = U"c";                               // Cortex (its name), Caudate (a model)
    const auto rows = tree_rows(content, st);
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[0].group, 0);
    EXPECT_EQ(rows[0].model, -1);
    EXPECT_EQ(rows[1].group, 1);
    EXPECT_EQ(rows[2].model, 2);
    st.query = U"lo";
    EXPECT_EQ(tree_rows(content, st).size(), 3u);  // Cortex with both lobes
    const std::vector<char32_t> letters = tree_letters(content);
    EXPECT_EQ(std::u32string(letters.begin(), letters.end()), U"bcfglop");
}

TEST(StructureTree, AFewGroupsKeepTheirToggles) {
    KioskApp app = test::make_app();
    app.update(0.0);
    EXPECT_EQ(all(app, ControlId::GroupToggle).size(), 2u);
    EXPECT_TRUE(all(app, ControlId::TreeOpen).empty());
}

TEST(StructureTree, FortyGroupsUnderTouchAndKeyboard) {
    KioskApp app = test::make_many_app(40, 30);  // 1,200 models
    app.update(0.0);
    EXPECT_TRUE(all(app, ControlId::GroupToggle).empty());
    ASSERT_EQ(all(app, ControlId::TreeOpen).size(), 1u);
    play(app, tap(*first(app, ControlId::TreeOpen), 0.1), 0.1);
    ASSERT_TRUE(app.tree().open);
    // Rows and keys are finger-sized, inside the screen, clear of the control column.
    const UiState ui = app.ui_state();
    const Control* home = first(app, ControlId::Home);
    ASSERT_NE(home, nullptr);
    const auto rows = all(app, ControlId::TreeGroup);
    ASSERT_GT(rows.size(), 3u);
    ASSERT_LT(rows.size(), 40u);  // a page of them
    for (ControlId id : {ControlId::TreeGroup, ControlId::TreeLetter, ControlId::TreeSearch}) {
        for (const Control* c : all(app, id)) {
            EXPECT_GE(c->rect.h, min_target_px(ui));
            EXPECT_GE(c->rect.x, 0.0f);
            EXPECT_LE(c->rect.x + c->rect.w, home->rect.x);
            EXPECT_LE(c->rect.y + c->rect.h, static_cast<float>(ui.height));
        }
    }
    // Page down, then back up.
    const int top_group = rows.front()->group;
    play(app, tap(*first(app, ControlId::TreeDown), 0.3), 0.3);
    EXPECT_GT(first(app, ControlId::TreeGroup)->group, top_group);
    play(app, tap(*first(app, ControlId::TreeUp), 0.5), 0.5);
    EXPECT_EQ(first(app, ControlId::TreeGroup)->group, top_group);

    // The letter key "C": only Caudate groups and models.
    const Control* c_key = first(app, ControlId::TreeLetter, static_cast<int>(U'c'));
    ASSERT_NE(c_key, nullptr);
    play(app, tap(*c_key, 0.7), 0.7);
    EXPECT_EQ(app.tree().query, U"c");
    ASSERT_FALSE(all(app, ControlId::TreeModel).empty());
    for (const Control* c : all(app, ControlId::TreeModel)) EXPECT_EQ(c->text.rfind("Caudate", 0), 0u) << c->text;
    // A model's row selects it; a group's row hides its group, as its toggle would.
    const Control* model_row = first(app, ControlId::TreeModel);
    const int model = model_row->group;
    play(app, tap(*model_row, 0.9), 0.9);
    EXPECT_EQ(app.selected(), model);
    const Control* group_row = first(app, ControlId::TreeGroup);
    const int group = group_row->group;
    ASSERT_TRUE(app.group(group).visible);
    play(app, tap(*group_row, 1.1), 1.1);
    EXPECT_FALSE(app.group(group).visible);
    EXPECT_TRUE(first(app, ControlId::TreeGroup, group)->active == false);

    // The keyboard: "op" types Optic; backspace leaves "o"; Escape closes.
    play(app, "1.3 key 257\n1.4 key 257\n1.5 text 79\n1.6 text 112\n", 1.3);
    EXPECT_EQ(app.tree().query, U"op");
    ASSERT_FALSE(all(app, ControlId::TreeModel).empty());
    for (const Control* c : all(app, ControlId::TreeModel)) EXPECT_EQ(c->text.rfind("Optic", 0), 0u) << c->text;
    play(app, "1.8 key 257\n", 1.8);
    EXPECT_EQ(app.tree().query, U"o");
    play(app, "2.0 key 256\n", 2.0);
    EXPECT_FALSE(app.tree().open);
    EXPECT_TRUE(all(app, ControlId::TreeGroup).empty());
    // Typing opens it again.
    play(app, "2.2 text 98\n", 2.2);
    EXPECT_TRUE(app.tree().open);
    EXPECT_EQ(app.tree().query, U"b");
}

TEST(StructureTree, LargeTextAndRightToLeft) {
    TreeContent content;
    for (int g = 0; g < 30; ++g) content.groups.push_back({"Group " + std::to_string(g), true, {{g, "Model"}}});
    TreeState st;
    st.open = true;
    UiState ui;
    ui.width = 1280;
    ui.height = 800;
    std::vector<Control> en, large, ar;
    add_tree_controls(ui, content, st, en);
    ui.large_text = true;
    add_tree_controls(ui, content, st, large);
    ui.large_text = false;
    ui.language = "ar";
    add_tree_controls(ui, content, st, ar);
    ASSERT_EQ(en.size(), ar.size());
    for (size_t i = 0; i < en.size(); ++i) {
        EXPECT_EQ(ar[i].id, en[i].id);
        EXPECT_FLOAT_EQ(ar[i].rect.x, 1280.0f - en[i].rect.x - en[i].rect.w);  // mirrored
        EXPECT_FLOAT_EQ(ar[i].rect.y, en[i].rect.y);
    }
    const auto row_height = [](const std::vector<Control>& cs) {
        for (const Control& c : cs)
            if (c.id == ControlId::TreeGroup) return c.rect.h;
        return 0.0f;
    };
    EXPECT_GT(row_height(large), row_height(en));  // larger rows, so fewer of them
    EXPECT_LT(large.size(), en.size());
}

}  // namespace
}  // namespace body::kiosk
