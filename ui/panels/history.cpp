// The offer over the canvas when recording the run to its end would pass the history's op
// limit: BRIO order (when it fits), a run without a history, or stepping anyway (the history then
// stops at the limit, and the messages say so).
#include "ui/panels/panels.h"

#include <imgui.h>

#include <algorithm>

namespace dlab::ui {

namespace {

void ShowHistoryChoices(AppState& st) {
    AppState::HistoryOffer& h = st.historyOffer;
    if (h.brioOps > 0) {
        if (ImGui::Button("Use BRIO order")) {
            InsertOptions o = st.engine.options();
            o.order = OrderKind::Brio;
            st.setUserOptions(o);
        }
        RecordItem(st, "history-brio");
        ImGui::SameLine();
    }
    if (ImGui::Button("Run without a history")) {
        st.run.running = false;
        st.engine.runWithoutHistory();
        st.log(Message::Level::Info, st.engine.batchReason());
        h.open = false;
    }
    RecordItem(st, "history-batch");
    ImGui::SameLine();
    if (ImGui::Button("Step anyway")) h.open = false;
    RecordItem(st, "history-keep");
}

}  // namespace

void ShowHistoryOffer(AppState& st) {
    AppState::HistoryOffer& h = st.historyOffer;
    if (h.open && (h.run != st.engine.run() || st.engine.batch())) h.open = false;
    if (!h.open) {
        st.itemRects.erase("history-offer");
        return;
    }
    const View& v = st.view;
    // At the bottom of the canvas: a file notice keeps the top.
    ImGui::SetNextWindowPos(
        ImVec2(static_cast<float>(v.origin.x + 12), static_cast<float>(v.origin.y + v.size.y - 12)),
        ImGuiCond_Always, ImVec2(0, 1));
    const float width = static_cast<float>(std::max(240.0, v.size.x - 24));
    ImGui::SetNextWindowSizeConstraints(ImVec2(std::min(width, 420.0f), 0), ImVec2(width, 400));
    ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.99f, 0.86f, 0.45f, 1.0f));
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.1f, 0.08f, 0.0f, 1));
    ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(1, 1, 1, 0.55f));
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration |
                                   ImGuiWindowFlags_AlwaysAutoResize |
                                   ImGuiWindowFlags_NoSavedSettings |
                                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav;
    if (ImGui::Begin("##history-offer", nullptr, flags)) {
        ImGui::PushTextWrapPos(width - 24);
        ImGui::TextUnformatted(historyOfferText(st).c_str());
        ImGui::PopTextWrapPos();
        ShowHistoryChoices(st);
        const ImVec2 a = ImGui::GetWindowPos(), s = ImGui::GetWindowSize();
        st.itemRects["history-offer"] = {a.x, a.y, a.x + s.x, a.y + s.y};
    }
    ImGui::End();
    ImGui::PopStyleColor(3);
}

}  // namespace dlab::ui
