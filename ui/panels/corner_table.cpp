// The corner table: one row per corner c with t, V[c], O[c] and the operators n, p, l, r; the
// cells the current operation changed are highlighted (hover shows the old value), the rows of
// the triangles it touched are marked, and a million rows scroll smoothly (ImGuiListClipper).
// Also the G tab: vertex coordinates.
#include "core/engine/numbers.h"
#include "ui/gui.h"
#include "ui/panels/canvas_looks.h"
#include "ui/panels/panels.h"

#include <imgui.h>

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <string>
#include <unordered_map>

namespace dlab::ui {

namespace {

constexpr ImU32 kChangedCell = IM_COL32(255, 200, 120, 255);
constexpr ImU32 kTouchedRow = IM_COL32(255, 244, 214, 255);
constexpr ImU32 kSelectedRow = IM_COL32(255, 214, 170, 255);
constexpr ImU32 kHoveredRow = IM_COL32(205, 225, 255, 255);

void IdCell(std::int32_t v) {
    if (v == kNone)
        ImGui::TextDisabled("-1");
    else
        ImGui::Text("%d", v);
}

using BeforeValues = std::unordered_map<std::int32_t, std::int32_t>;  // corner -> value before

// What the current op changed: the cells' values before it, and the triangles it touched.
struct OpChanges {
    BeforeValues beforeV, beforeO;
    std::vector<std::int32_t> touched;  // sorted
};

// The field that jumps to a corner, the Follow switch and the table's size.
void ShowGoToCorner(AppState& st) {
    const Mesh& m = st.engine.mesh();
    int jump = st.selection.corner == kNone ? 0 : st.selection.corner;
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 5.5f);  // the number and its - + buttons
    if (ImGui::InputInt("Go to corner", &jump, 1, 100, ImGuiInputTextFlags_EnterReturnsTrue)) {
        st.select(std::clamp(jump, 0, std::max(0, m.numCorners() - 1)));
        st.selection.jumpToCorner = st.selection.corner;
    }
    RecordItem(st, "go-to-corner");
    ImGui::SameLine();
    ImGui::Checkbox("Follow", &st.selection.followOp);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Scroll to the cells each operation changes");
    ImGui::SameLine();
    ImGui::TextDisabled("%d corners   l(c) = o(n(c)), r(c) = o(p(c))", m.numCorners());
    if (const Editor* ed = st.engine.editing() ? st.engine.editor() : nullptr;
        ed && !ed->constrainedEdges().empty()) {
        ImGui::SameLine();
        ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(lookOf(Mark::ConstrainedEdge).colour),
                           "O* = constrained edge");
    }
}

// The current op's changes; when following the run, a new step scrolls to its first change.
OpChanges collectOpChanges(AppState& st) {
    const Engine& e = st.engine;
    OpChanges out;
    // The op's cells: the run's op, or the edit's (its removal's or its constraint's record).
    const std::vector<CellChange>* changes = nullptr;
    std::uint32_t first = 0, count = 0;
    if (const Op* op = e.current(); op && e.journal()) {
        changes = &e.journal()->changes();
        first = op->firstChange;
        count = op->numChanges;
    } else if (const EditStep s = e.currentEdit(); s.removal) {
        changes = &s.edit->removal.changes;
        first = s.removal->firstChange;
        count = s.removal->numChanges;
    } else if (s.constraint) {
        changes = &s.edit->constraint.changes;
        first = s.constraint->firstChange;
        count = s.constraint->numChanges;
    }
    const std::int32_t corners = e.mesh().numCorners();
    std::int32_t firstCell = kNone;
    for (std::uint32_t i = 0; changes && i < count; ++i) {
        const CellChange& ch = (*changes)[first + i];
        if (ch.corner() >= corners) continue;  // a row a removal took away
        if (firstCell == kNone) firstCell = ch.corner();
        // The first record of a cell holds its value before the op.
        (ch.isO() ? out.beforeO : out.beforeV).emplace(ch.corner(), ch.before);
        out.touched.push_back(tri(ch.corner()));
    }
    std::sort(out.touched.begin(), out.touched.end());
    out.touched.erase(std::unique(out.touched.begin(), out.touched.end()), out.touched.end());
    // Follow the run: after each step, bring the first changed cell into view.
    if (st.selection.followOp && e.version() != st.tableVersion && firstCell != kNone)
        st.selection.jumpToCorner = firstCell;
    st.tableVersion = e.version();
    return out;
}

