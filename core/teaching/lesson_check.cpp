// Lessons the engine vouches for: {{values}} in the text rendered from the engine, and the
// checks `dtlab lesson check` adds to planning (characters the GUI's font cannot draw, answers
// given away by the text or the operation banner).
#include "core/teaching/lesson.h"

#include "core/engine/numbers.h"
#include "core/engine/text_util.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <iterator>

namespace dlab {

// ============================================================================================
// [SECTION] Embedded values
// ============================================================================================

std::optional<std::vector<EmbeddedValue>> findEmbeddedValues(std::string_view text,
                                                             std::string* error) {
    std::vector<EmbeddedValue> out;
    int line = 1;
    std::size_t scanned = 0;
    for (std::size_t open = text.find("{{"); open != std::string_view::npos;
         open = text.find("{{", open + 2)) {
        line +=
            static_cast<int>(std::count(text.begin() + static_cast<std::ptrdiff_t>(scanned),
                                        text.begin() + static_cast<std::ptrdiff_t>(open), '\n'));
        scanned = open;
        const std::size_t close = text.find("}}", open + 2);
        const std::size_t nl = text.find('\n', open);
        const auto fail = [&](const std::string& why) {
            if (error) *error = "line " + std::to_string(line) + " of the text: " + why;
            return std::nullopt;
        };
        if (close == std::string_view::npos || (nl != std::string_view::npos && nl < close))
            return fail("unclosed {{ (write {{name}} on one line)");
        EmbeddedValue v;
        v.spec = trimmed(text.substr(open + 2, close - open - 2));
        if (v.spec.empty()) return fail("empty {{}}: name a value, e.g. {{walk_steps}}");
        v.begin = open;
        v.end = close + 2;
        v.line = line;
        out.push_back(std::move(v));
        open = close;
    }
    return out;
}

std::optional<std::string> renderEmbeddedValues(std::string_view text, Inserter& ins,
                                                Journal& journal, std::int32_t selected,
                                                std::string* error) {
    const auto values = findEmbeddedValues(text, error);
    if (!values) return std::nullopt;
    std::string out;
    std::size_t at = 0;
    for (const EmbeddedValue& v : *values) {
        out.append(text.substr(at, v.begin - at));
        std::string why;
        const auto a = computeAnswer(v.spec, ins, journal, selected, &why);
        if (!a) {
            if (error)
                *error =
                    "line " + std::to_string(v.line) + " of the text: {{" + v.spec + "}}: " + why;
            return std::nullopt;
        }
        out += a->display();
        at = v.end;
    }
    out.append(text.substr(at));
    return out;
}

// ============================================================================================
// [SECTION] What the GUI's font can draw
// ============================================================================================

namespace {

// Decodes one UTF-8 sequence at s[i]; 0xFFFD and one byte for anything malformed.
char32_t decode(std::string_view s, std::size_t& i) {
    const auto b = static_cast<unsigned char>(s[i]);
    int extra = b < 0x80 ? 0 : (b >> 5) == 6 ? 1 : (b >> 4) == 14 ? 2 : (b >> 3) == 30 ? 3 : -1;
    if (extra < 0 || i + static_cast<std::size_t>(extra) >= s.size() + (extra == 0)) {
        ++i;
        return 0xFFFD;
    }
    char32_t cp = extra == 0 ? b : b & (0x3F >> extra);
    for (int k = 1; k <= extra; ++k) {
        const auto c = static_cast<unsigned char>(s[i + static_cast<std::size_t>(k)]);
        if ((c >> 6) != 2) {
            ++i;
            return 0xFFFD;
        }
        cp = (cp << 6) | (c & 0x3F);
    }
    i += static_cast<std::size_t>(extra) + 1;
    return cp;
}

bool drawable(char32_t cp) {
    if (cp == '\n' || cp == '\r' || cp == '\t') return true;
    for (std::size_t k = 0; kLessonGlyphRanges[k] != 0; k += 2) {
        if (cp >= kLessonGlyphRanges[k] && cp <= kLessonGlyphRanges[k + 1]) return true;
    }
    return false;
}

}  // namespace

std::optional<std::pair<std::size_t, char32_t>> firstUndrawable(std::string_view text) {
    for (std::size_t i = 0; i < text.size();) {
        const std::size_t at = i;
        const char32_t cp = decode(text, i);
        if (cp == 0xFFFD || !drawable(cp)) return std::make_pair(at, cp);
    }
    return std::nullopt;
}

// ============================================================================================
// [SECTION] Answers given away
// ============================================================================================

namespace {

struct Token {
    std::string word;  // lower case letters and digits
    std::size_t begin, end;
};

std::vector<Token> tokens(std::string_view s) {
    std::vector<Token> out;
    for (std::size_t i = 0; i < s.size();) {
        if (!std::isalnum(static_cast<unsigned char>(s[i]))) {
            ++i;
            continue;
        }
        Token t{"", i, i};
        while (i < s.size() && std::isalnum(static_cast<unsigned char>(s[i])))
            t.word += static_cast<char>(std::tolower(static_cast<unsigned char>(s[i++])));
        t.end = i;
        out.push_back(std::move(t));
    }
    return out;
}

bool isDash(std::string_view sep) {
    const std::string t = trimmed(sep);
    return t == "-" || t == "\u2013" || t == "\u2014" || t == "\u2212";
}

// Whole numbers written in s, with their sign ("-1", "t25" -> 25; "0.001" is no whole number).
std::vector<std::int64_t> wholeNumbers(std::string_view s) {
    std::vector<std::int64_t> out;
    for (std::size_t i = 0; i < s.size();) {
        if (!std::isdigit(static_cast<unsigned char>(s[i]))) {
            ++i;
            continue;
        }
        std::size_t j = i;
        while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) ++j;
        const bool decimal = (j + 1 < s.size() && s[j] == '.' &&
                              std::isdigit(static_cast<unsigned char>(s[j + 1]))) ||
                             (i > 0 && s[i - 1] == '.');
        if (!decimal && j - i < 18) {
            std::int64_t v = std::stoll(std::string(s.substr(i, j - i)));
            const bool minus = i > 0 && s[i - 1] == '-' &&
                               (i == 1 || !std::isalnum(static_cast<unsigned char>(s[i - 2])));
            const bool unicodeMinus = i >= 3 && s.substr(i - 3, 3) == "\u2212";
            out.push_back(minus || unicodeMinus ? -v : v);
        }
        while (j < s.size() && (std::isdigit(static_cast<unsigned char>(s[j])) || s[j] == '.')) ++j;
        i = j;
    }
    return out;
}

const char* const kNumberWords[] = {"zero",  "one",   "two",  "three", "four",   "five",  "six",
                                    "seven", "eight", "nine", "ten",   "eleven", "twelve"};

bool vertexIs(const std::string& w, std::int64_t v, const std::string& label) {
    return w == std::to_string(v) || (!label.empty() && w == lowered(label));
}

// The answer's words in order: "SplitEdge" -> split, edge; "outside-hull" -> outside, hull.
std::vector<std::string> phraseWords(const std::string& text) {
    std::string spaced;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (i > 0 && std::isupper(static_cast<unsigned char>(text[i])) &&
            std::islower(static_cast<unsigned char>(text[i - 1])))
            spaced += ' ';
        spaced += text[i];
    }
    std::vector<std::string> out;
    for (const Token& t : tokens(spaced)) out.push_back(t.word);
    return out;
}

}  // namespace

