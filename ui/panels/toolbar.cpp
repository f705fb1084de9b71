// The step controls (op / insertion / start / end / run with a speed slider), the engine's
// modes, the caption of the current operation and the timeline scrubber.
#include "core/teaching/breakpoint.h"
#include "core/teaching/describe.h"
#include "ui/gui.h"
#include "ui/panels/panels.h"
#include "ui/platform/keys.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace dlab::ui {

namespace {

// The toolbar wraps: the next item goes on this row when `width` more pixels fit, else on a new
// row (small windows, presentation mode's large fonts).
void SameLineOrWrap(float width, float spacing = -1.0f) {
    ImGui::SameLine(0, spacing);
    if (ImGui::GetContentRegionAvail().x < width) ImGui::NewLine();
}

float ButtonWidth(const char* label) {
    return ImGui::CalcTextSize(label, nullptr, true).x + 2 * ImGui::GetStyle().FramePadding.x;
}

// Widths in the toolbar are given at the normal 16-pixel font and grow with it.
float Scaled(float width) { return width * ImGui::GetFontSize() / 16.0f; }

bool ToolButton(AppState& state, const char* label, const char* tip, bool enabled = true,
                bool first = false) {
    if (!first) SameLineOrWrap(ButtonWidth(label));
    if (!enabled) ImGui::BeginDisabled();
    const bool clicked = ImGui::Button(label);
    if (!enabled) ImGui::EndDisabled();
    // Record under the stable part of the label ("Pause###run" -> "run").
    const char* id = std::strstr(label, "###");
    RecordItem(state, id ? id + 3 : label);
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("%s", tip);
    return clicked && enabled;
}

// "Label [combo]": the label first, so that the row reads "Boundary: exact  Locate: walk".
template <class Enum>
bool EnumCombo(AppState& state, const char* label, Enum& value, const std::vector<Enum>& values,
               float width, float spacing = -1.0f) {
    const float w = Scaled(width);
    SameLineOrWrap(ImGui::CalcTextSize(label).x + ImGui::GetStyle().ItemInnerSpacing.x + w,
                   spacing);
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted(label);
    RecordItem(state, (std::string(label) + " label").c_str());
    ImGui::SameLine(0, ImGui::GetStyle().ItemInnerSpacing.x);
    bool changed = false;
    ImGui::SetNextItemWidth(w);
    const std::string id = std::string("##") + label;
    if (ImGui::BeginCombo(id.c_str(), toString(value))) {
        for (Enum v : values) {
            if (ImGui::Selectable(toString(v), v == value)) {
                changed = v != value;
                value = v;
            }
            RecordItem(state, (std::string(label) + ":" + toString(v)).c_str());
        }
        ImGui::EndCombo();
    }
    RecordItem(state, id.c_str() + 2);
    return changed;
}

ImVec4 opColour(OpType t) {
    switch (t) {
        case OpType::LocateStep:
        case OpType::Located: return ImVec4(0.10f, 0.35f, 0.75f, 1);
        case OpType::Split:
        case OpType::SplitEdge: return ImVec4(0.55f, 0.25f, 0.65f, 1);
        case OpType::InCircleTest: return ImVec4(0.10f, 0.50f, 0.20f, 1);
        case OpType::Flip: return ImVec4(0.80f, 0.20f, 0.10f, 1);
        case OpType::SkipDuplicate: return ImVec4(0.75f, 0.45f, 0.0f, 1);
        default: return ImVec4(0.15f, 0.15f, 0.15f, 1);
    }
}

int findBreakpoint(const RunControl& run, const Breakpoint& bp) {
    for (std::size_t i = 0; i < run.breakpoints.size(); ++i) {
        if (run.breakpoints[i].bp == bp) return static_cast<int>(i);
    }
    return -1;
}

// A checkbox for a common breakpoint: on when it is in the list and enabled.
void BreakpointToggle(RunControl& run, const char* text, const Breakpoint& bp) {
    const int i = findBreakpoint(run, bp);
    bool on = i >= 0 && run.breakpoints[i].enabled;
    if (ImGui::Checkbox(text, &on)) {
        if (i >= 0)
            run.breakpoints[i].enabled = on;
        else
            run.breakpoints.push_back({bp, true});
    }
}

void ShowQuickBreakpoints(RunControl& run) {
    ImGui::TextUnformatted("Stop the run...");
    BreakpointToggle(run, "at the next flip", {BreakKind::Flip, std::nullopt});
    BreakpointToggle(run, "at a degenerate case (point on an edge or a vertex, cocircular test)",
                     {BreakKind::Degenerate, std::nullopt});
    BreakpointToggle(run, "at a duplicate point", {BreakKind::Duplicate, std::nullopt});
    BreakpointToggle(run, "after each whole insertion", {BreakKind::Insertion, std::nullopt});
}

// Breakpoints at a vertex k or a corner c (the selected one to start with), and any kind by
// its text form.
void ShowAddBreakpoint(AppState& state) {
    RunControl& run = state.run;
    ImGui::SetNextItemWidth(90);
    ImGui::InputInt("##vertex", &state.dialogs.breakVertex);
    RecordItem(state, "breakpoint-vertex");
    ImGui::SameLine();
    if (ImGui::Button("before vertex k is inserted")) {
        run.breakpoints.push_back({{BreakKind::Insert, state.dialogs.breakVertex}, true});
    }
    ImGui::SetNextItemWidth(90);
    if (state.selection.corner != kNone && state.dialogs.breakCorner < 0)
        state.dialogs.breakCorner = state.selection.corner;
    ImGui::InputInt("##corner", &state.dialogs.breakCorner);
    RecordItem(state, "breakpoint-corner");
    ImGui::SameLine();
    if (ImGui::Button("when corner c changes (V[c] or O[c])")) {
        run.breakpoints.push_back({{BreakKind::Corner, state.dialogs.breakCorner}, true});
    }
    ImGui::SetNextItemWidth(200);
    const bool enter =
        ImGui::InputTextWithHint("##text", "flip, insert:5, corner:17, op:120, incircle:0...",
                                 &state.dialogs.breakText, ImGuiInputTextFlags_EnterReturnsTrue);
    RecordItem(state, "breakpoint-text");
    ImGui::SameLine();
    if (ImGui::Button("Add") || enter) {
        std::string error;
        if (const auto bp = parseBreakpoint(state.dialogs.breakText, &error)) {
            run.breakpoints.push_back({*bp, true});
            state.dialogs.breakText.clear();
        } else {
            state.log(Message::Level::Error, error);
        }
    }
}

// The active breakpoints, each with its meaning, an on/off box and a remove button.
void ShowBreakpointList(RunControl& run) {
    if (run.breakpoints.empty()) ImGui::TextDisabled("no breakpoints: Run goes to the end");
    for (std::size_t i = 0; i < run.breakpoints.size(); ++i) {
        ImGui::PushID(static_cast<int>(i));
        ImGui::Checkbox("##on", &run.breakpoints[i].enabled);
        ImGui::SameLine();
        ImGui::Text("%s  (%s)", toString(run.breakpoints[i].bp).c_str(),
                    explain(run.breakpoints[i].bp).c_str());
        ImGui::SameLine();
        const bool remove = ImGui::SmallButton("x");
        ImGui::PopID();
        if (remove) {
            run.breakpoints.erase(run.breakpoints.begin() + static_cast<std::ptrdiff_t>(i));
            break;
        }
    }
}

// The breakpoints popup: quick toggles for the common ones, any kind by its text form, and the
// list of active breakpoints. A running animation stops where one hits.
void ShowBreakpointsButton(AppState& state) {
    RunControl& run = state.run;
    int active = 0;
    for (const BreakpointEntry& b : run.breakpoints) active += b.enabled;
    char label[48];
    std::snprintf(label, sizeof label, "Breakpoints (%d)###breakpoints", active);
    if (ImGui::Button(label)) ImGui::OpenPopup("##breakpoints");
    RecordItem(state, "breakpoints");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "Where Run stops: the next flip, a degenerate case, vertex k, a corner changing...");
    if (!ImGui::BeginPopup("##breakpoints")) return;
    const ImVec2 at = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    state.itemRects["breakpoints-popup"] = {at.x, at.y, at.x + size.x, at.y + size.y};
    // Esc closes it (unless a text field in it has the keyboard: there Esc leaves the field).
    if (!ImGui::GetIO().WantTextInput && ImGui::IsKeyPressed(key::kEscape, false))
        ImGui::CloseCurrentPopup();
    ShowQuickBreakpoints(run);
    ShowAddBreakpoint(state);
    ImGui::Separator();
    ShowBreakpointList(run);
    ImGui::EndPopup();
}