void SetUpCornerColumns(const Engine& e) {
    ImGui::TableSetupScrollFreeze(0, 1);
    // V[c] is as wide as its widest text, "12 (ghost)" at any font size; the others share
    // the rest.
    const std::string widest = std::string(std::to_string(e.mesh().numVertices()).size(), '0') +
                               (e.options().boundary == Boundary::Exact ? " (ghost)" : " (super)");
    for (const char* h : {"c", "t", "V[c]", "O[c]", "n", "p", "l", "r"}) {
        if (h[0] == 'V')
            ImGui::TableSetupColumn(h, ImGuiTableColumnFlags_WidthFixed,
                                    ImGui::CalcTextSize(widest.c_str()).x);
        else
            ImGui::TableSetupColumn(h, ImGuiTableColumnFlags_WidthStretch);
    }
    ImGui::TableHeadersRow();
}

// Scrolls a corner asked for (go to, follow, a click elsewhere) into view.
void ScrollToJump(AppState& st, float rowH) {
    if (st.selection.jumpToCorner == kNone) return;
    const float y = rowH * static_cast<float>(st.selection.jumpToCorner);
    const float visible = ImGui::GetWindowHeight() - 2 * rowH;
    if (y < ImGui::GetScrollY() || y > ImGui::GetScrollY() + visible)
        ImGui::SetScrollY(std::max(0.0f, y - visible / 2));
    st.selection.jumpToCorner = kNone;
}

// The V[c] or O[c] cell of row c: highlighted when the op changed it, and the old value in a
// tooltip anywhere over the cell.
void ChangedCell(AppState& st, std::int32_t c, int column, const BeforeValues& before,
                 std::int32_t value, bool virtualVertex, float rowH) {
    ImGui::TableSetColumnIndex(column);
    // The whole cell, padding included: the tooltip shows anywhere over it.
    const ImVec2 pad = ImGui::GetStyle().CellPadding;
    const ImVec2 at = ImGui::GetCursorScreenPos();
    const float cellW = ImGui::GetContentRegionAvail().x;
    const ImVec2 cellMin(at.x - pad.x, at.y - pad.y),
        cellMax(at.x + cellW + pad.x, at.y - pad.y + rowH);
    const auto it = before.find(c);
    if (it != before.end()) ImGui::TableSetBgColor(ImGuiTableBgTarget_CellBg, kChangedCell);
    const Editor* ed = st.engine.editing() ? st.engine.editor() : nullptr;
    if (column == 3 && ed && ed->isConstrained(c)) {  // the edge opposite c is constrained
        ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(lookOf(Mark::ConstrainedEdge).colour),
                           "%d*", value);
    } else if (column == 2 && virtualVertex) {
        ImGui::Text(st.engine.options().boundary == Boundary::Exact ? "%d (ghost)" : "%d (super)",
                    value);
        // For tests: the text's width against its cell's.
        st.itemRects["ghost-v-cell"] = {ImGui::GetItemRectSize().x, cellW, 0, 0};
    } else {
        IdCell(value);
    }
    if (it != before.end() && ImGui::IsWindowHovered() &&
        ImGui::IsMouseHoveringRect(cellMin, cellMax)) {
        ImGui::SetTooltip("%s[%d] was %d, now %d", column == 2 ? "V" : "O", c, it->second, value);
        st.itemRects["cell-tooltip"] = {cellMin.x, cellMin.y, cellMax.x, cellMax.y};
    }
}

// Row c of the table; returns whether the mouse is over it.
bool ShowCornerRow(AppState& st, const OpChanges& changes, std::int32_t c, float rowH) {
    const Mesh& m = st.engine.mesh();
    const Inserter& ins = st.engine.inserter();
    ImGui::TableNextRow(ImGuiTableRowFlags_None, rowH);
    const std::int32_t t = tri(c);
    if (c == st.selection.corner) {
        ImGui::TableSetBgColor(ImGuiTableBgTarget_RowBg1, kSelectedRow);
    } else if (c == st.selection.hoveredCorner) {
        ImGui::TableSetBgColor(ImGuiTableBgTarget_RowBg1, kHoveredRow);
    } else if (std::binary_search(changes.touched.begin(), changes.touched.end(), t)) {
        ImGui::TableSetBgColor(ImGuiTableBgTarget_RowBg1, kTouchedRow);
    }
    ImGui::TableSetColumnIndex(0);
    char label[24];
    std::snprintf(label, sizeof label, "%d", c);
    if (ImGui::Selectable(label, c == st.selection.corner, ImGuiSelectableFlags_SpanAllColumns)) {
        st.select(c);
    }
    const bool hovered = ImGui::IsItemHovered();
    ImGui::TableSetColumnIndex(1);
    ImGui::Text("%d", t);
    const bool virtualVertex = st.engine.showsVirtual() && ins.isVirtual(m.V[c]);
    ChangedCell(st, c, 2, changes.beforeV, m.V[c], virtualVertex, rowH);
    ChangedCell(st, c, 3, changes.beforeO, m.O[c], virtualVertex, rowH);
    ImGui::TableSetColumnIndex(4);
    ImGui::Text("%d", next(c));
    ImGui::TableSetColumnIndex(5);
    ImGui::Text("%d", prev(c));
    ImGui::TableSetColumnIndex(6);
    IdCell(m.l(c));
    ImGui::TableSetColumnIndex(7);
    IdCell(m.r(c));
    return hovered;
}

}  // namespace

