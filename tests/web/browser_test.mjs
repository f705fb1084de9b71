// Web.Browser: the browser build (build-web/) in headless Chromium (SwiftShader's WebGL2), served
// from 127.0.0.1, driven with real key presses and clicks through the DevTools protocol
// (puppeteer-core) and read through the page's test hooks (app/delaunay_lab_web.cpp):
//   1. the demo loads; stepping it with the Right key performs, op for op, the operations of the
//      native build's trace (dtlab demo --order input), up to the first flip; screenshot
//   2. ?lesson=05_flips&stop=2&presentation=1 opens the lesson at its stop in presentation mode;
//      presentation mode comes back from IndexedDB after a reload; screenshot
//   3. a bad point file, opened through File > Open (Ctrl+O, the browser's file chooser), shows
//      one line naming the file and the line; the run is unchanged; a good file's points are
//      autosaved to IndexedDB and offered back on the next visit
//   4. Ctrl+S and the dialog's Save button hand a session to the browser as a download
//   5. the canvas follows the window; a tap clicks, a pinch zooms
//   6. Table 1 runs every method at two small sizes on WebGL2 and plots them; screenshot
// Prints the first-load time, the frame time and the Table 1 numbers it measured.
//   usage: node browser_test.mjs WEB_DIR OUT_DIR NATIVE_TRACE NODE_MODULES_DIR [CHROMIUM]
import { createRequire } from "module";
import fs from "fs";
import http from "http";
import os from "os";
import path from "path";

const [webArg, outDir, nativeTracePath, modulesDir, chromium = "/usr/bin/chromium"] =
  process.argv.slice(2);
const webDir = path.resolve(webArg);
const require = createRequire(path.join(path.resolve(modulesDir), "x.js"));
const puppeteer = require("puppeteer-core");
fs.mkdirSync(outDir, { recursive: true });

let failures = 0;
function check(ok, what) {
  console.log(`${ok ? "ok  " : "FAIL"} ${what}`);
  if (!ok) failures++;
}

// ---- A static server on 127.0.0.1 (any free port) ----------------------------------------------
const types = { ".html": "text/html", ".js": "text/javascript", ".wasm": "application/wasm",
                ".data": "application/octet-stream" };
const server = http.createServer((req, res) => {
  let p = decodeURIComponent(new URL(req.url, "http://localhost").pathname);
  if (p.endsWith("/")) p += "index.html";
  const file = path.join(webDir, path.normalize(p));
  if (!file.startsWith(webDir)) { res.writeHead(403); res.end(); return; }
  fs.readFile(file, (err, data) => {
    if (err) { res.writeHead(404); res.end(); return; }
    res.writeHead(200, { "Content-Type": types[path.extname(file)] || "application/octet-stream" });
    res.end(data);
  });
});
await new Promise((r) => server.listen(0, "127.0.0.1", r));
const base = `http://127.0.0.1:${server.address().port}/`;

const browser = await puppeteer.launch({
  executablePath: chromium,
  headless: true,
  args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
         "--ignore-gpu-blocklist", "--window-size=1280,720"],
});
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

async function open(page, query) {
  const t0 = Date.now();
  await page.goto(base + (query || ""));
  await page.waitForFunction("window.dlab && (window.dlab.firstFrameMs !== null || " +
                             "window.dlab.errors.length > 0)", { timeout: 60000 });
  const state = await page.evaluate("JSON.stringify(window.dlab)");
  const d = JSON.parse(state);
  if (d.errors.length) throw new Error("the page failed: " + d.errors.join("; "));
  return { wallMs: Date.now() - t0, ...d };
}
const info = (page) => page.evaluate(
  "JSON.parse(Module.ccall('dlab_web_test_info', 'string', [], []))");
const lastOp = (page) => page.evaluate("Module.ccall('dlab_web_test_last_op', 'string', [], [])");
async function waitFor(page, predicate, what, timeout = 10000) {
  const t0 = Date.now();
  for (;;) {
    const i = await info(page);
    if (predicate(i)) return i;
    if (Date.now() - t0 > timeout) throw new Error("timed out waiting for " + what);
    await sleep(15);
  }
}
// A key held until the app has seen it (ImGui reads keys once per frame).
async function press(page, key, changed) {
  await page.keyboard.down(key);
  try { return await waitFor(page, changed, "key " + key); } finally { await page.keyboard.up(key); }
}
// A key (with modifiers held) down for two frames of the app.
async function chord(page, keys) {
  const start = (await info(page)).frame;
  for (const k of keys) await page.keyboard.down(k);
  try { return await waitFor(page, (x) => x.frame >= start + 2, "keys " + keys.join("+")); }
  finally { for (const k of [...keys].reverse()) await page.keyboard.up(k); }
}
async function clickItem(page, name) {
  const i = await waitFor(page, (x) => x.rects && x.rects[name], "the item " + name);
  const [x0, y0, x1, y1] = i.rects[name];
  await page.mouse.click((x0 + x1) / 2, (y0 + y1) / 2);
}

