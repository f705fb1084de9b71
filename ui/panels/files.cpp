// The file dialogs (open, save points, save session, export mesh / SVG, animated GIF), the offer
// to recover an autosave after a crash, and the notice over the canvas that shows a file error
// until it is dismissed.
#include "ui/files/files.h"
#include "ui/panels/panels.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <filesystem>

namespace dlab::ui {

namespace {

namespace fs = std::filesystem;

struct DialogInfo {
    FileState::Dialog kind;
    const char* title;
    const char* defaultName;
    std::vector<const char*> extensions;
    const char* ok;
};

const std::vector<DialogInfo>& dialogs() {
    static const std::vector<DialogInfo> kDialogs = {
        {FileState::Dialog::OpenFile,
         "Open points, a mesh, a session, a lesson or a student trace",
         "",
         {".node", ".csv", ".xy", ".txt", ".pts", ".ele", ".off", ".obj", ".corners", ".json",
          ".toml", ".jsonl"},
         "Open"},
        {FileState::Dialog::SavePoints,
         "Save the points",
         "points.node",
         {".node", ".csv"},
         "Save"},
        {FileState::Dialog::SaveSession, "Save the session", "session.json", {".json"}, "Save"},
        {FileState::Dialog::ExportMesh,
         "Export the mesh",
         "mesh.ele",
         {".ele", ".off", ".obj"},
         "Export"},
        {FileState::Dialog::ExportSvg, "Export an SVG of the view", "view.svg", {".svg"}, "Export"},
        {FileState::Dialog::ExportGif, "Animated GIF of steps", "steps.gif", {".gif"}, "Render"},
    };
    return kDialogs;
}

bool hasExtension(const fs::path& p, const std::vector<const char*>& exts) {
    std::string e = p.extension().string();
    for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return std::find_if(exts.begin(), exts.end(), [&](const char* x) { return e == x; }) !=
           exts.end();
}

// A path field over a folder listing (files with the dialog's extensions, and subfolders).
// True when a file was double-clicked in the Open dialog: open it at once.
bool PathField(AppState& st, const DialogInfo& d) {
    bool activated = false;
    std::string& path = st.files.dialogPath;
    ImGui::SetNextItemWidth(560);
    ImGui::InputText("Path", &path);
    RecordItem(st, "dialog-path");
    std::error_code ec;
    fs::path folder = fs::path(path).parent_path();
    if (folder.empty() || !fs::is_directory(folder, ec)) folder = fs::current_path(ec);
    const std::string name = fs::path(path).filename().string();
    ImGui::TextDisabled("%s", folder.string().c_str());
    ImGui::BeginChild("##listing", ImVec2(560, 200), true);
    if (ImGui::Selectable("..")) path = (folder.parent_path() / name).string();
    std::vector<fs::directory_entry> entries;
    for (const auto& entry : fs::directory_iterator(folder, ec)) entries.push_back(entry);
    std::sort(entries.begin(), entries.end(),
              [](const auto& a, const auto& b) { return a.path() < b.path(); });
    for (const auto& entry : entries) {
        const std::string n = entry.path().filename().string();
        if (entry.is_directory(ec)) {
            if (ImGui::Selectable((n + "/").c_str())) path = (entry.path() / name).string();
        } else if (hasExtension(entry.path(), d.extensions)) {
            if (ImGui::Selectable(n.c_str(), n == name, ImGuiSelectableFlags_AllowDoubleClick)) {
                path = entry.path().string();
                activated |= d.kind == FileState::Dialog::OpenFile &&
                             ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left);
            }
            RecordItem(st, ("dialog-file:" + n).c_str());
        }
    }
    ImGui::EndChild();
    return activated;
}

// The fields some dialogs have besides the path.
void DialogFields(AppState& st, const DialogInfo& d) {
    FileState& f = st.files;
    if (d.kind == FileState::Dialog::ExportMesh) {
        ImGui::RadioButton("Triangle .node/.ele/.neigh", &f.meshFormat, 0);
        ImGui::SameLine();
        ImGui::RadioButton("OFF", &f.meshFormat, 1);
        ImGui::SameLine();
        ImGui::RadioButton("OBJ", &f.meshFormat, 2);
        if (st.engine.showsVirtual()) {
            ImGui::TextDisabled(
                "The run is not finished: the mesh at this step is exported, without its virtual "
                "triangles.");
        }
    } else if (d.kind == FileState::Dialog::ExportGif) {
        GifRequest& g = f.gifDraft;
        const int last = static_cast<int>(st.engine.recorded());
        int from = static_cast<int>(g.from), to = static_cast<int>(g.to),
            every = static_cast<int>(g.every);
        ImGui::SetNextItemWidth(140);
        ImGui::InputInt("from operation", &from);
        ImGui::SameLine();
        ImGui::SetNextItemWidth(140);
        ImGui::InputInt("to", &to);
        ImGui::SetNextItemWidth(140);
        ImGui::InputInt("every", &every);
        ImGui::SameLine();
        ImGui::SetNextItemWidth(140);
        ImGui::InputInt("ms per frame", &g.delayMs, 10, 100);
        ImGui::Checkbox("Whole window (else the canvas)", &g.wholeWindow);
        g.from = static_cast<std::size_t>(std::clamp(from, 0, std::max(last, 0)));
        g.to = static_cast<std::size_t>(std::clamp(to, 0, std::max(last, 0)));
        g.every = static_cast<std::size_t>(std::max(1, every));
        g.delayMs = std::clamp(g.delayMs, 10, 10000);
        ImGui::TextDisabled("%zu frames; the GUI plays them while it records",
                            g.to >= g.from ? (g.to - g.from) / g.every + 1 : 0);
    }
}

// The dialog's action; true when it succeeded (the dialog closes).
bool runDialog(AppState& st, const DialogInfo& d) {
    FileState& f = st.files;
    const std::string path = f.dialogPath;
    switch (d.kind) {
        case FileState::Dialog::OpenFile: return openFile(st, path);
        case FileState::Dialog::SavePoints: return savePoints(st, path);
        case FileState::Dialog::SaveSession: return saveSessionFile(st, path);
        case FileState::Dialog::ExportSvg: return exportViewSvg(st, path);
        case FileState::Dialog::ExportMesh:
            return exportMesh(st, path, static_cast<MeshFormat>(f.meshFormat));
        case FileState::Dialog::ExportGif:
            f.gifDraft.path = path;
            f.gif = f.gifDraft;  // rendered by serviceCaptures after this frame
            return true;
        case FileState::Dialog::None: break;
    }
    return false;
}

void ShowNotice(AppState& st) {
    FileState& f = st.files;
    if (f.notice.empty()) return;
    const View& v = st.view;
    ImGui::SetNextWindowPos(
        ImVec2(static_cast<float>(v.origin.x + 12), static_cast<float>(v.origin.y + 12)));
    ImGui::SetNextWindowSizeConstraints(
        ImVec2(200, 0), ImVec2(static_cast<float>(std::max(240.0, v.size.x - 24)), 400));
    ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.75f, 0.08f, 0.10f, 1.0f));
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 1, 1, 1));
    ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(1, 1, 1, 0.25f));
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration |
                                   ImGuiWindowFlags_AlwaysAutoResize |
                                   ImGuiWindowFlags_NoSavedSettings |
                                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav;
    if (ImGui::Begin("##file-notice", nullptr, flags)) {
        ImGui::PushTextWrapPos(static_cast<float>(std::max(240.0, v.size.x - 60)));
        ImGui::TextUnformatted(f.notice.c_str());
        ImGui::PopTextWrapPos();
        if (ImGui::Button("Dismiss")) f.notice.clear();
        RecordItem(st, "notice-dismiss");
        const ImVec2 a = ImGui::GetWindowPos(), s = ImGui::GetWindowSize();
        st.itemRects["file-notice"] = {a.x, a.y, a.x + s.x, a.y + s.y};
    }
    ImGui::End();
    ImGui::PopStyleColor(3);
}

