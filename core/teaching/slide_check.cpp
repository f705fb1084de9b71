// The check of a slide as rendered (slide_check.h): what a stop names, read from its text and
// answer, against the runs of text and the canvas marks drawn on its slide.
#include "core/teaching/slide_check.h"

#include "core/engine/text_util.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <set>

namespace dlab {

namespace {

struct Word {
    std::string text;  // lower case letters and digits
    std::size_t begin, end;
    bool number() const {
        return !text.empty() && text.size() < 10 &&
               std::all_of(text.begin(), text.end(),
                           [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
    }
};

std::vector<Word> words(std::string_view s) {
    std::vector<Word> out;
    for (std::size_t i = 0; i < s.size();) {
        if (!std::isalnum(static_cast<unsigned char>(s[i]))) {
            ++i;
            continue;
        }
        Word w{"", i, i};
        while (i < s.size() && std::isalnum(static_cast<unsigned char>(s[i])))
            w.text += static_cast<char>(std::tolower(static_cast<unsigned char>(s[i++])));
        w.end = i;
        out.push_back(std::move(w));
    }
    return out;
}

bool dashBetween(std::string_view s, const Word& a, const Word& b) {
    const std::string sep = trimmed(s.substr(a.end, b.begin - a.end));
    return sep == "-" || sep == "\u2013" || sep == "\u2014" || sep == "\u2212";
}

// Words after which numbers are not vertices: "corners 0-2", "op 12", "rows 3-5".
bool countsOther(const std::string& w) {
    static const char* const kOther[] = {"corner", "corners", "triangle", "triangles", "row",
                                         "rows",   "op",      "ops",      "operation", "operations",
                                         "step",   "steps",   "line",     "lines",     "stop",
                                         "stops",  "lesson",  "lessons",  "page",      "pages",
                                         "figure", "figures", "edges",    "columns",   "column"};
    return std::any_of(std::begin(kOther), std::end(kOther), [&](const char* o) { return w == o; });
}

void addUnique(std::vector<std::int32_t>& out, std::int32_t v) {
    if (std::find(out.begin(), out.end(), v) == out.end()) out.push_back(v);
}

std::int32_t toId(const Word& w) { return static_cast<std::int32_t>(std::stol(w.text)); }

// Words of a drawn line, split on spaces and the table's " | ".
std::vector<std::string> cellWords(const std::string& line) {
    std::vector<std::string> out;
    std::string cur;
    for (char ch : line + " ") {
        if (ch != ' ' && ch != '|') {
            cur += ch;
        } else if (!cur.empty()) {
            out.push_back(std::move(cur));
            cur.clear();
        }
    }
    return out;
}

bool startsWith(const std::vector<std::string>& w, std::initializer_list<const char*> head) {
    if (w.size() < head.size()) return false;
    std::size_t k = 0;
    for (const char* h : head) {
        if (w[k++] != h) return false;
    }
    return true;
}

// Whether `text` holds `word` as a whole word ("20 4" holds "4", "14" does not).
bool holdsWord(const std::string& text, const std::string& word) {
    for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) {
        const bool before = at == 0 || text[at - 1] == ' ';
        const std::size_t end = at + word.size();
        if (before && (end == text.size() || text[end] == ' ')) return true;
    }
    return false;
}

// The run of text drawn for a label recorded at `mark`: it reads `text` (alone, beside another
// label close by: "20 4", or followed by a word: "4 (s0)") across the mark's box. Null when none
// was read back there (cut by the clip rectangle, or drawn over so that glyphs interleave).
const SlideRun* labelRun(const SlideMark& mark, const std::string& text,
                         const RenderedSlide& slide) {
    for (const SlideRun& r : slide.runs) {
        // The selected corner's label is drawn twice on one spot (under its disc, then on it):
        // the glyphs read back as one run, "22".
        const bool twice = r.text == text + text;
        if ((holdsWord(r.text, text) || twice) && r.box.meets(mark.box, 0) &&
            r.box.x0 <= mark.box.x0 + 3 && r.box.x1 >= mark.box.x1 - 3)
            return &r;
    }
    return nullptr;
}

// Another run drawn over the label's box, or null.
const SlideRun* coveringRun(const SlideMark& mark, const SlideRun* own,
                            const RenderedSlide& slide) {
    SlideBox box = mark.box;
    box.y0 = std::max(box.y0, own->box.y0);
    box.y1 = std::min(box.y1, own->box.y1);
    for (const SlideRun& r : slide.runs) {
        // The same label drawn again on the spot (the selected corner's, on its disc).
        const bool again = r.text == own->text && std::abs(r.box.x0 - own->box.x0) < 3 &&
                           std::abs(r.box.y0 - own->box.y0) < 3;
        if (&r != own && !again && r.box.meets(box)) return &r;
    }
    return nullptr;
}

}  // namespace

std::vector<std::int32_t> verticesNamedIn(std::string_view text) {
    const std::vector<Word> w = words(text);
    std::vector<std::int32_t> out;
    for (std::size_t i = 0; i < w.size(); ++i) {
        const std::string& t = w[i].text;
        if (t == "vertex" || t == "vertices" || t == "point" || t == "points") {
            // "vertices 2, 3 and 5": numbers joined by commas, "and", "or".
            // "vertex 7", not "the new vertex (2, 14 and 17)": spaces only before the number.
            const bool next = i + 1 < w.size() &&
                              trimmed(text.substr(w[i].end, w[i + 1].begin - w[i].end)).empty();
            for (std::size_t k = i + 1; next && k < w.size() && w[k].number(); ++k) {
                addUnique(out, toId(w[k]));
                if (k + 1 < w.size() && (w[k + 1].text == "and" || w[k + 1].text == "or"))
                    ++k;
                else if (k + 1 < w.size() &&
                         trimmed(text.substr(w[k].end, w[k + 1].begin - w[k].end)) != ",")
                    break;
            }
        }
        if (i + 1 < w.size() && w[i].number() && w[i + 1].number() &&
            dashBetween(text, w[i], w[i + 1]) && !(i > 0 && countsOther(w[i - 1].text))) {
            addUnique(out, toId(w[i]));
            addUnique(out, toId(w[i + 1]));
        }
    }
    return out;
}

std::vector<std::string> panelsNamedIn(std::string_view text) {
    std::string flat;  // lower case, one space between words
    for (const Word& w : words(text)) flat += " " + w.text;
    flat += " ";
    std::vector<std::string> out;
    const auto says = [&](const char* phrase) { return flat.find(phrase) != std::string::npos; };
    // The panel, not the idea ("a corner table stores V and O"): named as a panel, or as what
    // it shows.
    const auto panel = [&](const char* name) {
        for (const char* what : {" panel ", " tab ", " shows ", " marks ", " highlights "}) {
            if (says((std::string(" ") + name + what).c_str())) return true;
        }
        return false;
    };
    if (panel("corner table") || says(" in the corner table ")) out.push_back("corner-table");
    if (panel("vertex table") || says(" in the vertex table ")) out.push_back("vertex-table");
    if (says(" the inspector ")) out.push_back("inspector");
    if (panel("id buffer") || says(" id buffer view ")) out.push_back("idbuffer");
    if (panel("statistics") || says(" in the statistics ")) out.push_back("statistics");
    if (panel("predicates")) out.push_back("predicates");
    if (panel("expressions")) out.push_back("expressions");
    return out;
}

bool panelOnSlide(std::string_view panel, const std::vector<std::string>& lines) {
    const auto any = [&](auto&& pred) { return std::any_of(lines.begin(), lines.end(), pred); };
    const auto has = [&](const char* s) {
        return any([&](const std::string& l) { return l.find(s) != std::string::npos; });
    };
    if (panel == "corner-table")
        return any([](const std::string& l) {
            return startsWith(cellWords(l), {"c", "t", "V[c]"});
        });
    if (panel == "vertex-table")
        return any([](const std::string& l) {
            return startsWith(cellWords(l), {"v", "x", "y", "state"});
        });
    if (panel == "statistics")
        return has("Checks of the current mesh") ||
               has("Counts of the run");  // a slide: counts first
    if (panel == "idbuffer")
        return any([](const std::string& l) {
                   return l.rfind("idbuffer", 0) == 0 && l.find(" pixels") != std::string::npos;
               }) ||
               has("The buffer is made at the first triangle");
    if (panel == "predicates") return has("The current operation");
    if (panel == "expressions") return has("identities checked after every step");
    if (panel == "inspector")
        return any([](const std::string& l) { return l.rfind("G[", 0) == 0; }) ||
               has("is the ghost vertex: it has no coordinates");
    return true;  // canvas (its own check), lesson, messages
}

std::optional<std::string> vertexLabelProblem(std::int32_t v, const RenderedSlide& slide,
                                              std::span<const Vec2> points) {
    const std::string id = std::to_string(v);
    const SlideMark* canvas = nullptr;
    const SlideMark* label = nullptr;
    const SlideMark* dot = nullptr;
    for (const SlideMark& m : slide.marks) {
        if (m.role == SlideMarkRole::Canvas) canvas = &m;
        if (m.role == SlideMarkRole::VertexLabel && m.a == v && !label) label = &m;
        if (m.role == SlideMarkRole::Vertex && m.a == v) dot = &m;
    }
    if (!canvas) return "the slide shows no canvas";
    if (!label) {
        return dot ? "vertex " + id +
                         " is drawn without its id: turn the vertex-ids overlay on, or zoom so "
                         "that its label finds room"
                   : "vertex " + id + " is not on the canvas (zoom to it: view = { fit = [...] })";
    }
    if (!label->box.within(canvas->box))
        return "the label of vertex " + id + " is cut off by the canvas's edge";
    for (const SlideMark& m : slide.marks) {
        if (m.role == SlideMarkRole::Legend &&
            (m.box.meets(label->box, 0) || (dot && m.box.meets(dot->box, 0))))
            return "the canvas's legend covers vertex " + id +
                   " (zoom so that a corner of the canvas is free: view = { fit = [...] })";
    }
    const SlideRun* own = labelRun(*label, id, slide);
    if (!own) return "the label of vertex " + id + " is not legible (cut off or drawn over)";
    if (const SlideRun* r = coveringRun(*label, own, slide))
        return "the label of vertex " + id + " is covered by \"" + escapeControls(r->text) + "\"";
    for (const SlideMark& m : slide.marks) {
        if (m.role != SlideMarkRole::Vertex || m.a == v) continue;
        const auto n = static_cast<std::int32_t>(points.size());
        if (v < n && m.a >= 0 && m.a < n && points[v] == points[m.a]) continue;  // a duplicate
        // Points closer than a point's radius read as one dot.
        const float apart = std::hypot(m.box.cx() - (dot ? dot->box.cx() : -1e9f),
                                       m.box.cy() - (dot ? dot->box.cy() : -1e9f));
        if (dot && apart < (dot->box.x1 - dot->box.x0) / 2 + 1)
            return "vertices " + id + " and " + std::to_string(m.a) + " are drawn " +
                   std::to_string(static_cast<int>(apart)) +
                   " pixels apart, as one dot (zoom in: view = { fit = [...] })";
        if (m.box.meets(label->box, 2))
            return "the label of vertex " + id + " sits on vertex " + std::to_string(m.a) +
                   "'s point";
    }
    return std::nullopt;
}

std::optional<std::int64_t> queueCountIn(std::string_view text) {
    const std::vector<Word> w = words(text);
    for (std::size_t i = 0; i + 2 < w.size(); ++i) {
        if (!w[i].number() || (w[i + 1].text != "edges" && w[i + 1].text != "edge")) continue;
        const std::string& next = w[i + 2].text;
        const bool inQueue = next == "in" && i + 4 < w.size() && w[i + 3].text == "the" &&
                             (w[i + 4].text == "queue" || w[i + 4].text == "flip");
        if (next == "wait" || next == "waits" || next == "waiting" || inQueue ||
            (next == "are" && i + 3 < w.size() && w[i + 3].text == "waiting"))
            return std::stoll(w[i].text);
    }
    for (std::size_t i = 0; i + 2 < w.size(); ++i) {
        if (w[i].text == "queue" && (w[i + 1].text == "holds" || w[i + 1].text == "has") &&
            w[i + 2].number())
            return std::stoll(w[i + 2].text);
    }
    return std::nullopt;
}

}  // namespace dlab

// ============================================================================================
// [SECTION] The stops' needs against their slides
// ============================================================================================

namespace dlab {

namespace {

// One thing a stop needs on its slide, and the line that asks for it.
struct Need {
    enum class Kind : std::uint8_t { Vertex, Corner, Triangle, Panel } kind;
    std::int32_t id = -1;
    std::string panel;
    int line = 0;
    std::string why;  // "the text names it", "the answer is this edge"
};

// The corners and triangles a text names: "corner 4", "triangle 1" (one word before the number).
std::vector<std::pair<Need::Kind, std::int32_t>> elementsNamedIn(std::string_view text) {
    const std::vector<Word> w = words(text);
    std::vector<std::pair<Need::Kind, std::int32_t>> out;
    for (std::size_t i = 0; i + 1 < w.size(); ++i) {
        const bool corner = w[i].text == "corner", triangle = w[i].text == "triangle";
        if (!(corner || triangle) || !w[i + 1].number() ||
            !trimmed(text.substr(w[i].end, w[i + 1].begin - w[i].end)).empty())
            continue;
        const auto e =
            std::make_pair(corner ? Need::Kind::Corner : Need::Kind::Triangle, toId(w[i + 1]));
        if (std::find(out.begin(), out.end(), e) == out.end()) out.push_back(e);
    }
    return out;
}

// The things `needs = [...]` declares ("vertex:4", "corner:7", "triangle:3", "panel:statistics").
void declaredNeeds(const LessonStop& s, std::vector<Need>& out) {
    for (const std::string& n : s.needs) {
        const std::size_t colon = n.find(':');
        const std::string kind = n.substr(0, colon), what = n.substr(colon + 1);
        const std::string why = "`needs` declares it";
        if (kind == "panel") {
            out.push_back({Need::Kind::Panel, -1, what, s.needsLine, why});
            continue;
        }
        const std::int32_t id = static_cast<std::int32_t>(std::stol(what));
        const Need::Kind k = kind == "vertex"   ? Need::Kind::Vertex
                             : kind == "corner" ? Need::Kind::Corner
                                                : Need::Kind::Triangle;
        out.push_back({k, id, "", s.needsLine, why});
    }
}

// What stop k needs: the vertices its text and question name, the ends of an edge answer, the
// panels its tab and text name, and what `needs` declares.
std::vector<Need> stopNeeds(const Lesson& lesson, const LessonPlan& plan, std::size_t k,
                            const Inserter& ins) {
    const LessonStop& s = lesson.stops[k];
    const StopState& st = plan.stops[k];
    std::vector<Need> out;
    const auto vertex = [&](std::int32_t v, int line, const char* why) {
        // The ghost vertex has no place to label; a number beyond every vertex is no vertex.
        const bool ghost = ins.isVirtual(v) && ins.options().boundary == Boundary::Exact;
        if (v < 0 || v >= ins.mesh().numVertices() || ghost) return;
        for (const Need& n : out) {
            if (n.kind == Need::Kind::Vertex && n.id == v) return;
        }
        out.push_back({Need::Kind::Vertex, v, "", line, why});
    };
    for (std::int32_t v : verticesNamedIn(st.text)) vertex(v, s.textLine, "the text names it");
    for (std::int32_t v : verticesNamedIn(st.question))
        vertex(v, s.questionLine, "the question names it");
    const Mesh& m = ins.mesh();
    for (const auto& [kind, id] : elementsNamedIn(st.text + "\n" + st.question)) {
        const bool corner = kind == Need::Kind::Corner;
        if (id >= (corner ? m.numCorners() : m.numTriangles())) continue;
        out.push_back({kind, id, "", s.textLine, "the text names it"});
    }
    if (st.answer && st.answer->kind == Answer::Kind::Edge) {
        vertex(static_cast<std::int32_t>(st.answer->a), s.answerLine,
               "the answer is an edge at it");
        vertex(static_cast<std::int32_t>(st.answer->b), s.answerLine,
               "the answer is an edge at it");
    }
    const auto panel = [&](const std::string& p, int line, const char* why) {
        for (const Need& n : out) {
            if (n.kind == Need::Kind::Panel && n.panel == p) return;
        }
        out.push_back({Need::Kind::Panel, -1, p, line, why});
    };
    if (!s.tab.empty() && s.tab != "none") panel(s.tab, s.line, "the stop's tab");
    for (const std::string& p : panelsNamedIn(st.text + "\n" + st.question))
        panel(p, s.textLine, "the text refers to it");
    declaredNeeds(s, out);
    return out;
}

// A corner's or a triangle's label (`text`, drawn in `role` for `id`): nullopt when legible.
std::optional<std::string> labelProblem(SlideMarkRole role, std::int32_t id,
                                        const std::string& noun, const std::string& text,
                                        const RenderedSlide& slide) {
    const SlideMark* canvas = nullptr;
    std::vector<const SlideMark*> labels;
    for (const SlideMark& m : slide.marks) {
        if (m.role == SlideMarkRole::Canvas) canvas = &m;
        if (m.role == role && m.a == id) labels.push_back(&m);
    }
    const std::string name = noun + " " + std::to_string(id);
    if (!canvas) return "the slide shows no canvas";
    if (labels.empty())
        return name + " has no label on the canvas (turn its overlay on, or zoom in)";
    for (const SlideMark* m : labels) {
        if (!m->box.within(canvas->box)) continue;
        const SlideRun* own = labelRun(*m, text, slide);
        if (!own) continue;
        if (!coveringRun(*m, own, slide)) return std::nullopt;
    }
    return "the label of " + name + " is cut off or covered";
}

std::string edgeText(std::int32_t a, std::int32_t b) {
    return std::to_string(std::min(a, b)) + "-" + std::to_string(std::max(a, b));
}

bool sameEdge(const SlideMark& m, std::int32_t a, std::int32_t b) {
    return (m.a == a && m.b == b) || (m.a == b && m.b == a);
}

// Whether a stop is about the in-circle test at it: its text, question or answer says "test".
bool aboutTheTest(const LessonStop& s, const StopState& st) {
    for (const std::string& t : {st.text, st.question, s.answer}) {
        for (const Word& w : words(t)) {
            if (w.text == "test" || w.text == "tested" || w.text.rfind("test_", 0) == 0 ||
                w.text == "incircle")
                return true;
        }
    }
    return s.answer.find("test") != std::string::npos;
}

// The picture against the engine at the stop: the edge under test, the queued edges counted.
void pictureProblems(const Lesson& lesson, const LessonPlan& plan, std::size_t k,
                     const Inserter& ins, const Op* op, const RenderedSlide& slide,
                     std::vector<LessonError>& out) {
    const LessonStop& s = lesson.stops[k];
    const StopState& st = plan.stops[k];
    const int stop = static_cast<int>(k) + 1;
    const Mesh& m = ins.mesh();
    if (op && op->type == OpType::InCircleTest && op->a >= 0 && op->a < m.numCorners() &&
        aboutTheTest(s, st)) {
        const std::int32_t a = m.V[next(op->a)], b = m.V[prev(op->a)];
        const bool ghost =
            ins.options().boundary == Boundary::Exact && (ins.isVirtual(a) || ins.isVirtual(b));
        std::vector<const SlideMark*> drawn;
        for (const SlideMark& mk : slide.marks)
            if (mk.role == SlideMarkRole::TestEdge) drawn.push_back(&mk);
        if (!ghost && drawn.empty())
            out.emplace_back(lesson.file, s.line, stop,
                             "the stop is about the in-circle test of edge " + edgeText(a, b) +
                                 ", but the canvas does not draw it (out of view?)");
        for (const SlideMark* d : drawn) {
            if (!sameEdge(*d, a, b))
                out.emplace_back(lesson.file, s.line, stop,
                                 "the canvas draws " + edgeText(d->a, d->b) +
                                     " as the edge under test, but the engine tests " +
                                     edgeText(a, b));
        }
    }
    const auto queued = static_cast<std::int64_t>(
        std::count_if(slide.marks.begin(), slide.marks.end(),
                      [](const SlideMark& mk) { return mk.role == SlideMarkRole::QueuedEdge; }));
    const auto engineQueue = static_cast<std::int64_t>(ins.flipStack().size());
    const auto countProblem = [&](std::int64_t said, int line, const std::string& where) {
        if (said == queued) return;
        out.emplace_back(lesson.file, line, stop,
                         where + " says " + std::to_string(said) +
                             " queued edges (the engine has " + std::to_string(engineQueue) +
                             "), but the canvas draws " + std::to_string(queued) +
                             " (turn the flip-queue overlay on, or zoom so that they show)");
    };
    if (const auto n = queueCountIn(st.text))
        countProblem(*n, s.textLine, "the text");
    else if (s.text.find("{{queue}}") != std::string::npos)
        countProblem(engineQueue, s.textLine, "the text");
    if (const auto n = queueCountIn(st.question)) countProblem(*n, s.questionLine, "the question");
}

// The corner-table rows on the slide: the first cell of each line under the table's header.
std::vector<std::int32_t> tableRowsOnSlide(const std::vector<std::string>& lines) {
    std::vector<std::int32_t> out;
    std::size_t columns = 0;
    for (const std::string& line : lines) {
        const std::vector<std::string> w = cellWords(line);
        if (startsWith(w, {"c", "t", "V[c]"})) {
            columns = w.size();
            continue;
        }
        if (columns == 0 || w.size() + 1 < columns || w.empty() || w[0].size() > 9 ||
            !std::all_of(w[0].begin(), w[0].end(),
                         [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
            continue;
        out.push_back(static_cast<std::int32_t>(std::stol(w[0])));
    }
    return out;
}

// A stop whose text points at the corner table while an operation changed cells: one of the
// rows it changed must be on the slide (the table scrolls to them; a short tab may not show one).
std::optional<std::string> changedRowsProblem(const Journal& journal,
                                              const std::vector<std::string>& lines) {
    const Op* op = journal.current();
    if (!op || op->numChanges == 0 || op->numChanges > 64) return std::nullopt;
    std::vector<std::int32_t> changed;
    for (std::uint32_t i = 0; i < op->numChanges; ++i)
        changed.push_back(journal.changes()[op->firstChange + i].corner());
    const std::vector<std::int32_t> rows = tableRowsOnSlide(lines);
    for (std::int32_t c : changed) {
        if (std::find(rows.begin(), rows.end(), c) != rows.end()) return std::nullopt;
    }
    std::string list;
    for (std::size_t i = 0; i < changed.size() && i < 8; ++i)
        list += (i ? ", " : "") + std::to_string(changed[i]);
    return "the corner table on the slide shows none of the rows the operation changed (" + list +
           "): give the tab more room (a shorter text), or declare the rows it needs";
}

}  // namespace

std::vector<LessonError> renderedSlideProblems(const Lesson& lesson, const LessonPlan& plan,
                                               const std::vector<RenderedSlide>& slides) {
    std::vector<LessonError> out;
    auto ins = makeInserter(lesson);
    Journal journal(*ins);
    for (std::size_t k = 0; k < lesson.stops.size() && k < plan.stops.size() && k < slides.size();
         ++k) {
        journal.seek(plan.stops[k].position);
        const RenderedSlide& slide = slides[k];
        const int stop = static_cast<int>(k) + 1;
        for (const Need& n : stopNeeds(lesson, plan, k, *ins)) {
            std::optional<std::string> why;
            switch (n.kind) {
                case Need::Kind::Vertex:
                    why = vertexLabelProblem(n.id, slide, lesson.points);
                    break;
                case Need::Kind::Corner:
                    why = labelProblem(SlideMarkRole::CornerLabel, n.id, "corner",
                                       std::to_string(n.id), slide);
                    break;
                case Need::Kind::Triangle:
                    why = labelProblem(SlideMarkRole::TriangleLabel, n.id, "triangle",
                                       "t" + std::to_string(n.id), slide);
                    break;
                case Need::Kind::Panel:
                    if (!panelOnSlide(n.panel, slide.lines))
                        why = "the " + n.panel + " panel is not on the slide (tab = \"" + n.panel +
                              "\" shows it)";
                    break;
            }
            if (!why && n.kind == Need::Kind::Panel && n.panel == "corner-table" &&
                n.why == std::string("the text refers to it"))
                why = changedRowsProblem(journal, slide.lines);
            if (why) out.emplace_back(lesson.file, n.line, stop, *why + " (" + n.why + ")");
        }
        pictureProblems(lesson, plan, k, *ins, journal.current(), slide, out);
    }
    return out;
}

}  // namespace dlab
