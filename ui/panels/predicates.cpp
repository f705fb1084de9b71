// The predicate inspector: the orient2d and incircle calls the current operation made, as the
// engine recorded them (its walk step, classification or in-circle test), each with its points,
// the floating-point determinant, the filter's error bound, the naive and the exact sign and the
// tier that decided; a loud warning where plain floating point would have answered wrong. The
// user can also type four points and test them.
#include "core/engine/io_write.h"
#include "ui/gui.h"
#include "ui/panels/panels.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <charconv>
#include <cmath>
#include <cstdio>

namespace dlab::ui {

namespace {

constexpr ImU32 kWarningFill = IM_COL32(200, 20, 30, 255);

const char* tierName(PredicateTier t) {
    switch (t) {
        case PredicateTier::Filter: return "floating-point filter";
        case PredicateTier::ZeroTail: return "exact: differences without round-off";
        case PredicateTier::StageB: return "adaptive: exact product beyond its error bound";
        case PredicateTier::Expansion: return "exact: floating-point expansions";
        case PredicateTier::BigInteger: return "exact: big integers";
    }
    return "?";
}

const char* signMeaning(bool inCircle, int s) {
    if (inCircle)
        return s > 0   ? "inside the circle: flip"
               : s < 0 ? "outside the circle: keep"
                       : "on the circle: keep";
    return s > 0   ? "left of the edge (counter-clockwise)"
           : s < 0 ? "right of the edge (clockwise)"
                   : "on the line (collinear)";
}

const char* signText(int s) { return s > 0 ? "+1" : s < 0 ? "-1" : " 0"; }

std::string shortest(double x) {
    std::string s;
    appendShortest(s, x);
    return s;
}

// A red box that cannot be missed; recorded as "predicate-warning" for the tests.
void WarningBox(AppState& st, const std::string& text) {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const float wrap = ImGui::GetContentRegionAvail().x - 16;
    const ImVec2 ts = ImGui::CalcTextSize(text.c_str(), nullptr, false, wrap);
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const ImVec2 q(p.x + wrap + 16, p.y + ts.y + 12);
    dl->AddRectFilled(p, q, kWarningFill, 4);
    dl->AddText(ImGui::GetFont(), ImGui::GetFontSize(), ImVec2(p.x + 8, p.y + 6),
                IM_COL32(255, 255, 255, 255), text.c_str(), nullptr, wrap);
    ImGui::Dummy(ImVec2(wrap + 16, ts.y + 12));
    RecordItem(st, "predicate-warning");
}

// The verdict: a red box where float is wrong, a note where only the exact tiers could decide.
void ShowVerdict(AppState& st, const PredicateCall& call) {
    const PredicateReport& r = call.report;
    if (r.naiveSign != r.exactSign) {
        WarningBox(st, std::string("Plain floating point is WRONG here: it gives ") +
                           signText(r.naiveSign) + " (" + signMeaning(call.inCircle, r.naiveSign) +
                           "), the exact sign is " + signText(r.exactSign) + " (" +
                           signMeaning(call.inCircle, r.exactSign) + ").");
    } else if (r.tier != PredicateTier::Filter) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.7f, 0.4f, 0.0f, 1));
        ImGui::TextWrapped(
            "Too close for the filter: decided exactly (the float sign happened to be right).");
        ImGui::PopStyleColor();
    }
}

