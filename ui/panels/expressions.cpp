// The corner-expression console: type `r(o(n(7)))` or `c.n.o.r` (c = the selected corner), see
// the value and the path of corners drawn on the canvas; and watches, identities such as
// o(o(c)) == c checked after every step, which pause a running animation at the first
// operation that breaks one and name that operation and corner.
#include "core/teaching/describe.h"
#include "ui/gui.h"
#include "ui/panels/canvas_looks.h"
#include "ui/panels/panels.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace dlab::ui {

namespace {

// The canvas colours of the path (the marks' table: distinct from every colour the canvas itself
// uses, so that tests can find the path in a screenshot).
const ImU32 kPathColour = lookOf(Mark::ExpressionPath).colour;
const ImU32 kResultColour = kPathColour;

// Above this many corners a step's watches look only at the corners it changed (and their
// neighbours): every corner after every operation would stall a large run.
constexpr std::int32_t kWatchAllCorners = 6000;  // six standard watches over 6000 corners: ~3 ms

ExprContext contextOf(const Engine& e) {
    ExprContext ctx;
    if (e.showsVirtual()) {
        ctx.firstVirtual = e.inserter().firstVirtual();
        ctx.ghost = e.options().boundary == Boundary::Exact;
    }
    return ctx;
}

std::string pathText(const std::vector<PathStep>& path) {
    std::string s;
    for (const PathStep& p : path) {
        if (!s.empty()) s += ",  ";
        s += std::to_string(p.from) + " -" + p.op + "-> " + std::to_string(p.to);
    }
    return s;
}

// Evaluates with c bound to the selection; an expression that needs c without a selection
// gets a clear message rather than the evaluator's "unbound variable".
ExprResult evaluateWithSelection(const CornerExpr& expr, const AppState& st) {
    const Mesh& m = st.engine.mesh();
    const std::int32_t c = st.selection.corner;
    if (expr.uses("c") && (c == kNone || c >= m.numCorners())) {
        ExprResult r;
        r.error.kind = ExprError::Kind::Range;
        r.error.message =
            "c is the selected corner: select one first (click near a corner, or a row of the "
            "corner table)";
        return r;
    }
    return expr.uses("c") ? expr.evaluateAt(m, c, contextOf(st.engine))
                          : expr.evaluate(m, {}, contextOf(st.engine));
}

// The corners whose V or O the ops between two positions changed, with the corners of their
// triangles and across their edges (identities look one step around a corner).
std::vector<std::int32_t> cornersChangedBetween(const Engine& e, std::size_t a, std::size_t b,
                                                bool& tooMany) {
    tooMany = false;
    std::vector<std::int32_t> out;
    const Journal* j = e.journal();
    if (!j) return out;
    const std::size_t lo = std::min(a, b), hi = std::min(std::max(a, b), j->ops().size());
    const Mesh& m = e.mesh();
    std::unordered_set<std::int32_t> seen;
    auto add = [&](std::int32_t c) {
        if (c < 0 || c >= m.numCorners()) return;
        const std::int32_t t = tri(c);
        for (std::int32_t k = 3 * t; k < 3 * t + 3; ++k) {
            if (seen.insert(k).second) out.push_back(k);
            const std::int32_t o = m.O[k];
            if (o >= 0 && o < m.numCorners()) {
                for (std::int32_t q = 3 * tri(o); q < 3 * tri(o) + 3; ++q) {
                    if (seen.insert(q).second) out.push_back(q);
                }
            }
        }
    };
    for (std::size_t i = lo; i < hi; ++i) {
        const Op& op = j->ops()[i];
        if (op.numChanges > 20000 || out.size() > 200000) {
            tooMany = true;
            return {};
        }
        for (std::uint32_t k = 0; k < op.numChanges; ++k)
            add(j->changes()[op.firstChange + k].corner());
    }
    return out;
}

// One watch at the current state. `corners` null: every corner.
WatchReport checkOne(const WatchEntry& w, const Engine& e,
                     const std::vector<std::int32_t>* corners) {
    const Mesh& m = e.mesh();
    const ExprContext ctx = contextOf(e);
    if (!w.expr->uses("c")) {
        // A fixed statement (V[7] != 3): false fails; a cell that does not exist yet is no failure.
        WatchReport rep;
        const ExprResult r = w.expr->evaluate(m, {}, ctx);
        if (!r.ok()) {
            const bool notYet =
                r.error.kind == ExprError::Kind::Range || r.error.kind == ExprError::Kind::Boundary;
            rep.ok = notYet;
            rep.message =
                (notYet ? "does not apply yet: " : "cannot be evaluated: ") + r.error.message;
        } else {
            rep.ok = r.value->kind != ValueKind::Truth || r.value->truth;
            rep.checked = 1;
            rep.message = rep.ok ? "holds" : w.text + " is false";
        }
        rep.failure = r;
        return rep;
    }
    if (corners) return checkWatchOn(*w.expr, m, *corners, ctx);
    return checkWatch(*w.expr, m, ctx);
}

// Checks every enabled watch; returns the index of the first one that newly fails, or -1.
// Updates each watch's status and failing flag. A check of some corners only (`corners` set)
// can find a failure but cannot clear one: the failing corner may lie elsewhere.
int checkAll(AppState& st, const std::vector<std::int32_t>* corners, WatchReport* firstFailure) {
    int first = -1;
    for (std::size_t i = 0; i < st.expressions.watches.size(); ++i) {
        WatchEntry& w = st.expressions.watches[i];
        if (!w.enabled || !w.expr) continue;
        WatchReport rep = checkOne(w, st.engine, corners);
        const bool wasFailing = w.failing;
        if (rep.ok && corners && wasFailing) continue;
        w.failing = !rep.ok;
        w.status = rep.message;
        if (w.failing && !wasFailing && first < 0) {
            first = static_cast<int>(i);
            if (firstFailure) *firstFailure = std::move(rep);
        }
    }
    return first;
}

std::string opName(const Engine& e) {
    const Op* op = e.current();
    if (!op) return "before the first operation";
    return opLabel(e.position()) + " (" + toString(op->type) + ": " + describe(*op, e.inserter()) +
           ")";
}

void reportFailure(AppState& st, const WatchEntry& w, const WatchReport& rep, bool runMoved) {
    const std::string where = opName(st.engine);
    st.log(Message::Level::Error, "watch " + w.text + " fails after " + where + ": " + rep.message);
    if (rep.corner != kNone) {
        // Show where: select the failing corner (the table scrolls to it).
        st.select(rep.corner);
        st.selection.jumpToCorner = rep.corner;
    }
    if ((runMoved || st.run.running) && st.expressions.pauseOnFailure) {
        st.run.running = false;
        st.run.stop("watch " + w.text + " fails" +
                        (rep.corner != kNone ? " at c = " + std::to_string(rep.corner) : ""),
                    st.engine.position(), st.engine.run());
    }
}

// Re-evaluates the live expression when the mesh or the selection changed.
void refreshLive(AppState& st) {
    ExpressionState& ex = st.expressions;
    if (ex.live.empty()) return;
    if (ex.liveVersion == st.engine.version() && ex.liveCorner == st.selection.corner) return;
    ex.liveVersion = st.engine.version();
    ex.liveCorner = st.selection.corner;
    ex.path.clear();
    ex.result.reset();
    const auto expr = CornerExpr::parse(ex.live);
    if (!expr) return;
    ExprResult r = evaluateWithSelection(*expr, st);
    ex.path = std::move(r.path);
    ex.result = r.value;
}

// A curved arrow from a to b; returns the middle of the curve (where its label goes).
ImVec2 PathArrow(ImDrawList* dl, ImVec2 a, ImVec2 b, ImU32 col, float w) {
    const float dx = b.x - a.x, dy = b.y - a.y, len = std::sqrt(dx * dx + dy * dy);
    if (len < 2) return a;
    const float ux = dx / len, uy = dy / len;
    // Stop short of the label at b, and bow the line a little so that a -> b and b -> a differ.
    const ImVec2 end(b.x - ux * 9, b.y - uy * 9);
    const ImVec2 mid((a.x + end.x) / 2 - uy * len * 0.12f, (a.y + end.y) / 2 + ux * len * 0.12f);
    dl->AddBezierQuadratic(a, mid, end, col, w, 16);
    const float s = 8 + w * 2;
    const float hx = end.x - mid.x, hy = end.y - mid.y,
                hl = std::max(1e-3f, std::sqrt(hx * hx + hy * hy));
    const float vx = hx / hl, vy = hy / hl;
    dl->AddTriangleFilled(
        end, ImVec2(end.x - vx * s - vy * s * 0.5f, end.y - vy * s + vx * s * 0.5f),
        ImVec2(end.x - vx * s + vy * s * 0.5f, end.y - vy * s - vx * s * 0.5f), col);
    // The quadratic curve at t = 1/2.
    return ImVec2(0.25f * a.x + 0.5f * mid.x + 0.25f * end.x,
                  0.25f * a.y + 0.5f * mid.y + 0.25f * end.y);
}

}  // namespace

