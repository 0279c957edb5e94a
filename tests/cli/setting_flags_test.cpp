// The flags the CLI adds to library messages (apps/knit/setting_flags.cpp): each one a flag of a
// subcommand, settings whose words never contain one another, each spelled where first named.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "setting_flags.hpp"

namespace knit::cli {
namespace {

bool anySubcommandHas(CLI::App& app, const std::string& flag) {
    for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
        if (sub->get_option_no_throw(flag) != nullptr) return true;
    return false;
}

TEST(SettingFlags, everyFlagIsAnOptionOfASubcommand) {
    CLI::App app("test");
    Commands commands;  // every subcommand, registered as main.cpp registers them
    addCommands(app, commands);
    for (const SettingSpelling& s : settingFlags()) {
#ifndef KNIT_HAVE_RENDER_CHECK
        if (s.spelling == "--surface-only") continue;  // a flag of builds with render_check only
#endif
#ifndef KNIT_HAVE_FIT
        if (s.spelling == "--fit" || s.spelling == "--bound") continue;  // knit fit needs NLopt
#endif
        EXPECT_TRUE(anySubcommandHas(app, s.spelling)) << s.words << ": " << s.spelling;
    }
}

TEST(SettingFlags, noSettingsWordsContainAnothers) {
    for (const SettingSpelling& a : settingFlags())
        for (const SettingSpelling& b : settingFlags())
            if (&a != &b) EXPECT_EQ(a.words.find(b.words), std::string::npos) << a.words << " / " << b.words;
}

TEST(SettingFlags, theFlagFollowsTheFirstMentionOfEachSetting) {
    EXPECT_EQ(withFlags("the ply pitch 1e+39 is beyond the float32 range (3.4e38); lower the ply pitch"),
              "the ply pitch (--ply-pitch) 1e+39 is beyond the float32 range (3.4e38); lower the ply pitch");
    EXPECT_EQ(
        withFlags("over the memory budget of 1 GiB; lower the repeats or raise the memory budget"),
        "over the memory budget (--max-memory) of 1 GiB; lower the repeats (--repeats) or raise the memory budget");
    // A message that names the flag already (the CLI's own) is left as it is; so is one naming no setting.
    const std::string own = "--gauge and --repeats are mutually exclusive (a gauge sets the repeats)";
    EXPECT_EQ(withFlags(own), "--gauge and --repeats are mutually exclusive (a gauge sets the repeats)");
    EXPECT_EQ(withFlags("mesh.obj:3: bad face"), "mesh.obj:3: bad face");
}

}  // namespace
}  // namespace knit::cli
