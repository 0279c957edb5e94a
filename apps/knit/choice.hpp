// choice.hpp — options whose value is one word of a fixed list, stored as the matching enum
// value (shown in --help as TEXT:{word,word,...}).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

namespace knit::cli {

// The accepted words, in the order --help lists them, and the value each one selects.
template <class Enum>
using Choices = std::vector<std::pair<std::string, Enum>>;

enum class Spelling { Exact, AnyCase };  // AnyCase: "YARNS" is read as the listed "yarns"

// The word of `value` (for a default shown in --help); "" if it has none.
template <class Enum>
std::string wordOf(const Choices<Enum>& choices, Enum value) {
    for (const auto& [word, v] : choices)
        if (v == value) return word;
    return "";
}

// Adds `flag` to `command`: one of the words of `choices`, stored into `target` as its value.
// Any other word is a CLI11 validation error naming the accepted ones.
template <class Enum>
CLI::Option* addChoice(CLI::App& command, const std::string& flag, Enum& target, const Choices<Enum>& choices,
                       const std::string& help, Spelling spelling = Spelling::Exact) {
    std::vector<std::string> words;
    for (const auto& choice : choices) words.push_back(choice.first);
    CLI::Option* option = command.add_option_function<std::string>(
        flag,
        [&target, choices](const std::string& word) {
            for (const auto& [w, value] : choices)
                if (w == word) target = value;
        },
        help);
    if (spelling == Spelling::AnyCase)
        option->transform(CLI::IsMember(words, CLI::ignore_case));  // maps to the listed spelling
    else option->check(CLI::IsMember(words));
    return option;
}

}  // namespace knit::cli