// The step buttons (start, back and forward by an op or an insertion, end, run) and the speed.
void ShowStepControls(AppState& state) {
    Engine& e = state.engine;
    RunControl& run = state.run;
    const bool canStep = !e.batch();
    const bool atStart = e.position() == 0;
    const bool atEnd = e.atEnd();
    if (ToolButton(state, "|<", "Back to the start (Home)", canStep && !atStart, true)) {
        run.running = false;
        e.toStart();
    }
    if (ToolButton(state, "<<", "Back one insertion (Shift+Left)", canStep && !atStart)) {
        run.running = false;
        e.backInsertion();
    }
    if (ToolButton(state, "<", "Back one operation (Left, Page Up)", canStep && !atStart)) {
        run.running = false;
        e.back();
    }
    if (ToolButton(state, ">", "Forward one operation (Right, Page Down)", canStep && !atEnd)) {
        run.running = false;
        e.forward();
    }
    if (ToolButton(state, ">>", "Forward one insertion (Shift+Right)", canStep && !atEnd)) {
        run.running = false;
        e.forwardInsertion();
    }
    if (ToolButton(state, ">|", "Run to the end at full speed, past every breakpoint (End)",
                   canStep && !atEnd)) {
        run.runToEnd();
    }
    if (ToolButton(state, run.running ? "Pause###run" : "Run###run",
                   "Run or pause the animation; it stops at the breakpoints (Space)",
                   canStep && (run.running || !atEnd))) {
        run.running = !run.running;
    }
    SameLineOrWrap(Scaled(150));
    ImGui::SetNextItemWidth(Scaled(150));
    const bool full = run.opsPerSecond >= RunControl::kFullSpeed;
    ImGui::SliderFloat("##speed", &run.opsPerSecond, 0.5f, RunControl::kFullSpeed,
                       full ? "full speed" : "%.1f ops/s", ImGuiSliderFlags_Logarithmic);
    RecordItem(state, "speed");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "Animation speed in operations per second (right end: as fast as possible)");
}

