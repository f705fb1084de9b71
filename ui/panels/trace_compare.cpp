// Student trace: a student's run, as a trace (JSON Lines), compared with ours on the
// same points and options. Opens at the first operation where the runs differ, shows both
// operations and the evidence, steps both runs side by side (one mesh change at a time), and
// draws the student's triangles that are not ours over the canvas.
#include "ui/files/files.h"
#include "ui/panels/canvas_looks.h"
#include "ui/panels/panels.h"

#include <imgui.h>

#include <algorithm>
#include <utility>

namespace dlab::ui {

namespace {

// Our own trace is a whole recorded run: keep it to what the GUI records anyway.
constexpr std::size_t kMaxComparedPoints = 20000;

bool stale(const AppState& st) {
    const auto& tc = st.traceCompare;
    return !tc.student || st.engine.points() != tc.points ||
           !sameRun(st.engine.options(), tc.options);
}

// The next (dir > 0) or previous mesh-changing op of a trace from op index `from` (exclusive);
// `none` when there is none.
std::size_t nextChange(const TraceFile& f, std::size_t from, int dir, std::size_t none) {
    if (dir > 0) {
        for (std::size_t k = from == none ? 0 : from + 1; k < f.ops.size(); ++k) {
            if (f.ops[k].changesMesh()) return k;
        }
        return none;
    }
    for (std::size_t k = std::min(from, f.ops.size()); k-- > 0;) {
        if (f.ops[k].changesMesh()) return k;
    }
    return none;
}

// Both runs one mesh change forward or back: ours by the engine (to just after the op), the
// student's by the number of their ops applied.
void stepBoth(AppState& st, int dir) {
    auto& tc = st.traceCompare;
    const std::size_t none = static_cast<std::size_t>(-1);
    const std::size_t oursAt = st.engine.position() == 0 ? none : st.engine.position() - 1;
    const std::size_t studentAt = tc.studentPos == 0 ? none : tc.studentPos - 1;
    if (dir > 0) {
        const std::size_t a = nextChange(*tc.ours, oursAt, 1, none),
                          b = nextChange(*tc.student, studentAt, 1, none);
        if (a != none) st.engine.seek(a + 1);
        if (b != none) tc.studentPos = b + 1;
    } else {
        const std::size_t a = oursAt == none ? none : nextChange(*tc.ours, oursAt, -1, none);
        const std::size_t b =
            studentAt == none ? none : nextChange(*tc.student, studentAt, -1, none);
        st.engine.seek(a == none ? 0 : a + 1);
        tc.studentPos = b == none ? 0 : b + 1;
    }
    st.run.running = false;
}

// A trace made on other points (or around a super-triangle where this run has the ghost vertex)
// names vertices this run does not have: what to load first, in one line; "" when it fits.
std::string wrongRunFor(const AppState& st, const TraceFile& student) {
    const auto n = static_cast<std::int32_t>(st.engine.points().size());
    const bool super = st.engine.options().boundary == Boundary::Super;
    const std::int32_t most = largestVertex(student);
    if (most < n + (super ? 3 : 1)) return "";
    const std::string uses = student.name + " uses vertices up to " + std::to_string(most);
    if (!super && most < n + 3) {
        return uses + ", the super-triangle's after the " + std::to_string(n) +
               " points: choose boundary \"super\" in the toolbar (or open the assignment it "
               "belongs to), then open the trace again (nothing was changed)";
    }
    return uses + ", but " +
           (n == 0 ? std::string("no points are loaded")
                   : "the points loaded here (" + st.source + ") are " + std::to_string(n)) +
           ": open the points or the assignment (.toml) the trace belongs to first, then the "
           "trace (nothing was changed)";
}

// The point a trace inserts first: its first split's "vertex", or the one vertex all the
// triangles of that split share; kNone when unknown.
std::int32_t firstInserted(const TraceFile& f) {
    for (const TraceOp& op : f.ops) {
        if (op.type != OpType::Split && op.type != OpType::SplitEdge) continue;
        if (op.vertex && *op.vertex >= 0) return *op.vertex;
        if (op.triangles.empty()) return kNone;
        std::vector<std::int32_t> common(op.triangles[0].begin() + 1, op.triangles[0].end());
        for (const auto& t : op.triangles) {
            std::erase_if(
                common, [&](std::int32_t v) { return std::count(t.begin() + 1, t.end(), v) == 0; });
        }
        return common.size() == 1 ? common[0] : kNone;
    }
    return kNone;
}

// When the two runs start with different points, the likely cause: another insertion order.
std::string orderHint(const AppState& st, const TraceFile& ours, const TraceFile& student) {
    const std::int32_t a = firstInserted(ours), b = firstInserted(student);
    if (a == kNone || b == kNone || a == b) return "";
    return "; the trace inserts point " + std::to_string(b) + " first, this run point " +
           std::to_string(a) + " (order " + toString(st.engine.options().order) +
           "): choose the order the trace was made in (the assignment's is input), or open the "
           "assignment";
}

void goToDifference(AppState& st) {
    auto& tc = st.traceCompare;
    st.run.running = false;
    st.engine.seek(std::min(tc.diff.refOp + 1, tc.ours->ops.size()));
    tc.studentPos = std::min(tc.diff.studentOp + 1, tc.student->ops.size());
}

}  // namespace

bool openStudentTrace(AppState& st, const std::string& path) {
    if (st.engine.points().size() > kMaxComparedPoints) {
        fileError(st, path + ": comparing a trace in the GUI takes at most " +
                          std::to_string(kMaxComparedPoints) +
                          " points (dtlab diff-trace takes any number)");
        return false;
    }
    if (st.engine.idBufferGl()) {
        fileError(st, path +
                          ": choose a CPU locator before comparing a trace (the GL ID buffer's run "
                          "is not replayed)");
        return false;
    }
    std::shared_ptr<TraceFile> student, ours;
    try {
        student = std::make_shared<TraceFile>(readTraceFile(path));
        if (const std::string wrong = wrongRunFor(st, *student); !wrong.empty()) {
            fileError(st, wrong);
            return false;
        }
        Inserter ins(st.engine.points(), st.engine.options());
        ours = std::make_shared<TraceFile>(traceOfRun(ins, "ours"));
    } catch (const std::exception& e) {
        fileError(st, std::string(e.what()) + " (nothing was changed)");
        return false;
    }
    auto& tc = st.traceCompare;
    tc = {};  // a new comparison: no cache of the last one
    tc.diff = diffTraces(*ours, *student);
    tc.ours = std::move(ours);
    tc.student = std::move(student);
    tc.points = st.engine.points();
    tc.options = st.engine.options();
    tc.selectTab = true;
    if (tc.diff.equal) {
        st.engine.seek(tc.ours->ops.size());
        tc.studentPos = tc.student->ops.size();
        st.log(Message::Level::Info, path + ": the same run as ours (" +
                                         std::to_string(tc.diff.compared) + " steps compared)");
    } else {
        goToDifference(st);
        st.log(Message::Level::Warning, path + ": " + tc.diff.what + " (" +
                                            summarize(*tc.student, tc.diff.studentOp) + ")" +
                                            orderHint(st, *tc.ours, *tc.student));
    }
    return true;
}

void closeStudentTrace(AppState& st) { st.traceCompare = {}; }

bool studentTraceSelectTab(AppState& st) { return std::exchange(st.traceCompare.selectTab, false); }

void ShowTraceCompare(AppState& st) {
    auto& tc = st.traceCompare;
    if (!tc.student) {
        ImGui::TextWrapped(
            "Compare a student's run with ours: open their trace (a .jsonl file, one JSON object "
            "per "
            "operation, at least \"op\" and \"triangles\") with File > Open or drop it on the "
            "window. "
            "Open the assignment (or the student's points and options) first.");
        ImGui::TextDisabled(
            "The same comparison on the command line: dtlab diff-trace REF STUDENT");
        return;
    }
    if (stale(st)) {
        ImGui::TextColored(ImVec4(0.8f, 0.4f, 0.0f, 1),
                           "The points or options changed since the trace was opened.");
        if (ImGui::Button("Close the comparison")) closeStudentTrace(st);
        return;
    }
    ImGui::TextWrapped("%s", tc.student->name.c_str());
    if (tc.diff.equal) {
        ImGui::TextColored(ImVec4(0.1f, 0.55f, 0.2f, 1),
                           "The same run as ours: %zu steps compared.", tc.diff.compared);
    } else {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.8f, 0.1f, 0.1f, 1));
        ImGui::TextWrapped("First difference: %s", tc.diff.what.c_str());
        ImGui::PopStyleColor();
        for (const std::string& d : tc.diff.details) ImGui::BulletText("%s", d.c_str());
    }
    if (ImGui::Button("< Both back")) stepBoth(st, -1);
    RecordItem(st, "trace-back");
    ImGui::SameLine();
    if (ImGui::Button("Both forward >")) stepBoth(st, 1);
    RecordItem(st, "trace-forward");
    ImGui::SameLine();
    if (!tc.diff.equal && ImGui::Button("The difference")) goToDifference(st);
    RecordItem(st, "trace-difference");
    ImGui::SameLine();
    if (ImGui::SmallButton("Close")) {
        closeStudentTrace(st);
        return;
    }
    ImGui::Separator();
    // Side by side: the last op of each run, and what comes next.
    const std::size_t ours = st.engine.position();
    if (ImGui::BeginTable("##sidebyside", 2,
                          ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_SizingStretchSame)) {
        ImGui::TableSetupColumn("Ours");
        ImGui::TableSetupColumn("The student's");
        ImGui::TableHeadersRow();
        auto cell = [](const TraceFile& f, std::size_t done, std::size_t diffAt, bool different) {
            ImGui::PushTextWrapPos(0);
            if (done == 0) ImGui::TextDisabled("(the start)");
            for (std::size_t k = done >= 3 ? done - 3 : 0; k < std::min(done + 2, f.ops.size());
                 ++k) {
                const bool last = k + 1 == done;
                const bool bad = different && k == diffAt;
                if (bad)
                    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.8f, 0.1f, 0.1f, 1));
                else if (!last)
                    ImGui::PushStyleColor(ImGuiCol_Text,
                                          ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
                ImGui::TextWrapped("%s%s", last ? "> " : "  ", summarize(f, k).c_str());
                if (bad || !last) ImGui::PopStyleColor();
            }
            ImGui::PopTextWrapPos();
        };
        ImGui::TableNextRow();
        ImGui::TableSetColumnIndex(0);
        cell(*tc.ours, ours, tc.diff.refOp, !tc.diff.equal);
        ImGui::TableSetColumnIndex(1);
        cell(*tc.student, tc.studentPos, tc.diff.studentOp, !tc.diff.equal);
        ImGui::EndTable();
    }
    ImGui::TextDisabled("On the canvas: the student's triangles that are not ours, in magenta.");
}