bool evaluateExpression(AppState& st, const std::string& text) {
    ExpressionState& ex = st.expressions;
    ExprLine line;
    line.text = text;
    ExprError perr;
    const auto expr = CornerExpr::parse(text, &perr);
    bool ok = false;
    if (!expr) {
        line.answer = perr.message;
        line.errorColumn = perr.column;
    } else {
        const ExprResult r = evaluateWithSelection(*expr, st);
        if (r.ok()) {
            line.answer = "= " + formatValue(*r.value) + "  (" + toString(r.value->kind) +
                          (expr->uses("c") ? ", c = " + std::to_string(st.selection.corner) : "") +
                          ")";
            ok = true;
        } else {
            line.answer = r.error.message;
            line.errorColumn = r.error.column;
        }
        // The path is drawn even when evaluation stopped at the boundary: it shows how far it got.
        ex.live = text;
        ex.liveVersion = st.engine.version();
        ex.liveCorner = st.selection.corner;
        ex.path = r.path;
        ex.result = r.value;
    }
    line.ok = ok;
    ex.history.push_back(std::move(line));
    if (ex.history.size() > 500) ex.history.erase(ex.history.begin());
    return ok;
}

bool addWatch(AppState& st, const std::string& text) {
    ExprError err;
    auto expr = CornerExpr::parse(text, &err);
    if (!expr) {
        st.log(Message::Level::Error, "watch \"" + text + "\": " + err.message);
        return false;
    }
    if (!expr->isComparison()) {
        st.log(Message::Level::Error,
               "watch \"" + text +
                   "\" is not a comparison: write it as A == B or A != B, e.g. o(o(c)) == c");
        return false;
    }
    for (const WatchEntry& w : st.expressions.watches) {
        if (w.text == expr->text()) return true;
    }
    WatchEntry w;
    w.text = expr->text();
    w.expr = std::make_shared<const CornerExpr>(std::move(*expr));
    st.expressions.watches.push_back(std::move(w));
    st.expressions.watchedVersion = ~std::uint64_t{0};  // check the new one now
    return true;
}