// The engine's modes: boundary, locator, insertion order and its seed; a change restarts the
// run with the same points.
void ShowModes(AppState& state) {
    const Engine& e = state.engine;
    InsertOptions o = e.options();
    bool changed = EnumCombo(state, "Boundary", o.boundary, valuesIn(kBoundaryNames), 80, 24);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "exact: a ghost vertex, the true Delaunay triangulation with its convex hull\nsuper: "
            "the paper's finite super-triangle (can lose hull triangles)");
    // The GL ID buffer draws on this window's context: without one its locators are not offered.
    std::vector<LocatorKind> locators;
    for (const auto& l : kLocatorNames)
        if (e.hasGl() || !needsGl(l.value)) locators.push_back(l.value);
    changed |= EnumCombo(state, "Locate", o.locator, locators, e.hasGl() ? 175 : 120);
    changed |= EnumCombo(state, "Order", o.order, valuesIn(kOrderNames), 80);
    if (o.order != OrderKind::Input) {
        SameLineOrWrap(ImGui::CalcTextSize("Seed").x + Scaled(110));
        ImGui::AlignTextToFramePadding();
        ImGui::TextUnformatted("Seed");
        ImGui::SameLine(0, ImGui::GetStyle().ItemInnerSpacing.x);
        int seed = static_cast<int>(o.seed);
        ImGui::SetNextItemWidth(Scaled(100));
        if (ImGui::InputInt("##seed", &seed) && seed >= 0) {
            o.seed = static_cast<std::uint64_t>(seed);
            changed = true;
        }
        RecordItem(state, "seed");
    }
    if (changed) state.setUserOptions(o);
}