void DrawTraceCompareOverlay(AppState& st) {
    auto& tc = st.traceCompare;
    if (!tc.student || stale(st)) return;
    const Mesh& m = st.engine.mesh();
    // The student's mesh after their ops so far, replayed when their position changes.
    if (tc.studentTrianglesAt != tc.studentPos) {
        TraceReplay replay;
        for (std::size_t k = 0; k < tc.studentPos && k < tc.student->ops.size(); ++k)
            replay.apply(tc.student->ops[k]);
        tc.studentTriangles = replay.triangles();
        tc.studentTrianglesAt = tc.studentPos;
    }
    if (tc.ourTrianglesVersion != st.engine.version()) {
        tc.ourTriangles.clear();
        for (std::int32_t t = 0; t < m.numTriangles(); ++t)
            tc.ourTriangles.push_back(canonical(m.V[3 * t], m.V[3 * t + 1], m.V[3 * t + 2]));
        std::sort(tc.ourTriangles.begin(), tc.ourTriangles.end());
        tc.ourTrianglesVersion = st.engine.version();
    }
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const View& view = st.view;
    dl->PushClipRect(toIm(view.origin), toIm(view.origin + view.size), true);
    const float w = st.presentation ? 4.0f : 2.5f;
    for (const Triple& t : tc.studentTriangles) {
        if (std::binary_search(tc.ourTriangles.begin(), tc.ourTriangles.end(), t)) continue;
        bool ok = true;
        ImVec2 p[3];
        for (int k = 0; k < 3; ++k) {
            ok &= t[k] >= 0 && t[k] < m.numVertices() &&
                  static_cast<std::size_t>(t[k]) < st.engine.points().size();
            if (ok) p[k] = toIm(view.toScreen(m.G[t[k]]));
        }
        if (!ok || !canvasHasRoom(st, dl, 40)) continue;
        dl->AddTriangle(p[0], p[1], p[2], useLook(st, Mark::StudentTriangle), w);
    }
    dl->PopClipRect();
}

}  // namespace dlab::ui
