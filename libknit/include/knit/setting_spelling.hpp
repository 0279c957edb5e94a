// knit/setting_spelling.hpp — how library messages name settings, and how a front end adds its
// own spelling of them.
//
// A knit::Error message names a setting in words every front end understands ("the ply pitch",
// "the memory budget"), never one front end's spelling of it (a CLI flag, a Python keyword). A
// front end adds its spelling with spellSettings(): the CLI turns "lower the ply pitch" into
// "lower the ply pitch (--ply-pitch)" (apps/knit/setting_flags.cpp), Python's export_scene names
// its keywords (python/src/export.cpp).
#pragma once
#include <string>
#include <vector>

namespace knit {

// A setting as library messages name it and as one front end spells it: {"the ply pitch",
// "--ply-pitch"}. No setting's words may contain another's.
struct SettingSpelling {
    std::string words;
    std::string spelling;
};

// `message` with " (spelling)" after the first mention of each setting's words (whole words,
// case-sensitive), unless the message already names that spelling elsewhere.
std::string spellSettings(const std::string& message, const std::vector<SettingSpelling>& spellings);

}  // namespace knit