// What a click on the canvas does: queue a point, or an edit of the finished mesh.
void ShowCanvasTool(AppState& st) {
    const float width = ImGui::CalcTextSize("constrain segment").x + Scaled(40);
    SameLineOrWrap(ImGui::CalcTextSize("Click").x + width);
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted("Click");
    ImGui::SameLine(0, ImGui::GetStyle().ItemInnerSpacing.x);
    ImGui::SetNextItemWidth(width);
    int tool = static_cast<int>(st.tool);
    if (ImGui::Combo("##tool", &tool, kCanvasToolNames, IM_ARRAYSIZE(kCanvasToolNames))) {
        st.tool = static_cast<AppState::CanvasTool>(tool);
        st.toolFirstVertex = kNone;
    }
    RecordItem(st, "tool");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "What a click on the canvas does. add points: queue a new point. The others edit the "
            "finished mesh, each edit stepped like the run:\nremove vertex: the vertex clicked "
            "(or Delete: the selected corner's vertex)\nconstrain segment / free segment: the "
            "segment between the two vertices clicked\nmove vertex: the vertex clicked, then where "
            "it goes "
            "(inside the hull of the others)");
}

}  // namespace

void ShowToolbar(AppState& state) {
    ShowStepControls(state);
    SameLineOrWrap(ButtonWidth("Breakpoints (00)"));
    ShowBreakpointsButton(state);
    ShowModes(state);
    ShowCanvasTool(state);
}

namespace {

// "[op 28] Flip: ": op N is the N-th operation done, as on the timeline ("op 28 of 120") and in
// breakpoints ("op:28").
std::string opPrefix(const Engine& e, const Op& op) {
    return opLabel(e.position()) + " " + toString(op.type) + ": ";
}

}  // namespace

std::string pointCountsText(const Engine& e) {
    if (e.repairs())  // no point is inserted: the triangles were given
        return std::to_string(e.points().size()) + " points, triangles given (none inserted)";
    const InsertStats& st = e.inserter().stats();
    std::string s = std::to_string(st.inserted) + " of " + std::to_string(e.points().size()) +
                    " points inserted";
    if (st.duplicates > 0) {
        s += ", " + std::to_string(st.duplicates) +
             (st.duplicates == 1 ? " duplicate skipped" : " duplicates skipped");
    }
    return s;
}

std::string captionText(const AppState& state) {
    const Engine& e = state.engine;
    if (e.batch()) {
        return "batch result: " + std::to_string(e.mesh().numTriangles()) + " triangles, " +
               std::to_string(e.points().size()) + " points (" + e.batchReason() + ")";
    }
    if (const Op* op = e.current()) return opPrefix(e, *op) + describe(*op, e.inserter());
    if (e.editing()) return opLabel(e.position()) + " " + editOpText(e);
    return std::to_string(e.points().size()) +
           " points ready: press Right (or >) to take the first step. F1 lists every shortcut.";
}

void ShowCaption(AppState& state) {
    const Engine& e = state.engine;
    ImGui::PushFont(fonts().caption);
    const Op* op = e.batch() ? nullptr : e.current();
    if (op) {
        // The operation's name in its colour, then what it did.
        ImGui::TextColored(opColour(op->type), "%s", opPrefix(e, *op).c_str());
        ImGui::SameLine(0, 0);
        ImGui::TextWrapped("%s", describe(*op, e.inserter()).c_str());
    } else if (e.batch() || e.editing()) {
        ImGui::TextWrapped("%s", captionText(state).c_str());
    } else {
        ImGui::TextDisabled("%s", captionText(state).c_str());
    }
    RecordItem(state, "caption");
    ImGui::PopFont();
    if (!state.run.stopReason.empty() && !state.run.running &&
        state.run.stopPosition == e.position() && state.run.stopRun == e.run()) {
        ImGui::SameLine();
        ImGui::TextDisabled("(stopped: %s)", state.run.stopReason.c_str());
    }
}

std::string timelineText(const Engine& e) {
    if (e.batch()) return pointCountsText(e);
    const bool complete = e.recorded() > 0 && e.atRunEnd() &&
                          (e.editor() || e.journal()->ops().back().type == OpType::Finalize);
    std::string s = "op " + std::to_string(e.position());
    if (complete)
        s += " of " + std::to_string(e.recorded());
    else if (e.recorded() > 0)
        s += " of " + std::to_string(e.recorded()) + " recorded so far";
    else
        s += " (recorded as you step)";
    s += "   |   " + pointCountsText(e);
    if (const Editor* ed = e.editor(); ed && !ed->edits().empty())
        s += ", " + std::to_string(ed->editsDone()) + " of " + std::to_string(ed->edits().size()) +
             (ed->edits().size() == 1 ? " edit done" : " edits done");
    return s;
}

