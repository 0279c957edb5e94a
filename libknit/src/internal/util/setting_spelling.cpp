// spellSettings(): a front end's spelling of the settings a message names
// (see knit/setting_spelling.hpp).
#include <cctype>

#include "knit/setting_spelling.hpp"

namespace knit {
namespace {

bool wordChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'; }

// Where `part` occurs in `text` from `from` on as whole words (not inside a longer word), or npos.
size_t findWords(const std::string& text, const std::string& part, size_t from = 0) {
    for (size_t at = text.find(part, from); at != std::string::npos; at = text.find(part, at + 1)) {
        const size_t end = at + part.size();
        const bool startsWord = at == 0 || !wordChar(text[at - 1]) || !wordChar(part.front());
        const bool endsWord = end == text.size() || !wordChar(text[end]) || !wordChar(part.back());
        if (startsWord && endsWord) return at;
    }
    return std::string::npos;
}

// True when `text` names `spelling` outside the mentions of `words` (a keyword may be one of the
// words: "meshopt" in "meshopt compression").
bool namesSpelling(const std::string& text, const std::string& words, const std::string& spelling) {
    std::string rest = text;
    for (size_t at = findWords(rest, words); at != std::string::npos; at = findWords(rest, words, at + 1))
        rest.replace(at, words.size(), "\x01");
    return findWords(rest, spelling) != std::string::npos;
}

}  // namespace

std::string spellSettings(const std::string& message, const std::vector<SettingSpelling>& spellings) {
    std::string out = message;
    for (const SettingSpelling& s : spellings) {
        if (s.words.empty() || namesSpelling(out, s.words, s.spelling)) continue;
        const size_t at = findWords(out, s.words);
        if (at != std::string::npos) out.insert(at + s.words.size(), " (" + s.spelling + ")");
    }
    return out;
}

}  // namespace knit