void ShowCornerTable(AppState& st) {
    const Engine& e = st.engine;
    ShowGoToCorner(st);
    const OpChanges changes = collectOpChanges(st);

    const ImGuiTableFlags flags = ImGuiTableFlags_ScrollY | ImGuiTableFlags_RowBg |
                                  ImGuiTableFlags_BordersInnerV |
                                  ImGuiTableFlags_SizingStretchSame | ImGuiTableFlags_Resizable;
    ImGui::PushFont(fonts().mono);
    if (ImGui::BeginTable("##corners", 8, flags)) {
        SetUpCornerColumns(e);
        const float rowH = ImGui::GetTextLineHeightWithSpacing();
        ScrollToJump(st, rowH);
        std::int32_t hoveredRow = kNone;
        ImGuiListClipper clipper;
        clipper.Begin(e.mesh().numCorners(), rowH);
        while (clipper.Step()) {
            for (int c = clipper.DisplayStart; c < clipper.DisplayEnd; ++c) {
                if (ShowCornerRow(st, changes, c, rowH)) hoveredRow = c;
            }
        }
        st.selection.hoveredRow = hoveredRow;
        // The scroll position, for tests of the virtualised list.
        st.itemRects["corner-table-scroll"] = {ImGui::GetScrollY(), ImGui::GetScrollMaxY(), 0, 0};
        ImGui::EndTable();
        RecordItem(st, "corner-table");
    }
    ImGui::PopFont();
}

void ShowVertexTable(AppState& st) {
    const Engine& e = st.engine;
    const Mesh& m = e.mesh();
    const auto& states = e.pointStates();
    ImGui::TextDisabled("%d vertices in G (%zu input points)", m.numVertices(), e.points().size());
    const ImGuiTableFlags flags = ImGuiTableFlags_ScrollY | ImGuiTableFlags_RowBg |
                                  ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_SizingStretchProp;
    ImGui::PushFont(fonts().mono);
    if (ImGui::BeginTable("##vertices", 4, flags)) {
        ImGui::TableSetupScrollFreeze(0, 1);
        // The state's longest words ("super-triangle") fit beside 17-digit coordinates.
        ImGui::TableSetupColumn("v", ImGuiTableColumnFlags_WidthStretch, 0.5f);
        ImGui::TableSetupColumn("x", ImGuiTableColumnFlags_WidthStretch, 1.3f);
        ImGui::TableSetupColumn("y", ImGuiTableColumnFlags_WidthStretch, 1.3f);
        ImGui::TableSetupColumn("state", ImGuiTableColumnFlags_WidthStretch, 1.45f);
        ImGui::TableHeadersRow();
        ImGuiListClipper clipper;
        clipper.Begin(m.numVertices());
        while (clipper.Step()) {
            for (int v = clipper.DisplayStart; v < clipper.DisplayEnd; ++v) {
                ImGui::TableNextRow();
                ImGui::TableSetColumnIndex(0);
                ImGui::Text("%d", v);
                const bool virt = v >= static_cast<int>(states.size());
                const bool ghost = virt && e.options().boundary == Boundary::Exact;
                ImGui::TableSetColumnIndex(1);
                if (ghost)
                    ImGui::TextDisabled("-");
                else
                    ImGui::TextUnformatted(shortest(m.G[v].x).c_str());
                ImGui::TableSetColumnIndex(2);
                if (ghost)
                    ImGui::TextDisabled("-");
                else
                    ImGui::TextUnformatted(shortest(m.G[v].y).c_str());
                ImGui::TableSetColumnIndex(3);
                if (virt) {
                    ImGui::TextDisabled(ghost ? "ghost vertex" : "super-triangle");
                } else {
                    static const char* const kNames[] = {"queued", "inserting", "vertex",
                                                         "duplicate"};
                    ImGui::TextUnformatted(kNames[static_cast<int>(states[v])]);
                }
            }
        }
        ImGui::EndTable();
    }
    ImGui::PopFont();
}

}  // namespace dlab::ui