void ShowTimeline(AppState& state) {
    Engine& e = state.engine;
    if (e.batch()) return;
    const int total = static_cast<int>(e.recorded());
    int pos = static_cast<int>(e.position());
    // The position in words beside the slider, where its handle cannot cover it; on a narrow
    // canvas only the position (the counts are in Statistics too).
    std::string text = timelineText(e);
    if (ImGui::CalcTextSize(text.c_str()).x + Scaled(200) > ImGui::GetContentRegionAvail().x)
        text = text.substr(0, text.find("   |   "));
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted(text.c_str());
    RecordItem(state, "timeline-text");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(std::max(80.0f, ImGui::GetContentRegionAvail().x));
    if (ImGui::SliderInt("##timeline", &pos, 0, std::max(total, 1), "")) {
        state.run.running = false;
        e.seek(static_cast<std::size_t>(std::max(0, pos)));
    }
    RecordItem(state, "timeline");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Timeline: drag to any recorded operation");
}

namespace {

// The stepping time of a full-speed frame: what is left of the target frame time after the rest
// (not stepping) of the last frame, from the previous call to this one. A large mesh is redrawn
// every other frame (updateCanvasMesh): the dearer of the last two frames sets the budget, or a
// cheap frame would hand its slack to the dear one.
double fullSpeedBudget(RunControl& run, double nowMs) {
    double budget = run.frameBudgetMs;
    if (run.lastAdvanceMs >= 0) {
        const double rest = nowMs - run.lastAdvanceMs - run.lastStepMs;
        if (rest >= 0 && rest < 1000) {
            budget = std::clamp(run.targetFrameMs - std::max(rest, run.previousRestMs), 2.0,
                                run.frameBudgetMs);
            run.previousRestMs = rest;
        }
    }
    return budget;
}

}  // namespace

void advanceRun(AppState& state, double dt) {
    RunControl& run = state.run;
    Engine& e = state.engine;
    const std::size_t startPos = e.position();
    run.clearStaleStop(startPos, e.run());
    struct Count {
        AppState& st;
        std::size_t from;
        ~Count() { st.frameStats.opsStepped = st.engine.position() - from; }
    } count{state, startPos};
    if (!run.running) {
        run.lastAdvanceMs = -1;  // a pause is not a slow frame
        run.previousRestMs = 0;
        run.toEnd = false;  // a paused run goes on at the slider's speed
        return;
    }
    if (e.batch() || e.atEnd()) {
        run.running = false;
        run.toEnd = false;
        run.stop("end of the run", e.position(), e.run());
        return;
    }
    auto stepOnce = [&]() -> bool {
        if (!e.forward()) {
            run.running = false;
            run.toEnd = false;
            run.stop("end of the run", e.position(), e.run());
            return false;
        }
        if (run.toEnd) return true;  // End runs past the breakpoints; Run stops at them
        for (const BreakpointEntry& b : run.breakpoints) {
            if (b.enabled && e.hits(b.bp)) {
                run.running = false;
                run.stop("breakpoint: " + explain(b.bp), e.position(), e.run());
                state.log(Message::Level::Info,
                          "run stopped at " + opLabel(e.position()) + ": " + run.stopReason);
                return false;
            }
        }
        return true;
    };
    if (run.fullSpeed()) {
        const auto t0 = std::chrono::steady_clock::now();
        const double nowMs =
            std::chrono::duration<double, std::milli>(t0.time_since_epoch()).count();
        const double budget = fullSpeedBudget(run, nowMs);
        run.lastAdvanceMs = nowMs;
        struct Stepped {
            RunControl& run;
            std::chrono::steady_clock::time_point t0;
            ~Stepped() {
                run.lastStepMs =
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                        .count();
            }
        } stepped{run, t0};
        // Check the clock every 64 ops: cheap, and a frame stays within its budget.
        for (int i = 0;; ++i) {
            if (!stepOnce()) return;
            if ((i & 63) == 63) {
                const double ms =
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                        .count();
                if (ms > budget) break;
            }
        }
        return;
    }
    run.carry += dt * run.opsPerSecond;
    while (run.carry >= 1.0) {
        run.carry -= 1.0;
        if (!stepOnce()) return;
    }
}

}  // namespace dlab::ui
