// The F1 overlay: every keyboard shortcut and mouse gesture, and the corner conventions.
#include "ui/panels/panels.h"

#include <imgui.h>

#include <array>
#include <vector>

namespace dlab::ui {

const std::vector<std::array<const char*, 2>>& helpRows() {
    static const std::vector<std::array<const char*, 2>> kRows = {
        {"Right / Page Down", "one operation forward"},
        {"Left / Page Up", "one operation back"},
        {"Shift + Right / Left", "one insertion forward / back"},
        {"Home / End",
         "back to the start / run to the end (at full speed, this once, past every breakpoint)"},
        {"Space", "run or pause (speed: the slider in the toolbar); a run stops at breakpoints"},
        {"N P O L R", "move the selected corner: next, previous, opposite, left, right"},
        {"S U", "swing / unswing around the selected corner's vertex"},
        {"Esc", "close a popup or this help, else clear the selection"},
        {"Mouse wheel, + / -", "zoom (at the cursor)"},
        {"Drag, middle drag, Ctrl + arrows", "pan"},
        {"F", "fit the points in view"},
        {"Click", "select the corner under the cursor, or queue a new point"},
        {"Drag a queued point", "move it; right-click removes it"},
        {"G", "snap new points to the grid"},
        {"V / C", "Voronoi diagram / circumcircles"},
        {"L", "Legend of the canvas' colours and lines"},
        {"Ctrl + Z / Ctrl + Y", "undo / redo an edit of the points"},
        {"Ctrl + O", "open a point file or a session"},
        {"Ctrl + S", "save the session"},
        {"F12", "screenshot of the window (a PNG; the messages say where)"},
        {"F1", "this help"},
        {"Ctrl + Q", "quit"},
    };
    return kRows;
}

void ShowHelp(AppState& st) {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(
        ImVec2(vp->WorkPos.x + vp->WorkSize.x / 2, vp->WorkPos.y + vp->WorkSize.y / 2),
        ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowBgAlpha(0.97f);
    if (!ImGui::Begin("Help (F1)", &st.showHelp,
                      ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse |
                          ImGuiWindowFlags_NoSavedSettings)) {
        ImGui::End();
        return;
    }
    if (ImGui::BeginTable("##keys", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
        for (const auto& row : helpRows()) {
            ImGui::TableNextRow();
            ImGui::TableSetColumnIndex(0);
            ImGui::TextUnformatted(row[0]);
            ImGui::TableSetColumnIndex(1);
            ImGui::TextUnformatted(row[1]);
        }
        ImGui::EndTable();
    }
    ImGui::Separator();
    ImGui::TextUnformatted(
        "Corners: triangle t owns corners 3t, 3t+1, 3t+2, counter-clockwise (y up).");
    ImGui::TextUnformatted(
        "c.n, c.p: next and previous corner of the same triangle.   c.o = O[c]: across the edge "
        "facing c.");
    ImGui::TextUnformatted(
        "c.l = o(n(c)) (left neighbour),  c.r = o(p(c)) (right neighbour),  c.s = n(l(c)),  c.u = "
        "p(r(c)).");
    const ImVec2 at = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    st.itemRects["help"] = {at.x, at.y, at.x + size.x, at.y + size.y};
    ImGui::End();
}

}  // namespace dlab::ui
