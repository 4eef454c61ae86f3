// The UI words (contract in ui_words.h): one row per word, one column per
// language in kUiLanguages' order; nullptr where a word has no translation
// yet (English is shown).
#include "kiosk/app/ui_words.h"

#include <iterator>

namespace body::kiosk {

namespace {

constexpr size_t kColumns = std::size(kUiLanguages);

struct Word {
    const char* key;
    const char* text[kColumns];  // en, de, fr, es, ru, el, ar, he, zh, ja
};

constexpr Word kWords[] = {
    // The control column (ui.h).
    {"home", {"Home", "Start", "Accueil", "Inicio", "Домой", "Αρχή", "الرئيسية", "בית", "主页", "ホーム"}},
    {"style", {"Style", "Stil", "Style", "Estilo", "Стиль", "Στυλ", "النمط", "סגנון", "样式", "スタイル"}},
    {"group", {"Group", "Gruppe", "Groupe", "Grupo", "Группа", "Ομάδα", "المجموعة", "קבוצה", "组", "グループ"}},
    {"lod", {"Detail", "Detail", "Détail", "Detalle", "Детали", "Λεπτομέρεια", "التفاصيل", "פירוט", "细节", "詳細"}},
    {"auto", {"Auto", "Auto", "Auto", "Auto", "Авто", "Αυτόματο", "تلقائي", "אוטומטי", "自动", "自動"}},
    {"isolate",
     {"Isolate", "Isolieren", "Isoler", "Aislar", "Изолировать", "Απομόνωση", "عزل", "בידוד", "单独显示", "単独表示"}},
    // The structure tree (structure_tree.h).
    {"structures",
     {"Structures", "Strukturen", "Structures", "Estructuras", "Структуры", "Δομές", "البنى", "מבנים", "结构", "構造"}},
    {"search", {"Search", "Suche", "Chercher", "Buscar", "Поиск", "Αναζήτηση", "بحث", "חיפוש", "搜索", "検索"}},
    // The cut plane (cut_plane.h).
    {"cut", {"Cut", "Schnitt", "Coupe", "Corte", "Срез", "Τομή", "مقطع", "חתך", "剖切", "断面"}},
    {"off", {"off", "aus", "non", "no", "выкл", "κλειστό", "إيقاف", "כבוי", "关", "オフ"}},
    {"move", {"move", "bewegen", "bouger", "mover", "двигать", "μετακίνηση", "تحريك", "הזזה", "移动", "移動"}},
    {"fixed", {"fixed", "fest", "fixe", "fijo", "закреплён", "σταθερό", "ثابت", "קבוע", "固定", "固定"}},
    {"axial", {"axial", "axial", "axiale", "axial", "аксиальный", "αξονικό", "محوري", "צירי", "轴位", "軸位"}},
    {"coronal",
     {"coronal", "koronal", "coronale", "coronal", "корональный", "στεφανιαίο", "إكليلي", "קורונלי", "冠状位",
      "冠状断"}},
    {"sagittal",
     {"sagittal", "sagittal", "sagittale", "sagital", "сагиттальный", "οβελιαίο", "سهمي", "סגיטלי", "矢状位",
      "矢状断"}},
    // Tours and the idle countdown (tour_controls.h).
    {"tour", {"Tour", "Tour", "Visite", "Recorrido"}},
    {"back", {"Back", "Zurück", "Retour", "Atrás"}},
    {"pause", {"Pause", "Pause", "Pause", "Pausa"}},
    {"play", {"Play", "Weiter", "Lecture", "Seguir"}},
    {"next", {"Next", "Weiter", "Suivant", "Siguiente"}},
    {"leave", {"Leave", "Beenden", "Quitter", "Salir"}},
    {"still", {"Still looking?", "Noch da?", "Toujours là ?", "¿Sigue ahí?"}},
};

const Word* find(std::string_view key) {
    for (const Word& w : kWords)
        if (key == w.key) return &w;
    return nullptr;
}

}  // namespace

std::string ui_word(std::string_view key, std::string_view language) {
    const Word* w = find(key);
    if (!w) return std::string(key);
    for (size_t i = 0; i < kColumns; ++i)
        if (language == kUiLanguages[i] && w->text[i]) return w->text[i];
    return w->text[0];
}

bool has_ui_word(std::string_view key) { return find(key) != nullptr; }

}  // namespace body::kiosk
