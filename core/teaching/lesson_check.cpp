// Lessons the engine vouches for: {{values}} in the text rendered from the engine, and the
// checks `dtlab lesson check` adds to planning (characters the GUI's font cannot draw, answers
// given away by the text, the operation banner or the rendered slide).
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
                                                std::string* error, Editor* edits) {
    const auto values = findEmbeddedValues(text, error);
    if (!values) return std::nullopt;
    std::string out;
    std::size_t at = 0;
    for (const EmbeddedValue& v : *values) {
        out.append(text.substr(at, v.begin - at));
        std::string why;
        const auto a = computeAnswer(v.spec, ins, journal, selected, &why, edits);
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

// Whether stop k shows the flip queue numbered in test order (the flip-queue-order overlay): as
// the player does, the overlays of the last stop up to k that names some, or the defaults.
bool showsTestOrder(const Lesson& lesson, std::size_t k) {
    std::size_t named = k + 1;
    while (named > 0 && lesson.stops[named - 1].overlays.empty()) --named;
    if (named == 0) return Overlays{}.flipQueue && Overlays{}.queueOrder;
    const std::vector<std::string>& o = lesson.stops[named - 1].overlays;
    const auto has = [&](const char* name) {
        return std::find(o.begin(), o.end(), name) != o.end();
    };
    return has("flip-queue") && has("flip-queue-order");
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
        if (trimmed(s.answer) == "next_test_edge" && showsTestOrder(lesson, k)) {
            out.emplace_back(lesson.file, s.line, stop,
                             "the flip queue is numbered in test order (flip-queue-order): its 1 "
                             "is the answer (" +
                                 said +
                                 "); number it in push order (flip-queue-pushed) or not at all");
        }
        if (answerAppearsIn(*st.answer, st.text)) {
            out.emplace_back(lesson.file, s.textLine, stop,
                             "the answer (" + said +
                                 ") already appears in the stop's text: say it after the "
                                 "question, or ask something the text does not tell");
        }
        // The banner without its "[op N] " operation counter: the caption and the op's type.
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

// ============================================================================================
// [SECTION] The rendered slide
// ============================================================================================

namespace dlab {

namespace {

// Words and numbers of a drawn line, in order: "flips | 24 (3.0 per insertion)" -> flips, 24, 3,
// 0, per, insertion; "32°" -> 32, °.
std::vector<std::string> slideWords(std::string_view s) {
    std::vector<std::string> out;
    for (const Token& t : tokens(s)) {
        out.push_back(t.word);
        if (s.substr(t.end, 2) == "\u00b0") out.push_back("\u00b0");
    }
    return out;
}

// Letters and digits only, lower case: a text as drawn, whatever its wrapping and markup.
std::string alnumOnly(std::string_view s) {
    std::string out;
    for (char ch : s) {
        if (std::isalnum(static_cast<unsigned char>(ch)))
            out += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    }
    return out;
}

// Whether `line` is a piece of `text` as drawn (wrapped over several lines, markup gone).
bool partOf(const std::string& line, const std::string& text) {
    const std::string l = alnumOnly(line);
    return !l.empty() && text.find(l) != std::string::npos;
}

// A number with a unit next to it, in either order, that the answer takes as its own.
bool countWithUnit(const Answer& answer, const std::vector<std::string>& w) {
    Answer bare = answer;
    bare.units.clear();
    for (std::size_t i = 0; i < w.size(); ++i) {
        if (!acceptsAnswer(bare, w[i])) continue;
        // Only with its unit: "0 0" (two cells) reads 0 too, and ids are everywhere.
        std::vector<std::string> tries;
        if (i + 1 < w.size()) tries.push_back(w[i] + " " + w[i + 1]);
        if (i + 2 < w.size()) tries.push_back(w[i] + " " + w[i + 1] + " " + w[i + 2]);
        if (i > 0) tries.push_back(w[i] + " " + w[i - 1]);
        if (i > 1) tries.push_back(w[i] + " " + w[i - 2] + " " + w[i - 1]);
        for (const std::string& t : tries) {
            if (acceptsAnswer(answer, t) && !acceptsAnswer(bare, t)) return true;
        }
    }
    return false;
}

// A phrase the answer takes, one to three words long. Where a point was found ("edge",
// "inside") is left to answerAppearsIn: those words are everywhere in a lesson.
bool phrase(const Answer& answer, const std::vector<std::string>& w, const std::string& line) {
    for (const char* where : {"inside", "edge", "vertex", "outside-hull", "none"}) {
        if (answer.text == where) return answerAppearsIn(answer, line);
    }
    for (std::size_t i = 0; i < w.size(); ++i) {
        std::string t;
        for (std::size_t n = 0; n < 3 && i + n < w.size(); ++n) {
            t += (n ? " " : "") + w[i + n];
            if (acceptsAnswer(answer, t)) return true;
        }
    }
    return false;
}

// The corner-table column and row an answer reads in one look: "O[c]" with corner 2 selected
// -> ("O[c]", 2); "n(5)" -> ("n", 5); "c.l" -> ("l", selected). nullopt for anything longer.
std::optional<std::pair<std::string, std::int64_t>> tableCell(std::string spec,
                                                              std::int32_t selected) {
    spec = trimmed(spec);
    const auto column = [](char x) -> std::string {
        switch (x) {
            case 'V': return "V[c]";
            case 'O':
            case 'o': return "O[c]";
            case 'n':
            case 'p':
            case 'l':
            case 'r': return std::string(1, x);
            default: return "";
        }
    };
    if (spec.size() == 3 && spec.rfind("c.", 0) == 0 && !column(spec[2]).empty() &&
        selected != kNone)
        return std::make_pair(column(spec[2]), std::int64_t{selected});
    if (spec.size() < 4 || column(spec[0]).empty()) return std::nullopt;
    const char open = spec[1], close = spec.back();
    if (!((open == '[' && close == ']') || (open == '(' && close == ')'))) return std::nullopt;
    const std::string inner = trimmed(spec.substr(2, spec.size() - 3));
    if (inner == "c" && selected != kNone)
        return std::make_pair(column(spec[0]), std::int64_t{selected});
    if (inner.empty() || !std::all_of(inner.begin(), inner.end(), [](char ch) {
            return std::isdigit(static_cast<unsigned char>(ch));
        }))
        return std::nullopt;
    return std::make_pair(column(spec[0]), std::stoll(inner));
}

std::vector<std::string> cells(const std::string& line) {
    std::vector<std::string> out;
    for (std::size_t at = 0;;) {
        const std::size_t bar = line.find(" | ", at);
        out.push_back(trimmed(line.substr(at, bar == std::string::npos ? bar : bar - at)));
        if (bar == std::string::npos) return out;
        at = bar + 3;
    }
}

// The row of the corner table on the slide that shows the cell the answer reads.
std::optional<std::string> cellOnSlide(const Answer& answer, const std::string& spec,
                                       std::int32_t selected,
                                       const std::vector<std::string>& lines) {
    const auto cell = tableCell(spec, selected);
    if (!cell) return std::nullopt;
    // The header's names have no spaces, but narrow columns can run them together ("O[c] n").
    std::vector<std::string> header;
    for (const std::string& line : lines) {
        std::vector<std::string> names;
        std::string cur;
        for (char ch : line + " ") {
            if (ch != ' ' && ch != '|') {
                cur += ch;
            } else if (!cur.empty()) {
                names.push_back(std::move(cur));
                cur.clear();
            }
        }
        if (names.size() > 4 && names[0] == "c" && names[1] == "t" && names[2] == "V[c]")
            header = names;
    }
    const auto col = std::find(header.begin(), header.end(), cell->first);
    if (col == header.end()) return std::nullopt;
    const auto k = static_cast<std::size_t>(col - header.begin());
    for (const std::string& line : lines) {
        const std::vector<std::string> c = cells(line);
        if (c.size() != header.size() || c[0] != std::to_string(cell->second)) continue;
        const std::vector<Token> value = tokens(c[k]);
        const bool minus = !c[k].empty() && c[k][0] == '-';
        if (!value.empty() && acceptsAnswer(answer, (minus ? "-" : "") + value[0].word))
            return "row " + c[0] + " of the corner table: " + line;
    }
    return std::nullopt;
}

}  // namespace

std::optional<std::string> answerOnSlide(const Answer& answer,
                                         const std::vector<std::string>& lines,
                                         std::string_view ownText) {
    const std::string own = alnumOnly(ownText);
    // Each line, and each line with the next (a phrase wrapped: "walked 2" / "steps from t3").
    std::vector<std::string> read;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (partOf(lines[i], own)) continue;
        read.push_back(lines[i]);
        if (i + 1 < lines.size() && !partOf(lines[i + 1], own))
            read.push_back(lines[i] + " " + lines[i + 1]);
    }
    for (const std::string& line : read) {
        const std::vector<std::string> w = slideWords(line);
        bool shown = false;
        switch (answer.kind) {
            case Answer::Kind::Integer: shown = countWithUnit(answer, w); break;
            case Answer::Kind::Text: shown = phrase(answer, w, line); break;
            case Answer::Kind::Edge:
            case Answer::Kind::Point: shown = answerAppearsIn(answer, line); break;
            case Answer::Kind::Truth: break;
        }
        if (shown) return line;
    }
    return std::nullopt;
}

std::vector<LessonError> slideProblems(const Lesson& lesson, const LessonPlan& plan,
                                       const std::vector<std::vector<std::string>>& slides) {
    std::vector<LessonError> out;
    for (std::size_t k = 0; k < lesson.stops.size() && k < plan.stops.size() && k < slides.size();
         ++k) {
        const StopState& st = plan.stops[k];
        if (!st.answer) continue;
        // The stop's text and question are checked on their own (lessonProblems): here, what
        // the panels, the banner and the canvas show.
        auto line = answerOnSlide(*st.answer, slides[k], st.text + "\n" + st.question);
        if (!line) line = cellOnSlide(*st.answer, lesson.stops[k].answer, st.selected, slides[k]);
        if (!line) continue;
        out.emplace_back(lesson.file, lesson.stops[k].line, static_cast<int>(k) + 1,
                         "the answer (" + st.answer->display() + ") is on the rendered slide: \"" +
                             escapeControls(*line) +
                             "\": show another tab (tab = \"...\"), or ask before it shows");
    }
    return out;
}

}  // namespace dlab