void checkWatches(AppState& st) {
    ExpressionState& ex = st.expressions;
    Engine& e = st.engine;
    refreshLive(st);
    if (ex.watchedVersion == e.version()) return;
    const std::size_t from = ex.watchedPosition, to = e.position();
    const bool firstCheck = ex.watchedVersion == ~std::uint64_t{0};
    ex.watchedVersion = e.version();
    ex.watchedPosition = to;
    const bool any = std::any_of(ex.watches.begin(), ex.watches.end(),
                                 [](const WatchEntry& w) { return w.enabled && w.expr; });
    if (!any) return;

    const bool small = e.mesh().numCorners() <= kWatchAllCorners;
    const bool anyFailing = std::any_of(ex.watches.begin(), ex.watches.end(),
                                        [](const WatchEntry& w) { return w.enabled && w.failing; });
    std::vector<std::int32_t> changed;
    bool tooMany = firstCheck;
    if (!small && !firstCheck) changed = cornersChangedBetween(e, from, to, tooMany);
    // Large meshes: the corners the step changed; all of them when a failing watch may have
    // recovered and nothing is running (a step by hand costs one full check).
    const bool full = small || tooMany || (anyFailing && !st.run.running);
    WatchReport rep;
    int failed = checkAll(st, full ? nullptr : &changed, &rep);
    if (failed < 0) return;

    // A run may have advanced many operations this frame (perhaps to its end): find the first
    // one that broke the watch by replaying them one at a time (they are recorded: this is
    // cheap) with the corners each one changed, and stop there.
    const bool runMoved = st.frameStats.opsStepped > 0;
    if (runMoved && to > from + 1 && !e.batch()) {
        const std::vector<WatchEntry> atTo = ex.watches;
        const WatchReport repAtTo = rep;
        const int failedAtTo = failed;
        for (WatchEntry& w : ex.watches) w.failing = false;
        e.seek(from);
        checkAll(st, nullptr, nullptr);  // the state before: which watches already failed
        failed = -1;
        while (e.position() < to && failed < 0) {
            const std::size_t before = e.position();
            if (!e.forward()) break;
            bool many = false;
            const std::vector<std::int32_t> local =
                cornersChangedBetween(e, before, e.position(), many);
            failed = checkAll(st, many ? nullptr : &local, &rep);
        }
        if (failed < 0) {
            // Beyond the corners the ops changed (a far-reaching expression): report where it
            // was seen.
            e.seek(to);
            ex.watches = atTo;
            failed = failedAtTo;
            rep = repAtTo;
        }
        ex.watchedVersion = e.version();
        ex.watchedPosition = e.position();
    }
    reportFailure(st, ex.watches[static_cast<std::size_t>(failed)], rep, runMoved);
    // reportFailure may have selected a corner: the live path follows at the next refresh.
    refreshLive(st);
}

