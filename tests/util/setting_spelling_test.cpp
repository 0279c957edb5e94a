// spellSettings (knit/setting_spelling.hpp): a front end's spelling after the first mention of a
// setting's words, whole words only, never twice.
#include <gtest/gtest.h>

#include "knit/setting_spelling.hpp"

namespace knit {
namespace {

const std::vector<SettingSpelling> kKeywords = {{"the ply pitch", "ply_pitch"}, {"the repeats", "repeats"}};

TEST(SettingSpelling, addsTheSpellingAfterTheFirstMention) {
    EXPECT_EQ(spellSettings("the ply pitch 2 is odd; lower the ply pitch", kKeywords),
              "the ply pitch (ply_pitch) 2 is odd; lower the ply pitch");
    EXPECT_EQ(spellSettings("raise the repeats or the ply pitch", kKeywords),
              "raise the repeats (repeats) or the ply pitch (ply_pitch)");
}

TEST(SettingSpelling, matchesWholeWordsOnlyAndNeverSpellsTwice) {
    EXPECT_EQ(spellSettings("the ply pitches", kKeywords), "the ply pitches");
    EXPECT_EQ(spellSettings("pass ply_pitch: the ply pitch is 0", kKeywords), "pass ply_pitch: the ply pitch is 0");
    EXPECT_EQ(spellSettings("nothing to spell", kKeywords), "nothing to spell");
    // A keyword that is one of the setting's words is still added.
    EXPECT_EQ(spellSettings("meshopt compression needs tubes", {{"meshopt compression", "meshopt"}}),
              "meshopt compression (meshopt) needs tubes");
    const std::string once = spellSettings("lower the ply pitch", kKeywords);
    EXPECT_EQ(spellSettings(once, kKeywords), once);
}

}  // namespace
}  // namespace knit
