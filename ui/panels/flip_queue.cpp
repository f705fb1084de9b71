// The Predicates tab's "Flip queue" section: the edges on the inserter's flip stack, the next one
// first, numbered as the canvas numbers them; a row selects its corner.
#include "core/teaching/describe.h"
#include "ui/panels/panels.h"

#include <imgui.h>

#include <cstdio>
#include <string>

namespace dlab::ui {

std::string queueRowText(const Inserter& ins, std::size_t number, const Engine::QueuedTest& q) {
    const bool exact = ins.options().boundary == Boundary::Exact;
    const auto triangle = [&](std::int32_t t) {
        if (t == kNone) return std::string("hull");
        std::string s = std::to_string(t);
        if (!ins.done() && ins.isVirtualTriangle(t)) s += exact ? " ghost" : " super";
        return s;
    };
    return std::to_string(number) + ". edge " + vertexName(ins, q.edge.a) + "-" +
           vertexName(ins, q.edge.b) + " (triangles " + triangle(q.near) + " | " + triangle(q.far) +
           (q.far == kNone ? "): nothing to test" : ")");
}

void ShowFlipQueue(AppState& st) {
    const Engine& e = st.engine;
    const std::vector<Engine::QueuedTest> queue = e.pendingTests();
    const std::string header = "Flip queue (" + std::to_string(queue.size()) +
                               (queue.size() == 1 ? " edge" : " edges") + " to test)###flipqueue";
    ImGui::Spacing();
    const bool open = ImGui::CollapsingHeader(header.c_str(), ImGuiTreeNodeFlags_DefaultOpen);
    RecordItem(st, "flip-queue");
    if (!open) return;
    if (e.batch()) {
        ImGui::TextWrapped("This run has no history: the flip queue shows while stepping.");
        return;
    }
    const Op* op = e.current();
    const Mesh& m = e.mesh();
    if (op && op->type == OpType::InCircleTest && op->a >= 0 && op->a < m.numCorners()) {
        ImGui::Text("Testing now: edge %s-%s (taken off the stack)",
                    vertexName(e.inserter(), m.V[next(op->a)]).c_str(),
                    vertexName(e.inserter(), m.V[prev(op->a)]).c_str());
    }
    if (queue.empty()) {
        ImGui::TextDisabled("No edge waits for its in-circle test.");
        return;
    }
    // A lesson asking which comes next hides the test order (the flip-queue-order overlay), or
    // shows the push order only (flip-queue-pushed): the stack's bottom first.
    const bool pushed = !st.overlays.queueOrder;
    if (pushed && !st.overlays.queuePushed) {
        ImGui::TextDisabled("Their order is hidden (View > Their order).");
        return;
    }
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped(pushed ? "In the order they were pushed: 1 went on the flip stack first."
                              : "The next first: the top of the flip stack is 1 (a flip puts its "
                                "two new outer edges on top).");
    ImGui::PopStyleColor();
    for (std::size_t k = 0; k < queue.size(); ++k) {
        const std::size_t i = pushed ? queue.size() - 1 - k : k;  // queue[0] is the top
        const std::string row = queueRowText(e.inserter(), k + 1, queue[i]);
        ImGui::PushID(static_cast<int>(i));
        if (ImGui::Selectable(row.c_str(), st.selection.corner == queue[i].corner))
            st.select(queue[i].corner);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("corner %d on the flip stack: the edge opposite it", queue[i].corner);
        ImGui::PopID();
    }
}

}  // namespace dlab::ui