void DrawExpressionOverlay(AppState& st) {
    const ExpressionState& ex = st.expressions;
    for (int k = 1; st.itemRects.erase("expr-path-" + std::to_string(k)) > 0; ++k) {}
    if (ex.live.empty() || ex.liveVersion != st.engine.version()) return;
    useLook(st, Mark::ExpressionPath);
    const Mesh& m = st.engine.mesh();
    const View& view = st.view;
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->PushClipRect(toIm(view.origin), toIm(view.origin + view.size), true);
    const float w = st.presentation ? 4.0f : 3.0f;
    auto anchor = [&](std::int32_t c, ImVec2& out) {
        float x = 0, y = 0;
        if (!cornerAnchor(st, c, x, y)) return false;
        out = ImVec2(x, y);
        return true;
    };
    auto vertexOk = [&](std::int32_t v) {
        return v >= 0 && v < m.numVertices() &&
               !(st.engine.isVirtual(v) && st.engine.showsVirtual());
    };
    ImFont* font = fonts().ui;
    const float fs = ImGui::GetFontSize();
    int stepNo = 0;
    for (const PathStep& s : ex.path) {
        ++stepNo;
        if (!canvasHasRoom(st, dl, 200)) break;
        ImVec2 a, b;
        switch (s.op) {
            case 't':
                if (s.to >= 0 && s.to < m.numTriangles()) {
                    ImVec2 q[3];
                    bool okAll = true;
                    for (int k = 0; k < 3; ++k) {
                        const std::int32_t v = m.V[3 * s.to + k];
                        okAll &= vertexOk(v);
                        if (okAll) q[k] = toIm(view.toScreen(m.G[v]));
                    }
                    if (okAll) dl->AddTriangle(q[0], q[1], q[2], kPathColour, w);
                }
                break;
            case 'v':
            case 'G':
                if (vertexOk(s.to)) {
                    const ImVec2 q = toIm(view.toScreen(m.G[s.to]));
                    dl->AddCircle(q, 11, kPathColour, 0, w);
                    if (anchor(s.from, a)) dl->AddLine(a, q, kPathColour, 1.5f);
                }
                break;
            default:
                if (s.to == kNone) {
                    // The boundary: a cross where the path ran out.
                    if (anchor(s.from, a)) {
                        dl->AddLine(ImVec2(a.x - 8, a.y - 8), ImVec2(a.x + 8, a.y + 8), kPathColour,
                                    w);
                        dl->AddLine(ImVec2(a.x - 8, a.y + 8), ImVec2(a.x + 8, a.y - 8), kPathColour,
                                    w);
                    }
                } else if (anchor(s.from, a) && anchor(s.to, b)) {
                    const ImVec2 at = PathArrow(dl, a, b, kPathColour, w);
                    // The step's number and operator in a box on the curve ("2.o").
                    char label[24];
                    std::snprintf(label, sizeof label, "%d.%c", stepNo, s.op);
                    const ImVec2 ts = font->CalcTextSizeA(fs, 1e9f, 0, label);
                    const ImVec2 l0(at.x - ts.x / 2 - 3, at.y - ts.y / 2),
                        l1(at.x + ts.x / 2 + 3, at.y + ts.y / 2);
                    dl->AddRectFilled(l0, l1, kPathColour, 3);
                    dl->AddText(font, fs, ImVec2(l0.x + 3, l0.y), IM_COL32(255, 255, 255, 255),
                                label);
                    st.itemRects["expr-path-" + std::to_string(stepNo)] = {l0.x, l0.y, l1.x, l1.y};
                }
                break;
        }
    }
    if (ex.result && ex.result->kind == ValueKind::Corner) {
        ImVec2 a;
        if (anchor(static_cast<std::int32_t>(ex.result->i), a))
            dl->AddCircle(a, 15, kResultColour, 0, w);
    }
    dl->PopClipRect();
}