async function newPage(hasTouch = false) {  // each in a context of its own: its own IndexedDB
  const context = await browser.createBrowserContext();
  const p = await context.newPage();
  await p.setViewport({ width: 1280, height: 720, hasTouch: hasTouch });
  p.on("pageerror", (e) => console.log("page error: " + e.message));
  return p;
}
let page = await newPage();

try {
  // ---- 1. The demo, stepped with the Right key, against the native trace ---------------------
  const load = await open(page, "");
  check(true, `the demo loaded: first frame ${load.firstFrameMs.toFixed(0)} ms after the page ` +
              `started (app ready ${load.startedMs.toFixed(0)} ms)`);
  let i = await info(page);
  check(i.gl.includes("WebGL 2"), "the GL context is WebGL2: " + i.gl);
  check(i.source === "built-in demo" && i.position === 0, "the demo is at operation 0");
  const native = fs.readFileSync(nativeTracePath, "utf8").trim().split("\n");
  let compared = 0, sawFlip = false;
  while (!sawFlip) {
    const before = i.position;
    i = await press(page, "ArrowRight", (x) => x.position > before);
    // The line of the operation just done (a held key may have repeated: its own index).
    const line = await lastOp(page);
    const record = JSON.parse(line);
    if (line !== native[record.i]) {
      check(false, `operation ${record.i} differs from the native trace:\n  browser ${line}` +
                   `\n  native  ${native[record.i]}`);
      break;
    }
    i = await info(page);
    compared++;
    sawFlip = record.op === "Flip";
  }
  check(sawFlip, `stepping gave the native trace, op for op, up to the first flip ` +
                 `(${compared} operations compared, at operation ${i.position})`);
  await page.screenshot({ path: path.join(outDir, "web-demo-flip.png") });

  // The frame time while the demo runs (Space), over 3 s, at 1280x720 and at 640x360.
  await chord(page, [" "]);
  for (const [w, h] of [[1280, 720], [640, 360]]) {
    await page.setViewport({ width: w, height: h });
    await waitFor(page, (x) => x.width === w && x.height === h, `the canvas at ${w} x ${h}`);
    const frames = await page.evaluate(() => new Promise((resolve) => {
      const times = [];
      const tick = (t) => { times.push(t); if (t - times[0] < 3000) requestAnimationFrame(tick);
                            else resolve(times); };
      requestAnimationFrame(tick);
    }));
    const gaps = frames.slice(1).map((t, k) => t - frames[k]).sort((a, b) => a - b);
    const running = await info(page);
    console.log(`frame time while running (${w}x${h}, SwiftShader): median ` +
                `${gaps[gaps.length >> 1].toFixed(1)} ms between frames over ${gaps.length} ` +
                `frames; the app's last frame ${running.frameMs.toFixed(1)} ms`);
  }
  await chord(page, [" "]);
  await page.setViewport({ width: 1280, height: 720 });

  // ---- 2. A lesson from the URL, presentation mode, IndexedDB ---------------------------------
  await open(page, "?lesson=05_flips&stop=2&presentation=1");
  i = await waitFor(page, (x) => x.lesson !== "", "the lesson");
  check(i.lesson !== "" && i.stop === 2 && i.presentation,
        `?lesson=05_flips&stop=2&presentation=1 opened "${i.lesson}" at stop ${i.stop}, ` +
        `presentation ${i.presentation}`);
  await sleep(300);
  await page.screenshot({ path: path.join(outDir, "web-lesson-presentation.png") });
  const syncs = await page.evaluate("window.dlab.syncs || 0");
  await page.evaluate("Module.ccall('dlab_web_save_state', null, [], [])");
  await page.waitForFunction(`(window.dlab.syncs || 0) > ${syncs}`, { timeout: 10000 });
  await open(page, "");
  i = await info(page);
  check(i.presentation, "presentation mode came back from IndexedDB after a reload");
  // ---- 3. A bad file through File > Open ------------------------------------------------------
  page = await newPage(true);
  await open(page, "?points=scattered24");
  i = await info(page);
  check(i.points === 24 && i.notice === "", `?points=scattered24 opened ${i.points} points`);
  const bad = path.join(os.tmpdir(), `dlab-web-${process.pid}`, "bad_points.csv");
  fs.mkdirSync(path.dirname(bad), { recursive: true });
  fs.writeFileSync(bad, "x,y\n1,2\n3,not-a-number\n");
  const [chooser] = await Promise.all([
    page.waitForFileChooser({ timeout: 10000 }),
    chord(page, ["Control", "o"]),
  ]);
  await chooser.accept([bad]);
  i = await waitFor(page, (x) => x.notice !== "", "the error notice");
  check(/^bad_points\.csv:3: /.test(i.notice) && !i.notice.includes("\n") && i.points === 24,
        `the bad file gave one line and changed nothing: "${i.notice}"`);
  await page.screenshot({ path: path.join(outDir, "web-bad-file.png") });

  // A good file the same way; its points are autosaved to IndexedDB, and after the tab is gone
  // the next visit offers them back.
  const good = path.join(path.dirname(bad), "square.csv");
  fs.writeFileSync(good, "x,y\n0,0\n100,0\n100,100\n0,100\n40,60\n");
  const [chooser2] = await Promise.all([page.waitForFileChooser({ timeout: 10000 }),
                                        chord(page, ["Control", "o"])]);
  await chooser2.accept([good]);
  i = await waitFor(page, (x) => x.points === 5, "the good file");
  // The autosave is written after the frame that changed the points (later on a loaded machine).
  i = await waitFor(page, (x) => x.autosaved === 5, "the autosave of the good file");
  const synced = await page.evaluate("window.dlab.syncs || 0");
  await page.evaluate("Module.ccall('dlab_web_save_state', null, [], [])");
  await page.waitForFunction(`(window.dlab.syncs || 0) > ${synced}`, { timeout: 10000 });
  await open(page, "");
  i = await info(page);
  check(i.recovery !== "" && i.points === 12,
        "after the tab was gone, the demo opens with an offer to recover the autosave");
  await clickItem(page, "recover");
  i = await waitFor(page, (x) => x.points === 5, "the recovered points");
  check(i.recovery === "", "Recover brought the 5 points of square.csv back");

  // ---- 4. Save a session: a download ----------------------------------------------------------
  await chord(page, ["Control", "s"]);
  await clickItem(page, "dialog-ok");
  await page.waitForFunction("window.dlab.downloads.length > 0", { timeout: 10000 });
  const dl = await page.evaluate("window.dlab.downloads[0]");
  check(dl.name.endsWith(".json") && dl.text && JSON.parse(dl.text).points !== undefined,
        `Save session handed ${dl.name} (${dl.size} bytes) to the browser as a download`);

  // ---- Resize and touch: the canvas follows the window; a tap clicks, a pinch zooms -------------
  await page.setViewport({ width: 1024, height: 640, hasTouch: true });
  i = await waitFor(page, (x) => x.width === 1024 && x.height === 640, "the canvas at 1024 x 640");
  check(true, "the canvas followed the window to 1024 x 640");
  i = await waitFor(page, (x) => x.rects && x.rects[">"], "the step button");
  const [bx0, by0, bx1, by1] = i.rects[">"];
  const before = i.position;
  await page.touchscreen.tap((bx0 + bx1) / 2, (by0 + by1) / 2);
  i = await waitFor(page, (x) => x.position === before + 1, "a tap on the step button");
  check(true, `a tap on ">" stepped once (operation ${before} -> ${i.position})`);
  const cdp = await page.createCDPSession();
  const scale0 = i.scale, cx = 300, cy = 350;
  const fingers = (d) => [{ x: cx - d, y: cy }, { x: cx + d, y: cy }];
  await cdp.send("Input.dispatchTouchEvent", { type: "touchStart", touchPoints: fingers(40) });
  for (let d = 50; d <= 160; d += 10) {
    await cdp.send("Input.dispatchTouchEvent", { type: "touchMove", touchPoints: fingers(d) });
    await sleep(30);
  }
  await cdp.send("Input.dispatchTouchEvent", { type: "touchEnd", touchPoints: [] });
  i = await waitFor(page, (x) => x.scale > scale0 * 1.5, "the pinch to zoom in");
  check(true, `a pinch apart zoomed in (${scale0.toFixed(3)} -> ${i.scale.toFixed(3)} px/unit)`);
  await page.setViewport({ width: 1280, height: 720, hasTouch: true });

  // ---- 5. Table 1 on WebGL2 ------------------------------------------------------------------
  await page.click("#table1-open");
  const t1 = await page.evaluate(() => window.dlab.runTable1({
    sizes: [256, 512], repeat: 1,
    methods: ["naive", "idbuffer-gl", "idbuffer-gl-batched", "idbuffer-cpu", "walk", "best"] }));
  const allRan = t1.ms.every((row) => row.every((v) => v > 0));
  check(allRan, "Table 1 ran every method at n = 256 and 512 on WebGL2");
  console.log("Table 1 in the browser (ms, one run each): n | " + t1.methods.join(" | "));
  t1.ms.forEach((row, k) => console.log(`  ${t1.sizes[k]} | ${row.map((v) => v.toFixed(1)).join(" | ")}`));
  check(await page.$eval("#t1-plot", (s) => s.querySelectorAll("polyline").length) === 6,
        "the plot shows one curve per method");
  await page.screenshot({ path: path.join(outDir, "web-table1.png") });
} catch (e) {
  check(false, "the test stopped: " + e.message);
  console.log(e.stack);
  await page.screenshot({ path: path.join(outDir, "web-failure.png") }).catch(() => {});
} finally {
  await browser.close();
  server.close();
}
console.log(`screenshots in ${outDir}`);
process.exit(failures ? 1 : 0);