// One call: its verdict first (on a projector the table below may be cut off) unless the caller
// showed it already, then the numbers.
void ShowCall(AppState& st, const PredicateCall& call, int index, bool verdict = true) {
    const PredicateReport& r = call.report;
    ImGui::PushID(index);
    ImGui::TextWrapped("%s", call.what.c_str());
    if (verdict) ShowVerdict(st, call);
    const int n = call.inCircle ? 4 : 3;
    static const char* const kNames[] = {"a", "b", "c", "d"};
    ImGui::PushFont(fonts().mono);
    if (ImGui::BeginTable("##pred", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
        ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthFixed);
        ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthStretch);
        auto row = [](const std::string& name, const std::string& value,
                      ImVec4 col = ImVec4(0, 0, 0, 0)) {
            ImGui::TableNextRow();
            ImGui::TableSetColumnIndex(0);
            ImGui::TextUnformatted(name.c_str());
            ImGui::TableSetColumnIndex(1);
            if (col.w > 0) ImGui::PushStyleColor(ImGuiCol_Text, col);
            ImGui::TextWrapped("%s", value.c_str());  // long coordinates wrap in a narrow column
            if (col.w > 0) ImGui::PopStyleColor();
        };
        for (int k = 0; k < n; ++k) {
            const std::string name = call.labels[k].empty() ? "" : " " + call.labels[k];
            row(kNames[k] + name, "(" + shortest(call.p[k].x) + ", " + shortest(call.p[k].y) + ")");
        }
        char buf[96];
        std::snprintf(buf, sizeof buf, "%.17g", r.approx);
        row("float det", buf);
        if (std::isfinite(r.errorBound))
            std::snprintf(buf, sizeof buf, "%.3e", r.errorBound);
        else
            std::snprintf(buf, sizeof buf, "n/a (outside the filter's safe range)");
        row("error bound", buf);
        if (std::isfinite(r.errorBound) && r.errorBound > 0) {
            std::snprintf(buf, sizeof buf, "%.3g %s", std::fabs(r.approx) / r.errorBound,
                          std::fabs(r.approx) > r.errorBound ? "(> 1: the float sign is certain)"
                                                             : "(<= 1: too close to call)");
            row("|det| / bound", buf);
        }
        const bool wrong = r.naiveSign != r.exactSign;
        row("naive sign",
            std::string(signText(r.naiveSign)) + "  " + signMeaning(call.inCircle, r.naiveSign),
            wrong ? ImVec4(0.8f, 0.1f, 0.1f, 1) : ImVec4(0, 0, 0, 0));
        row("exact sign",
            std::string(signText(r.exactSign)) + "  " + signMeaning(call.inCircle, r.exactSign),
            ImVec4(0.05f, 0.45f, 0.15f, 1));
        row("decided by", tierName(r.tier));
        ImGui::EndTable();
    }
    ImGui::PopFont();
    if (call.fromEngine && ImGui::SmallButton("Copy these points below")) {
        for (int k = 0; k < 4; ++k) {
            const Vec2 p = k < n ? call.p[k] : call.p[0];
            st.predicates.points[k] = shortest(p.x) + ", " + shortest(p.y);
        }
    }
    ImGui::PopID();
}

// An argument's name: its vertex id, the walk's origin q, or a super-triangle vertex.
std::string argumentLabel(const Inserter& ins, std::int32_t v) {
    if (v == kNone) return "q";
    return "v" + std::to_string(v) + (ins.isVirtual(v) ? " (super-triangle)" : "");
}

}  // namespace

bool parsePointText(std::string_view text, Vec2& out) {
    // "x, y", "x y" or "(x, y)": two decimal numbers, read exactly as the file readers do.
    std::string s(text);
    for (char& ch : s) {
        if (ch == '(' || ch == ')' || ch == ',' || ch == ';' || ch == '\t') ch = ' ';
    }
    double v[2];
    const char* p = s.data();
    const char* end = s.data() + s.size();
    for (double& x : v) {
        while (p < end && *p == ' ') ++p;
        if (p < end && *p == '+') ++p;
        const auto [q, ec] = parseDouble(p, end, x);
        if (ec != std::errc() || !std::isfinite(x)) return false;
        p = q;
    }
    while (p < end && *p == ' ') ++p;
    if (p != end) return false;
    out = {v[0], v[1]};
    return true;
}

std::vector<PredicateCall> currentPredicateCalls(const Engine& e) {
    std::vector<PredicateCall> calls;
    const Journal* journal = e.journal();
    if (!journal || journal->position() == 0) return calls;
    const Inserter& ins = e.inserter();
    for (const RecordedPredicateCall& r : journal->predicateCallsOf(journal->position() - 1)) {
        PredicateCall call;
        call.fromEngine = true;
        call.inCircle = r.inCircle();
        call.what = describe(r);
        call.p = r.p;
        call.v = r.v;
        call.engineSign = r.sign;
        for (int k = 0; k < r.numArgs(); ++k) call.labels[k] = argumentLabel(ins, r.v[k]);
        call.report = call.inCircle ? incircleReport(r.p[0], r.p[1], r.p[2], r.p[3])
                                    : orient2dReport(r.p[0], r.p[1], r.p[2]);
        calls.push_back(std::move(call));
    }
    return calls;
}

namespace {

void ShowPredicatesTitle() {
    ImGui::TextUnformatted("The current operation");
    ImGui::SameLine();
    ImGui::TextDisabled("(?)");
    if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip(
            "Every orientation and in-circle decision is exact. A floating-point filter decides "
            "most calls:\n"
            "when |det| exceeds the error bound, the float sign is certain. Otherwise the "
            "determinant is\n"
            "evaluated exactly (expansions, or big integers for extreme exponents).");
    }
}

// One line per call, all of them in view before the details: "2. orient2d(v4, v0, p = v5) = -1",
// in red where plain floating point gives another sign.
void ShowCallList(const std::vector<PredicateCall>& calls) {
    ImGui::PushFont(fonts().mono);
    for (std::size_t i = 0; i < calls.size(); ++i) {
        const PredicateCall& c = calls[i];
        std::string args;
        for (int k = 0; k < (c.inCircle ? 4 : 3); ++k) {
            if (k > 0) args += ", ";
            args += c.v[k] == kNone ? std::string("q") : "v" + std::to_string(c.v[k]);
        }
        const bool wrong = c.report.naiveSign != c.report.exactSign;
        if (wrong) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.8f, 0.1f, 0.1f, 1));
        ImGui::Text("%zu. %s(%s) = %s%s", i + 1, c.inCircle ? "incircle" : "orient2d", args.c_str(),
                    signText(c.engineSign), wrong ? "  (float: wrong sign)" : "");
        if (wrong) ImGui::PopStyleColor();
    }
    ImGui::PopFont();
}