bool answerAppearsIn(const Answer& answer, std::string_view text) {
    const std::vector<Token> tok = tokens(text);
    switch (answer.kind) {
        case Answer::Kind::Integer: {
            const auto nums = wholeNumbers(text);
            if (std::find(nums.begin(), nums.end(), answer.a) != nums.end()) return true;
            for (const Token& t : tok) {
                if (!answer.labelA.empty() && t.word == lowered(answer.labelA)) return true;
                // "one" reads as a pronoun too often to count.
                if (answer.a >= 0 && answer.a != 1 &&
                    answer.a < static_cast<std::int64_t>(std::size(kNumberWords)) &&
                    t.word == kNumberWords[answer.a])
                    return true;
            }
            return false;
        }
        case Answer::Kind::Edge:
            for (std::size_t i = 0; i + 1 < tok.size(); ++i) {
                if (!isDash(text.substr(tok[i].end, tok[i + 1].begin - tok[i].end))) continue;
                const std::string &x = tok[i].word, &y = tok[i + 1].word;
                if ((vertexIs(x, answer.a, answer.labelA) &&
                     vertexIs(y, answer.b, answer.labelB)) ||
                    (vertexIs(x, answer.b, answer.labelB) && vertexIs(y, answer.a, answer.labelA)))
                    return true;
            }
            return false;
        case Answer::Kind::Text: {
            // Where a point was found: "edge" and "vertex" give it away after "on" ("on the
            // edge", "on vertex 2"), not in "every edge around it".
            if (answer.text == "edge" || answer.text == "vertex") {
                for (std::size_t i = 0; i < tok.size(); ++i) {
                    if (tok[i].word != answer.text) continue;
                    std::size_t k = i;
                    while (k > 0 && (tok[k - 1].word == "the" || tok[k - 1].word == "an" ||
                                     tok[k - 1].word == "a"))
                        --k;
                    if (k > 0 && tok[k - 1].word == "on") return true;
                }
                return false;
            }
            const std::vector<std::string> want = phraseWords(answer.text);
            const std::string joined = looseName(answer.text);
            for (std::size_t i = 0; i < tok.size(); ++i) {
                if (tok[i].word == joined) return true;
                if (i + want.size() > tok.size() || want.empty()) continue;
                bool all = true;
                for (std::size_t k = 0; k < want.size() && all; ++k)
                    all = tok[i + k].word == want[k];
                if (all) return true;
            }
            return false;
        }
        case Answer::Kind::Point: {
            const std::string xy = shortest(answer.point.x) + ", " + shortest(answer.point.y);
            return text.find(xy) != std::string_view::npos;
        }
        case Answer::Kind::Truth: return false;
    }
    return false;
}

