// setting_flags.hpp — the flag that sets each setting library messages name in words: knit's
// spelling of them, added to every error it prints ("lower the ply pitch (--ply-pitch)").
#pragma once
#include <string>
#include <vector>

#include "knit/setting_spelling.hpp"

namespace knit::cli {

// {words as library messages name the setting, the flag that sets it}, one per setting.
const std::vector<SettingSpelling>& settingFlags();

// `message` naming the flag of each setting it names (spellSettings with settingFlags()).
std::string withFlags(const std::string& message);

}  // namespace knit::cli