namespace {

// What c stands for, and the syntax in a tooltip.
void ShowCornerBinding(AppState& st) {
    const Mesh& m = st.engine.mesh();
    const std::int32_t c = st.selection.corner;
    if (c != kNone && c < m.numCorners()) {
        ImGui::Text("c = %d", c);
        ImGui::SameLine();
        ImGui::TextDisabled("(the selected corner)");
    } else {
        ImGui::TextDisabled("c is unbound: select a corner to use it");
    }
    ImGui::SameLine();
    ImGui::TextDisabled("(?)");
    if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip(
            "Operators n p o l r s u t v, as calls r(o(n(7))) or chains c.n.o.r\n"
            "Tables: V[c] (vertex), O[c] (opposite), G[v] (coordinates)\n"
            "Comparisons: V[n(o(c))] == V[p(c)], t(o(c)) != t(c)\n"
            "The path is drawn on the canvas and follows every step.");
    }
}

// A text field that keeps the keyboard after Enter: what is typed next goes there, not to the
// single-letter shortcuts. `refocus` counts the frames it takes the keyboard back.
bool KeyboardKeepingInput(AppState& st, const char* id, const char* hint, std::string& text,
                          int& refocus, const char* item) {
    if (refocus > 0) ImGui::SetKeyboardFocusHere();
    const bool enter =
        ImGui::InputTextWithHint(id, hint, &text, ImGuiInputTextFlags_EnterReturnsTrue);
    RecordItem(st, item);
    if (ImGui::IsItemActive()) refocus = 0;
    if (enter) {
        ImGui::SetKeyboardFocusHere(-1);  // from the next frame on, as Enter deactivated it
        refocus = ExpressionState::kRefocusFrames;
    }
    return enter;
}

// The console's input line: Enter or Eval evaluates it.
void ShowConsoleInput(AppState& st) {
    ExpressionState& ex = st.expressions;
    ImGui::PushFont(fonts().mono);
    ImGui::SetNextItemWidth(-70);
    const bool enter = KeyboardKeepingInput(st, "##expr", "r(o(n(7)))  or  c.n.o.r", ex.input,
                                            ex.refocusInput, "expr-input");
    ImGui::PopFont();
    ImGui::SameLine();
    const bool eval = ImGui::Button("Eval");
    RecordItem(st, "expr-eval");
    if (enter || eval) ex.refocusInput = ExpressionState::kRefocusFrames;
    if ((enter || eval) && !ex.input.empty()) {
        evaluateExpression(st, ex.input);
        ex.input.clear();
    }
}

// The log of earlier answers in its own scrolling box, in the height left (at least three
// lines), the newest line kept in view.
void ShowHistory(const ExpressionState& ex) {
    const float logH =
        std::max(ImGui::GetTextLineHeightWithSpacing() * 3, ImGui::GetContentRegionAvail().y);
    ImGui::BeginChild("##exprlog", ImVec2(0, logH), true);
    ImGui::PushFont(fonts().mono);
    for (const ExprLine& line : ex.history) {
        ImGui::TextDisabled(">");
        ImGui::SameLine();
        ImGui::TextUnformatted(line.text.c_str());
        if (line.ok) {
            ImGui::TextColored(ImVec4(0.05f, 0.45f, 0.15f, 1), "  %s", line.answer.c_str());
        } else {
            // A caret under the culprit, as a compiler does.
            ImGui::TextColored(
                ImVec4(0.8f, 0.1f, 0.1f, 1), "  %s^",
                std::string(std::min<std::size_t>(line.errorColumn, 200), ' ').c_str());
            ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.8f, 0.1f, 0.1f, 1));
            ImGui::TextWrapped("  %s", line.answer.c_str());
            ImGui::PopStyleColor();
        }
    }
    ImGui::PopFont();
    if (ImGui::GetScrollY() >= ImGui::GetScrollMaxY() - 4) ImGui::SetScrollHereY(1.0f);
    ImGui::EndChild();
}

