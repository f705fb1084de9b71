// The message log: every warning and error the GUI produced (never only on stderr).
#include "ui/panels/panels.h"

#include <imgui.h>

namespace dlab::ui {

void ShowMessages(AppState& st) {
    ImGui::TextUnformatted("Messages");
    ImGui::SameLine();
    if (ImGui::SmallButton("Clear")) st.messages.clear();
    ImGui::BeginChild("##log", ImVec2(0, 0), true);
    for (const Message& m : st.messages) {
        const ImVec4 col = m.level == Message::Level::Error     ? ImVec4(0.8f, 0.1f, 0.1f, 1)
                           : m.level == Message::Level::Warning ? ImVec4(0.7f, 0.4f, 0.0f, 1)
                                                                : ImVec4(0.2f, 0.2f, 0.25f, 1);
        ImGui::PushStyleColor(ImGuiCol_Text, col);
        ImGui::TextWrapped("%s%s",
                           m.level == Message::Level::Error     ? "error: "
                           : m.level == Message::Level::Warning ? "warning: "
                                                                : "",
                           m.text.c_str());
        ImGui::PopStyleColor();
    }
    if (ImGui::GetScrollY() >= ImGui::GetScrollMaxY() - 4) ImGui::SetScrollHereY(1.0f);
    ImGui::EndChild();
}

}  // namespace dlab::ui