// The current operation's predicate calls, and buttons to step to the next op that makes one.
void ShowCurrentCalls(AppState& st) {
    Engine& e = st.engine;
    const std::vector<PredicateCall> calls = currentPredicateCalls(e);
    if (calls.empty()) {
        ImGui::TextWrapped(
            "%s", e.current()
                      ? "This operation made no predicate call. Step to an in-circle test or a "
                        "locate step."
                      : "Nothing has happened yet. Step to an in-circle test or a locate step.");
    } else {
        ImGui::TextWrapped("%s made %zu predicate call%s, in this order:",
                           toString(e.current()->type), calls.size(), calls.size() == 1 ? "" : "s");
    }
    RecordItem(st, "predicate-calls");
    if (!e.batch() && !e.atEnd()) {
        if (ImGui::Button("Next in-circle test")) {
            st.run.running = false;
            while (e.forward() && e.current()->type != OpType::InCircleTest) {}
        }
        RecordItem(st, "predicate-next");
        ImGui::SameLine();
        if (ImGui::Button("Next locate step")) {
            st.run.running = false;
            while (e.forward() && e.current()->type != OpType::LocateStep &&
                   e.current()->type != OpType::Located) {}
        }
    }
    ShowCallList(calls);
    for (std::size_t i = 0; i < calls.size(); ++i) {
        ImGui::Separator();
        ImGui::TextDisabled("%zu.", i + 1);
        ImGui::SameLine();
        ShowCall(st, calls[i], static_cast<int>(i));
    }
}

// The four fields a, b, c, d; returns whether each holds a point (a "?" marks one that does not).
bool ReadOwnPoints(AppState& st, Vec2 (&p)[4]) {
    static const char* const kLabels[] = {"a", "b", "c", "d"};
    bool ok = true;
    ImGui::PushFont(fonts().mono);
    for (int k = 0; k < 4; ++k) {
        ImGui::SetNextItemWidth(-30);
        ImGui::InputText(kLabels[k], &st.predicates.points[k]);
        RecordItem(st, (std::string("predicate-point-") + kLabels[k]).c_str());
        if (!parsePointText(st.predicates.points[k], p[k])) {
            ok = false;
            ImGui::SameLine();
            ImGui::TextColored(ImVec4(0.8f, 0.1f, 0.1f, 1), "?");
        }
    }
    ImGui::PopFont();
    return ok;
}

// The user's own four points: orient2d(a, b, c) and incircle(a, b, c, d), verdicts first.
void ShowOwnPoints(AppState& st) {
    ImGui::Separator();
    ImGui::TextUnformatted("Test your own points");
    ImGui::TextDisabled("x, y each; read exactly (17 digits round-trip)");
    Vec2 p[4];
    if (!ReadOwnPoints(st, p)) {
        ImGui::TextColored(ImVec4(0.8f, 0.1f, 0.1f, 1),
                           "Each point is two finite numbers, e.g. 0.5, 1e-3");
        return;
    }
    PredicateCall orient;
    orient.what = "orient2d(a, b, c)";
    orient.p = {p[0], p[1], p[2], p[3]};
    orient.report = orient2dReport(p[0], p[1], p[2]);
    PredicateCall circle;
    circle.inCircle = true;
    circle.what = "incircle(a, b, c, d) (for counter-clockwise a, b, c)";
    circle.p = {p[0], p[1], p[2], p[3]};
    circle.report = incircleReport(p[0], p[1], p[2], p[3]);
    // Both verdicts right under the fields, where the user is typing; the numbers below.
    for (const PredicateCall* call : {&orient, &circle}) {
        ImGui::TextWrapped("%s: %s %s", call->inCircle ? "incircle" : "orient2d",
                           signText(call->report.exactSign),
                           signMeaning(call->inCircle, call->report.exactSign));
        ShowVerdict(st, *call);
    }
    ImGui::Separator();
    ShowCall(st, orient, 100, false);
    ShowCall(st, circle, 101, false);
}

}  // namespace

void ShowPredicates(AppState& st) {
    ShowPredicatesTitle();
    ImGui::BeginChild("##predbody", ImVec2(0, 0), false);  // scrolls when the column is short
    ShowCurrentCalls(st);
    ShowFlipQueue(st);
    ShowOwnPoints(st);
    ImGui::EndChild();
}

}  // namespace dlab::ui