// The expression drawn on the canvas: its value, its path, and buttons to select or clear it.
void ShowLiveExpression(AppState& st) {
    ExpressionState& ex = st.expressions;
    if (ex.live.empty()) return;
    ImGui::TextDisabled("on the canvas:");
    ImGui::SameLine();
    ImGui::TextUnformatted(ex.live.c_str());
    if (ex.result) {
        ImGui::SameLine();
        ImGui::TextColored(ImVec4(0.84f, 0.0f, 0.47f, 1), "= %s", formatValue(*ex.result).c_str());
    }
    // The path and the buttons share a line (a short column keeps the watches below in sight).
    if (!ex.path.empty()) {
        ImGui::TextDisabled("path: %s", pathText(ex.path).c_str());
        ImGui::SameLine();
    }
    if (ex.result && ex.result->kind == ValueKind::Corner && ex.result->i >= 0) {
        if (ImGui::SmallButton("Select the result")) {
            st.select(static_cast<std::int32_t>(ex.result->i));
            st.selection.jumpToCorner = st.selection.corner;
        }
        ImGui::SameLine();
    }
    if (ImGui::SmallButton("Clear")) {
        ex.live.clear();
        ex.path.clear();
        ex.result.reset();
        ex.history.clear();
    }
}

// One watch: on/off, its verdict and text, a remove button; returns whether that was clicked.
bool ShowWatch(ExpressionState& ex, WatchEntry& w) {
    if (ImGui::Checkbox("##on", &w.enabled)) ex.watchedVersion = ~std::uint64_t{0};
    ImGui::SameLine();
    const ImVec4 col = !w.enabled  ? ImVec4(0.5f, 0.5f, 0.5f, 1)
                       : w.failing ? ImVec4(0.8f, 0.1f, 0.1f, 1)
                                   : ImVec4(0.05f, 0.45f, 0.15f, 1);
    ImGui::TextColored(col, "%s %s", w.enabled ? (w.failing ? "FAIL" : "ok  ") : "off ",
                       w.text.c_str());
    if (ImGui::IsItemHovered() && !w.status.empty()) ImGui::SetTooltip("%s", w.status.c_str());
    ImGui::SameLine();
    const bool remove = ImGui::SmallButton("x");
    if (w.failing && w.enabled) {
        ImGui::PushStyleColor(ImGuiCol_Text, col);
        ImGui::TextWrapped("   %s", w.status.c_str());
        ImGui::PopStyleColor();
    }
    return remove;
}

// The watches: identities checked after every step, one line each.
void ShowWatches(ExpressionState& ex) {
    ImGui::Separator();
    ImGui::TextUnformatted("Watches");
    ImGui::SameLine();
    ImGui::TextDisabled("identities checked after every step");
    ImGui::Checkbox("Pause the run when one fails", &ex.pauseOnFailure);
    int remove = -1;
    ImGui::PushFont(fonts().mono);
    for (std::size_t i = 0; i < ex.watches.size(); ++i) {
        ImGui::PushID(static_cast<int>(i));
        if (ShowWatch(ex, ex.watches[i])) remove = static_cast<int>(i);
        ImGui::PopID();
    }
    ImGui::PopFont();
    if (remove >= 0) ex.watches.erase(ex.watches.begin() + remove);
}

// The field that adds a watch, and the standard identities in one click.
void ShowAddWatch(AppState& st) {
    ExpressionState& ex = st.expressions;
    ImGui::SetNextItemWidth(-150);
    const bool addEnter = KeyboardKeepingInput(st, "##watch", "V[n(o(c))] == V[p(c)]",
                                               ex.watchInput, ex.refocusWatch, "watch-input");
    ImGui::SameLine();
    if ((ImGui::Button("Add") || addEnter) && !ex.watchInput.empty()) {
        if (addWatch(st, ex.watchInput)) ex.watchInput.clear();
    }
    ImGui::SameLine();
    if (ImGui::Button("Standard")) {
        for (const char* s : standardWatches()) addWatch(st, s);
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Add the identities every corner table satisfies");
}

}  // namespace

void ShowExpressions(AppState& st) {
    ShowCornerBinding(st);
    ShowConsoleInput(st);
    // Below the input line everything scrolls (the side column may be short); the history has
    // its own scrolling box.
    ImGui::BeginChild("##exprbody", ImVec2(0, 0), false);
    // The answer first, then the watches, then the log of earlier answers in what is left: an
    // Eval never pushes the watches out of a short column.
    ShowLiveExpression(st);
    ShowWatches(st.expressions);
    ShowAddWatch(st);
    ImGui::Separator();
    ShowHistory(st.expressions);
    ImGui::EndChild();
}

}  // namespace dlab::ui
