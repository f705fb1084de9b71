// The page around the WebAssembly GUI (delaunay-lab.js): loading, the canvas size, the file
// picker, downloads, IndexedDB saves when the page is hidden, touch (tap = click, drag, pinch =
// zoom) and the Table 1 panel. The app calls Module.openFilePicker, Module.onDownload and
// Module.onStarted; the page calls the app's dlab_web_* functions (app/delaunay_lab_web.cpp).
"use strict";

(function () {
  const canvas = document.getElementById("canvas");
  const status = document.getElementById("status");
  const picker = document.getElementById("picker");
  const t0 = performance.now();

  // What the browser test reads: load time, downloads, errors.
  const dlab = (window.dlab = { downloads: [], errors: [], startedMs: null, firstFrameMs: null });

  function fitCanvas() {
    canvas.style.width = window.innerWidth + "px";
    canvas.style.height = window.innerHeight + "px";
    if (dlab.started) Module.ccall("dlab_web_resize", null, ["number", "number"],
                                   [window.innerWidth, window.innerHeight]);
  }

  window.Module = {
    canvas: canvas,
    print: (text) => console.log(text),
    printErr: (text) => console.warn(text),
    setStatus: (text) => { if (text) status.textContent = text; },
    fatal: (text) => {
      status.textContent = "Delaunay Lab cannot start: " + text;
      status.className = "error";
      status.style.display = "block";
      dlab.errors.push(text);
    },
    onAbort: (what) => Module.fatal(String(what)),
    onStarted: () => {
      dlab.started = true;
      dlab.startedMs = performance.now() - t0;
      status.style.display = "none";
      fitCanvas();
      requestAnimationFrame(() => requestAnimationFrame(() => {
        dlab.firstFrameMs = performance.now() - t0;
      }));
    },
    openFilePicker: () => picker.click(),
    onDownload: (name, bytes) => {
      dlab.downloads.push({ name: name, size: bytes.length, text: bytes.length < 65536 ?
                            new TextDecoder().decode(bytes) : null });
      const url = URL.createObjectURL(new Blob([bytes]));
      const a = document.createElement("a");
      a.href = url;
      a.download = name;
      document.body.appendChild(a);
      a.click();
      a.remove();
      setTimeout(() => URL.revokeObjectURL(url), 10000);
    },
  };
  window.addEventListener("error", (e) => dlab.errors.push(String(e.message)));
  window.addEventListener("resize", fitCanvas);
  fitCanvas();

  // Files picked in the browser's dialog: copied into the app's file system, opened there.
  async function openFiles(files) {
    for (const file of files) {
      const bytes = new Uint8Array(await file.arrayBuffer());
      const name = file.name.replace(/[\/\\]/g, "_");
      FS.mkdirTree("/uploads");
      FS.writeFile("/uploads/" + name, bytes);
      Module.ccall("dlab_web_open", "number", ["string", "string"], ["/uploads", name]);
    }
  }
  picker.addEventListener("change", () => {
    const files = Array.from(picker.files);
    picker.value = "";
    openFiles(files);
  });
  dlab.openFiles = openFiles;

  // Settings, lesson progress and the autosave: to IndexedDB when the tab is hidden or closed.
  function save() { if (dlab.started) Module.ccall("dlab_web_save_state", null, [], []); }
  document.addEventListener("visibilitychange", () => { if (document.hidden) save(); });
  window.addEventListener("pagehide", save);

  // ---- Touch: one finger taps (a click) or drags (a mouse drag); two fingers pinch (the wheel,
  // at their midpoint). Emscripten's GLFW sees only the mouse events made here.
  function mouse(type, x, y, buttons) {
    canvas.dispatchEvent(new MouseEvent(type, { clientX: x, clientY: y, button: 0,
                                                buttons: buttons, bubbles: true }));
  }
  let touch = null;  // {x, y, dragging} of the one finger, or {pinch: distance, ...}
  function pinchOf(ts) {
    const dx = ts[0].clientX - ts[1].clientX, dy = ts[0].clientY - ts[1].clientY;
    return { pinch: Math.hypot(dx, dy), x: (ts[0].clientX + ts[1].clientX) / 2,
             y: (ts[0].clientY + ts[1].clientY) / 2 };
  }
  function onTouch(e) {
    if (e.target !== canvas) return;
    e.preventDefault();
    e.stopPropagation();
    const ts = e.touches;
    if (e.type === "touchstart") {
      if (ts.length === 1) {
        touch = { x: ts[0].clientX, y: ts[0].clientY, dragging: false };
        mouse("mousemove", touch.x, touch.y, 0);
      } else if (ts.length === 2) {
        if (touch && touch.dragging) mouse("mouseup", touch.x, touch.y, 0);
        touch = pinchOf(ts);
        mouse("mousemove", touch.x, touch.y, 0);
      }
    } else if (e.type === "touchmove" && touch) {
      if (ts.length === 2 && touch.pinch) {
        const now = pinchOf(ts);
        const steps = Math.log(now.pinch / touch.pinch) / Math.log(1.15);
        if (Math.abs(steps) >= 0.5) {
          mouse("mousemove", now.x, now.y, 0);
          canvas.dispatchEvent(new WheelEvent("wheel", { clientX: now.x, clientY: now.y,
                                                         deltaY: -100 * Math.round(steps),
                                                         deltaMode: 0, bubbles: true }));
          touch = now;
        }
      } else if (ts.length === 1 && !touch.pinch) {
        const x = ts[0].clientX, y = ts[0].clientY;
        if (!touch.dragging && Math.hypot(x - touch.x, y - touch.y) > 8) {
          touch.dragging = true;
          mouse("mousedown", touch.x, touch.y, 1);
        }
        if (touch.dragging) mouse("mousemove", x, y, 1);
        touch.x = x;
        touch.y = y;
      }
    } else if (e.type === "touchend" || e.type === "touchcancel") {
      if (ts.length === 0 && touch && !touch.pinch) {
        if (!touch.dragging && e.type === "touchend") mouse("mousedown", touch.x, touch.y, 1);
        mouse("mouseup", touch.x, touch.y, 0);
      }
      if (ts.length === 0) touch = null;
    }
  }
  for (const type of ["touchstart", "touchmove", "touchend", "touchcancel"])
    document.addEventListener(type, onTouch, { capture: true, passive: false });

  // ---- The wheel: Emscripten 3.1.6's GLFW hands the DOM's deltas on as they are (100 per notch
  // in Chrome, the sign opposite to GLFW's), so ImGui would zoom by 1.2^100. Each wheel event on
  // the canvas is replaced by one in GLFW's units: +1 per notch up.
  function onWheel(e) {
    if (e.target !== canvas || e.dlabNormalized) return;
    e.preventDefault();
    e.stopPropagation();
    const unit = e.deltaMode === 1 ? 3 : e.deltaMode === 2 ? 1 / 80 : 100;
    const ev = new WheelEvent("wheel", { clientX: e.clientX, clientY: e.clientY,
                                         deltaX: -e.deltaX / unit, deltaY: -e.deltaY / unit,
                                         deltaMode: 0, bubbles: true, cancelable: true });
    ev.dlabNormalized = true;
    canvas.dispatchEvent(ev);
  }
  document.addEventListener("wheel", onWheel, { capture: true, passive: false });

  // ---- Table 1 on this GPU: each (size, method) run is one call, with the page updated between.
  const methods = ["naive", "idbuffer-gl", "idbuffer-gl-batched", "idbuffer-cpu", "walk", "best"];
  const colours = ["#d62728", "#1f77b4", "#17becf", "#2ca02c", "#9467bd", "#7f7f7f"];
  const panel = document.getElementById("table1");
  const methodBox = document.getElementById("t1-methods");
  methods.forEach((m, i) => {
    const label = document.createElement("label");
    label.innerHTML = `<input type="checkbox" id="t1-m${i}" ${i <= 2 ? "checked" : ""}> ${m} `;
    methodBox.appendChild(label);
  });
  document.getElementById("table1-open").onclick = () => { panel.style.display = "block"; };
  document.getElementById("t1-close").onclick = () => { panel.style.display = "none"; };
  document.getElementById("t1-run").onclick = () => runTable1();

  const median = (v) => { const s = [...v].sort((a, b) => a - b), k = s.length;
                          return k % 2 ? s[(k - 1) / 2] : (s[k / 2 - 1] + s[k / 2]) / 2; };
  const frame = () => new Promise((r) => setTimeout(r, 0));

  // Runs the sizes and methods chosen on the panel (or given); resolves to
  // {sizes, methods, ms: [[median ms per method] per size]} and draws the table and the plot.
  async function runTable1(options) {
    const o = options || {};
    const sizes = (o.sizes || document.getElementById("t1-sizes").value.split(/[\s,]+/)
                   .filter((s) => s).map(Number));
    if (sizes.some((n) => !Number.isInteger(n) || n < 3 || n > 1048576)) {
      document.getElementById("t1-state").textContent = "sizes: whole numbers from 3 to 1048576";
      return null;
    }
    const chosen = o.methods || methods.filter((m, i) => document.getElementById("t1-m" + i).checked);
    const repeat = o.repeat || Math.max(1, Number(document.getElementById("t1-repeat").value) | 0);
    const state = document.getElementById("t1-state");
    const result = { sizes: sizes, methods: chosen, ms: [] };
    for (const n of sizes) {
      const runs = chosen.map(() => []);
      for (let r = 0; r < repeat; ++r) {
        for (let k = 0; k < chosen.length; ++k) {
          state.textContent = `n = ${n}: ${chosen[k]} (${r + 1}/${repeat})…`;
          await frame();
          runs[k].push(Module.ccall("dlab_web_table1_run", "number",
                                    ["number", "number", "number"],
                                    [n, methods.indexOf(chosen[k]), 1]));
        }
      }
      result.ms.push(runs.map((v) => (v.some((x) => x < 0) ? NaN : median(v))));
      drawTable1(result);
    }
    state.textContent = "done";
    dlab.table1 = result;
    return result;
  }
  dlab.runTable1 = runTable1;

  function drawTable1(res) {
    let html = "<table><tr><th>n</th>" + res.methods.map((m) => `<th>${m}</th>`).join("") + "</tr>";
    res.ms.forEach((row, i) => {
      html += `<tr><td>${res.sizes[i]}</td>` +
              row.map((v) => `<td>${isNaN(v) ? "–" : v.toFixed(1)}</td>`).join("") + "</tr>";
    });
    document.getElementById("t1-result").innerHTML = html + "</table>";
    // Log-log plot: ms against n.
    const svg = document.getElementById("t1-plot");
    const W = 540, H = 320, L = 74, R = 130, T = 12, B = 36;
    const all = res.ms.flat().filter((v) => v > 0);
    if (!all.length) { svg.innerHTML = ""; return; }
    const x0 = Math.log2(Math.min(...res.sizes)), x1 = Math.max(x0 + 1, Math.log2(Math.max(...res.sizes)));
    const y0 = Math.floor(Math.log10(Math.min(...all))), y1 = Math.max(y0 + 1, Math.ceil(Math.log10(Math.max(...all))));
    const px = (n) => L + (Math.log2(n) - x0) / (x1 - x0) * (W - L - R);
    const py = (v) => H - B - (Math.log10(v) - y0) / (y1 - y0) * (H - T - B);
    let s = `<rect x="${L}" y="${T}" width="${W - L - R}" height="${H - T - B}" fill="none" stroke="#999"/>`;
    for (let e = y0; e <= y1; ++e)
      s += `<line x1="${L}" x2="${W - R}" y1="${py(10 ** e)}" y2="${py(10 ** e)}" stroke="#ddd"/>` +
           `<text x="${L - 4}" y="${py(10 ** e) + 4}" font-size="11" text-anchor="end">${10 ** e} ms</text>`;
    for (const n of res.sizes)
      s += `<text x="${px(n)}" y="${H - B + 14}" font-size="11" text-anchor="middle">${n}</text>`;
    s += `<text x="${(L + W - R) / 2}" y="${H - 4}" font-size="12" text-anchor="middle">points (n)</text>`;
    res.methods.forEach((m, k) => {
      const c = colours[methods.indexOf(m)];
      const pts = res.ms.map((row, i) => [res.sizes[i], row[k]]).filter((p) => p[1] > 0);
      s += `<polyline fill="none" stroke="${c}" stroke-width="2" points="${pts.map((p) => `${px(p[0])},${py(p[1])}`).join(" ")}"/>`;
      s += pts.map((p) => `<circle cx="${px(p[0])}" cy="${py(p[1])}" r="3" fill="${c}"/>`).join("");
      s += `<text x="${W - R + 8}" y="${T + 14 + 16 * k}" font-size="12" fill="${c}">${m}</text>`;
    });
    svg.innerHTML = s;
  }
})();