void ShowRecoveryOffer(AppState& st) {
    FileState& f = st.files;
    constexpr const char* kTitle = "Recover your points?";
    if (f.recoveryPath.empty()) return;
    if (!ImGui::IsPopupOpen(kTitle)) ImGui::OpenPopup(kTitle);
    if (!ImGui::BeginPopupModal(kTitle, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
    ImGui::Text("The last session did not end cleanly. Its autosave holds %zu points",
                f.recoveryPoints);
    if (!f.recoverySource.empty()) ImGui::Text("(from %s).", f.recoverySource.c_str());
    ImGui::TextDisabled("%s", f.recoveryPath.c_str());
    if (ImGui::Button("Recover them")) {
        if (acceptRecovery(st)) ImGui::CloseCurrentPopup();
    }
    RecordItem(st, "recover");
    ImGui::SameLine();
    if (ImGui::Button("Discard")) {
        declineRecovery(st);
        ImGui::CloseCurrentPopup();
    }
    RecordItem(st, "discard-recovery");
    ImGui::EndPopup();
}

}  // namespace

void ShowFileDialogs(AppState& st) {
    FileState& f = st.files;
    ShowNotice(st);
    ShowRecoveryOffer(st);
    if (f.dialog == FileState::Dialog::OpenFile && f.platformOpenDialog) {
        f.dialog = FileState::Dialog::None;
        f.platformOpenDialog();
    }
    if (f.dialog != FileState::Dialog::None) {
        for (const DialogInfo& d : dialogs()) {
            if (d.kind != f.dialog) continue;
            std::error_code ec;
            const fs::path current(f.dialogPath);
            if (f.dialogPath.empty() || (*d.defaultName && !hasExtension(current, d.extensions))) {
                const fs::path folder =
                    current.has_parent_path() ? current.parent_path() : fs::current_path(ec);
                f.dialogPath = (folder / d.defaultName).string();
            }
            if (d.kind == FileState::Dialog::ExportGif && f.gifDraft.to == 0)
                f.gifDraft.to = st.engine.recorded();
            ImGui::OpenPopup(d.title);
        }
        f.dialog = FileState::Dialog::None;
    }
    for (const DialogInfo& d : dialogs()) {
        if (!ImGui::BeginPopupModal(d.title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) continue;
        const bool activated = PathField(st, d);
        DialogFields(st, d);
        const bool ok = ImGui::Button(d.ok) || activated;
        RecordItem(st, "dialog-ok");
        ImGui::SameLine();
        const bool cancel = ImGui::Button("Cancel");
        RecordItem(st, "dialog-cancel");
        if (cancel || (ok && runDialog(st, d))) ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
    }
}

}  // namespace dlab::ui