// ============================================================================================
// [SECTION] lesson check
// ============================================================================================

namespace {

std::string codePoint(char32_t cp) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "U+%04X", static_cast<unsigned>(cp));
    return buf;
}

// A character the GUI cannot draw in `text` (content starting at `line`), as a problem.
void checkFont(const Lesson& lesson, int stop, const std::string& what, const std::string& text,
               int line, std::vector<LessonError>& out) {
    const auto bad = firstUndrawable(text);
    if (!bad) return;
    const auto [at, cp] = *bad;
    const int l =
        line > 0 ? line + static_cast<int>(std::count(
                              text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'))
                 : 0;
    std::size_t end = at;
    decode(text, end);
    std::string shown = "a byte that is not UTF-8";
    if (cp != 0xFFFD) {
        shown = "\"";
        shown.append(text, at, end - at);
        shown += "\" (";
        shown += codePoint(cp);
        shown += ")";
    }
    out.emplace_back(lesson.file, l, stop,
                     "the " + what + " has " + shown +
                         ", which the GUI's font cannot draw (it shows \"?\"): use plain "
                         "characters (- for a minus sign, -> for an arrow)");
}

}  // namespace

std::vector<LessonError> lessonProblems(const Lesson& lesson, const LessonPlan& plan) {
    std::vector<LessonError> out;
    checkFont(lesson, 0, "title", lesson.title, 0, out);
    checkFont(lesson, 0, "summary", lesson.summary, 0, out);
    for (std::size_t k = 0; k < lesson.stops.size() && k < plan.stops.size(); ++k) {
        const LessonStop& s = lesson.stops[k];
        const StopState& st = plan.stops[k];
        const int stop = static_cast<int>(k) + 1;
        checkFont(lesson, stop, "text", s.text, s.textLine, out);
        checkFont(lesson, stop, "question", s.question, s.questionLine, out);
        checkFont(lesson, stop, "hint", s.hint, s.hintLine, out);
        if (!st.answer) continue;
        const std::string said = st.answer->display();
        if (answerAppearsIn(*st.answer, st.text)) {
            out.emplace_back(lesson.file, s.textLine, stop,
                             "the answer (" + said +
                                 ") already appears in the stop's text: say it after the "
                                 "question, or ask something the text does not tell");
        }
        // The banner without its "[N] " operation counter: the caption and the op's type.
        const std::size_t close = st.banner.find("] ");
        const std::string banner =
            close == std::string::npos ? st.banner : st.banner.substr(close + 2);
        if (answerAppearsIn(*st.answer, banner)) {
            out.emplace_back(lesson.file, s.line, stop,
                             "the answer (" + said +
                                 ") appears in the operation banner at this "
                                 "stop (\"" +
                                 st.banner +
                                 "\"): ask one operation earlier what will happen, or ask "
                                 "something else");
        }
    }
    return out;
}

}  // namespace dlab
