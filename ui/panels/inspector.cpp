// The corner inspector: the selected corner's t, v, n, p, o, l, r, s, u and how each is
// computed from V and O; buttons (and keys N P O L R S U) move the selection along an operator,
// and the move is drawn as an arrow on the canvas.
#include "core/engine/numbers.h"
#include "ui/gui.h"
#include "ui/panels/panels.h"

#include <imgui.h>

#include <cstdio>
#include <string>

namespace dlab::ui {

namespace {

std::string id(std::int32_t c) { return c == kNone ? "-1 (boundary)" : std::to_string(c); }

// A button per operator (N P O L R S U): a click moves the selection along it.
void ShowOperatorButtons(AppState& st) {
    const struct {
        char op;
        const char* tip;
    } ops[] = {{'n', "next corner of the same triangle (counter-clockwise)"},
               {'p', "previous corner of the same triangle"},
               {'o', "opposite corner, across the edge facing c"},
               {'l', "left neighbour: o(n(c)), across the edge c - p(c)"},
               {'r', "right neighbour: o(p(c)), across the edge c - n(c)"},
               {'s', "swing: n(l(c)), the next corner around the same vertex (counter-clockwise)"},
               {'u', "unswing: p(r(c)), the previous corner around the same vertex (clockwise)"}};
    for (const auto& o : ops) {
        char label[8];
        std::snprintf(label, sizeof label, "%c", o.op - 'a' + 'A');
        if (ImGui::Button(label, ImVec2(ImGui::GetFrameHeight() * 1.4f, 0))) st.moveSelection(o.op);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", o.tip);
        ImGui::SameLine();
    }
    ImGui::NewLine();
}

// Corner c's t, v, n, p, o, l, r, s, u: the value, and how it comes from V and O.
void ShowCornerValues(const Mesh& m, std::int32_t c) {
    const std::int32_t n = next(c), p = prev(c);
    const std::int32_t o = m.O[c], l = m.O[n], r = m.O[p];
    const std::int32_t s = l == kNone ? kNone : next(l), u = r == kNone ? kNone : prev(r);
    struct Row {
        const char* name;
        std::string value, how;
    };
    const Row rows[] = {
        {"c", std::to_string(c), "the selected corner"},
        {"c.t", std::to_string(tri(c)), "c / 3 = " + std::to_string(c) + " / 3"},
        {"c.v", std::to_string(m.V[c]), "V[" + std::to_string(c) + "]"},
        {"c.n", std::to_string(n), "3 c.t + (c + 1) mod 3"},
        {"c.p", std::to_string(p), "3 c.t + (c + 2) mod 3"},
        {"c.o", id(o), "O[" + std::to_string(c) + "]"},
        {"c.l", id(l), "o(n(c)) = O[" + std::to_string(n) + "]"},
        {"c.r", id(r), "o(p(c)) = O[" + std::to_string(p) + "]"},
        {"c.s", id(s),
         l == kNone ? "n(l(c)): l(c) is the boundary" : "n(l(c)) = n(" + std::to_string(l) + ")"},
        {"c.u", id(u),
         r == kNone ? "p(r(c)): r(c) is the boundary" : "p(r(c)) = p(" + std::to_string(r) + ")"},
    };
    ImGui::PushFont(fonts().mono);
    if (ImGui::BeginTable("##inspector", 3,
                          ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV |
                              ImGuiTableFlags_SizingStretchProp)) {
        ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthStretch, 0.5f);
        ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthStretch, 1.0f);
        ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthStretch, 2.5f);
        for (const Row& row : rows) {
            ImGui::TableNextRow();
            ImGui::TableSetColumnIndex(0);
            ImGui::TextUnformatted(row.name);
            ImGui::TableSetColumnIndex(1);
            ImGui::TextUnformatted(row.value.c_str());
            ImGui::TableSetColumnIndex(2);
            ImGui::TextDisabled("%s", row.how.c_str());
        }
        ImGui::EndTable();
    }
    ImGui::PopFont();
}

}  // namespace

void ShowInspector(AppState& st) {
    const Mesh& m = st.engine.mesh();
    const std::int32_t c = st.selection.corner;
    const char* hint = "click a corner on the canvas or a table row; N P O L R S U move it";
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted("Corner inspector");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", hint);
    if (c == kNone || c >= m.numCorners()) {
        ImGui::SameLine();
        ImGui::PushTextWrapPos(0);  // a narrow column wraps the hint instead of cutting it
        ImGui::TextDisabled("(%s)", hint);
        ImGui::PopTextWrapPos();
        ImGui::TextWrapped(
            "No corner selected. A corner is a triangle seen from one of its vertices: triangle t "
            "owns "
            "corners 3t, 3t+1 and 3t+2, counter-clockwise.");
        return;
    }
    // The operator buttons beside the title when they fit: a short column keeps its rows for
    // the values (s and u included); the hint is the title's tooltip.
    const ImGuiStyle& style = ImGui::GetStyle();
    const float buttons = 7 * (ImGui::GetFrameHeight() * 1.4f + style.ItemSpacing.x);
    ImGui::SameLine();
    if (ImGui::GetContentRegionAvail().x < buttons) ImGui::NewLine();
    ShowOperatorButtons(st);
    ShowCornerValues(m, c);
    const Vec2 g = m.G[m.V[c]];
    const bool ghost = st.engine.showsVirtual() && st.engine.isVirtual(m.V[c]) &&
                       st.engine.options().boundary == Boundary::Exact;
    if (ghost)
        ImGui::TextDisabled("vertex %d is the ghost vertex: it has no coordinates", m.V[c]);
    else
        ImGui::TextDisabled("G[%d] = (%s, %s)", m.V[c], shortest(g.x).c_str(),
                            shortest(g.y).c_str());
    if (const CornerMove* mv = st.currentMove()) {
        ImGui::Text("last move: %d.%c = %d", mv->from, mv->op, mv->to);
    }
}

}  // namespace dlab::ui
