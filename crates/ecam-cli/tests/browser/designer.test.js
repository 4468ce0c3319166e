// End-to-end test of the designer page in a real browser (Chromium driven
// by playwright-core): design a rotary-cut table in the generator dialog,
// see the plot change, download it (and read it back with `ecam table
// show`), write it to the PLC, start the cam, watch the slave move in the
// live view, meet the 409 of a running cam and switch at the seam, drag a
// key point, reload from the address; impulses where the server's steps
// are, labelled without overlap; a point table's jerk switch off; the
// DECAM block named by the server; edit a segment cam (change a law, make
// it continuous, drag a point, see the plots, the continuity report and
// the drive check change, write it to the PLC). Screenshots go to
// target/browser-artifacts/; with ECAM_DOCS_SCREENSHOTS=1 the two the
// user guide shows are refreshed in docs/img/.
//
// Run by .ci/run after `cargo test` (which builds target/debug/ecam):
//   node crates/ecam-cli/tests/browser/designer.test.js
// Environment: ECAM_BIN (default target/debug/ecam), CHROMIUM (default
// the first of chromium / chromium-browser / google-chrome on PATH).
"use strict";

const { chromium } = require("playwright-core");
const { spawn, execFileSync } = require("node:child_process");
const fs = require("node:fs");
const os = require("node:os");
const path = require("node:path");
const readline = require("node:readline");
const assert = require("node:assert/strict");

const ROOT = path.resolve(__dirname, "../../../..");
const ARTIFACTS = path.join(ROOT, "target", "browser-artifacts");
const ECAM = process.env.ECAM_BIN || path.join(ROOT, "target", "debug", "ecam");
const STEP_MS = 20000;

// A cam that waits for M0: the feed (DPLSY on Y1, 2 kHz: one 4000-count cut in 2 s, wired back into
// X0 and counted by C231) and DECAM on the block at D2000 start when a
// client sets M0. The sync output Y7 is driven while the cam is in its sync
// zone (thresholds written by the test from the designed table).
const PROGRAM = `
LD M8002
MOV K1 D2004
MOV K7 D2008
LD M8000
OUT C231 K2147483647
LD M0
MOV K1 D2005
DPLSY K2000 K0 Y1
DECAM C231 D2000 X002 Y000 Y004
LDI M0
MOV K0 D2005
END
`;

function findChromium() {
  if (process.env.CHROMIUM) return process.env.CHROMIUM;
  for (const name of ["chromium", "chromium-browser", "google-chrome"]) {
    try {
      return execFileSync("which", [name], { encoding: "utf8" }).trim();
    } catch {
      // not this one
    }
  }
  throw new Error("no Chromium on PATH (set CHROMIUM)");
}

// Starts `ecam serve` on free loopback ports; resolves to {http, modbus, child}.
function startServer(program) {
  const child = spawn(
    ECAM,
    ["serve", "--modbus", "127.0.0.1:0", "--http", "127.0.0.1:0", "--program", program, "--wire", "Y1:X0"],
    { stdio: ["ignore", "pipe", "inherit"] },
  );
  return new Promise((resolve, reject) => {
    const addresses = {};
    const timer = setTimeout(() => reject(new Error("ecam serve printed no addresses")), STEP_MS);
    child.on("error", reject);
    child.on("exit", (code) => reject(new Error(`ecam serve exited with ${code}`)));
    readline.createInterface({ input: child.stdout }).on("line", (line) => {
      const [kind, addr] = line.trim().split(" ");
      addresses[kind] = addr;
      if (addresses.http && addresses.modbus) {
        clearTimeout(timer);
        resolve({ ...addresses, child });
      }
    });
  });
}

async function until(what, check) {
  const start = Date.now();
  for (;;) {
    const value = await check();
    if (value) return value;
    if (Date.now() - start > STEP_MS) throw new Error("timed out waiting for " + what);
    await new Promise((r) => setTimeout(r, 100));
  }
}

// What a chart drew of its impulses (plots.js keeps it): the arrows, and
// labels that stay inside the plot and overlap no other.
async function impulsesDrawn(page, key) {
  const drawn = await page.evaluate((k) => charts[k].drawn, key);
  const overlaps = (a, b) => a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;
  for (const [i, a] of drawn.labels.entries()) {
    const box = drawn.box;
    assert.ok(a.x >= box.x && a.y >= box.y && a.x + a.w <= box.x + box.w + 0.5 && a.y + a.h <= box.y + box.h + 0.5,
      `${key}: label ${a.text} leaves the plot`);
    for (const b of drawn.labels.slice(i + 1)) assert.ok(!overlaps(a, b), `${key}: ${a.text} overlaps ${b.text}`);
  }
  return drawn;
}

async function postJson(base, url, body) {
  const response = await fetch(base + url, {
    method: "POST",
    headers: { "Content-Type": "application/json" },
    body: JSON.stringify(body),
  });
  const text = await response.text();
  assert.equal(response.status, 200, `${url}: ${text}`);
  return JSON.parse(text);
}

async function main() {
  fs.mkdirSync(ARTIFACTS, { recursive: true });
  const work = fs.mkdtempSync(path.join(os.tmpdir(), "ecam-browser-"));
  const program = path.join(work, "designer_cam.il");
  fs.writeFileSync(program, PROGRAM);
  const server = await startServer(program);
  const base = "http://" + server.http;
  const browser = await chromium.launch({
    executablePath: findChromium(),
    args: ["--no-sandbox", "--disable-dev-shm-usage"],
  });
  const errors = [];
  try {
    const context = await browser.newContext({ viewport: { width: 1440, height: 1000 }, acceptDownloads: true });
    const page = await context.newPage();
    page.on("pageerror", (err) => errors.push(err.message));
    // The refused generator parameter (400) and the write to the running
    // cam (409) are expected answers; any other failed load is an error.
    page.on("console", (msg) => {
      const text = msg.text();
      if (msg.type() === "error" && !/status of (400|409) /.test(text)) errors.push(text);
    });
    const shot = (name, target = page) => target.screenshot({ path: path.join(ARTIFACTS, name) });

    await page.goto(base + "/");
    // The default design (the rotary cut's defaults) is drawn without a click.
    await until("the first plot", async () => (await page.textContent("#plots-title")).includes("points"));
    await until("a settled plot", async () => !(await page.getAttribute("#plots", "class") || "").includes("updating"));
    const before = await page.locator("#plot-s canvas").screenshot();

    // ---- design a rotary cut in the generator dialog
    await page.click("#tab-gen");
    await page.click("#gen-open");
    await page.selectOption("#gen-name", "rotary-cut");
    await page.fill('#gen-fields [name="master"]', "4000");
    await page.fill('#gen-fields [name="slave"]', "1200");
    await page.fill('#gen-fields [name="sync"]', "400");
    await page.selectOption('#gen-fields [name="placement"]', "mid-all");
    await shot("01-generator-dialog.png");
    // A value the generator refuses keeps the dialog open with its message.
    await page.fill('#gen-fields [name="resolution"]', "1");
    await page.click("#gen-apply");
    await until("the generator's refusal", async () => (await page.textContent("#gen-error")).length > 0);
    assert.ok(await page.isVisible("#gen-dialog"), "the dialog stays open on a refused parameter");
    await page.fill('#gen-fields [name="resolution"]', "120");
    await page.click("#gen-apply");
    await until("the dialog to close", async () => !(await page.isVisible("#gen-dialog")));
    await until("the new table's plot", async () => (await page.textContent("#plots-title")).includes("120 points"));
    await until("a settled plot", async () => !(await page.getAttribute("#plots", "class") || "").includes("updating"));
    const summary = await page.textContent("#summary");
    assert.match(summary, /master span\s*4000/, summary);
    assert.match(summary, /stroke\s*1200/, summary);
    const after = await page.locator("#plot-s canvas").screenshot();
    assert.ok(!before.equals(after), "the displacement plot changed with the design");
    // Jerk impulses where the server says the acceleration steps (the
    // four corners of the ramps around the centred sync zone; the seam
    // lies in the dwell), none in acceleration (velocity is continuous),
    // labels inside the plot and apart.
    await page.check("#show-jerk");
    await until("the jerk plot", async () => page.isVisible("#plot-j"));
    const gen = await postJson(base, "/api/table/gen", await page.evaluate(() => ({
      generator: "rotary-cut", params: paramsOf(generator("rotary-cut").fields, state.gen.params) })));
    assert.equal(gen.steps.acceleration.length, 4, JSON.stringify(gen.steps));
    const jerk = await impulsesDrawn(page, "j");
    assert.equal(jerk.arrows, 4, "an arrow per acceleration step");
    assert.ok(jerk.labels.length >= 3 && jerk.labels.every((l) => /Δa/.test(l.text)), JSON.stringify(jerk.labels));
    assert.equal((await impulsesDrawn(page, "a")).arrows, 0, "no acceleration impulse");
    // The design's jerk is 0 between its impulses: an axis labelled 0 only,
    // not a range of meaningless units.
    assert.ok(await page.evaluate(() => charts.j.flat), "a flat jerk axis");
    await shot("05-jerk-impulses.png", page.locator("#plot-j"));
    // The address holds the design: a reload restores it.
    const url = page.url();
    assert.match(decodeURIComponent(url), /"master":"4000"/);
    await page.reload();
    await until("the restored plot", async () => (await page.textContent("#plots-title")).includes("120 points"));
    assert.match(await page.textContent("#summary"), /master span\s*4000/);
    assert.match(await page.textContent("#gen-summary"), /master 4000/);

    // ---- live redraw on an edit of the grid (no Draw button)
    await page.click("#tab-keys");
    await until("the key point plot", async () => (await page.textContent("#plots-title")).includes("Key points"));
    await page.fill('#keys-grid [data-row="2"][data-field="slave"]', "2500");
    await until("the redraw after the grid edit", async () => /stroke\s*0/.test(await page.textContent("#summary")) &&
      /slave max\s*2500/.test(await page.textContent("#summary")));
    // Drag the second key point up on the displacement plot.
    const over = page.locator("#plot-s .u-over");
    const box = await over.boundingBox();
    const marker = await page.evaluate(() => {
      const u = charts.s.u;
      const k = state.keys[1];
      return { x: u.valToPos(Number(k.master), "x"), y: u.valToPos(Number(k.slave), "y"), slave: Number(k.slave) };
    });
    await page.mouse.move(box.x + marker.x, box.y + marker.y);
    await page.mouse.down();
    await page.mouse.move(box.x + marker.x, box.y + marker.y - 30, { steps: 5 });
    await page.mouse.up();
    const dragged = Number(await page.inputValue('#keys-grid [data-row="1"][data-field="slave"]'));
    assert.ok(dragged > marker.slave, `the dragged key point rose (${marker.slave} → ${dragged})`);
    await shot("02-key-points.png");

    // ---- segments: change a law, make continuous, drag a point, write to the PLC
    const settled = () => until("a settled plot", async () => !(await page.getAttribute("#plots", "class") || "").includes("updating"));
    await page.click("#tab-segments");
    await until("the segment cam", async () => (await page.textContent("#plots-title")).includes("Segments between"));
    await settled();
    await until("the continuity report", async () => (await page.textContent("#seg-class")).includes("cam C2"));
    assert.match(await page.textContent("#seg-grid"), /1\.7596 \/ 5\.528/, "Cv / Ca of the modified sine");
    await until("the drive check", async () => /cycles\/min/.test(await page.textContent("#drive-result")));
    const driveBefore = await page.textContent("#drive-result");
    const segBefore = await page.locator("#plot-v canvas").screenshot();
    // A constant velocity out of a dwell: the velocity steps at both of its points.
    await page.selectOption('#seg-grid select[data-row="2"]', "constant-velocity");
    await until("the velocity steps reported", async () => (await page.textContent("#seg-class")).includes("cam C0"));
    assert.equal(await page.getAttribute('#seg-grid td.joint[data-point="1"]', "data-class"), "C0");
    await settled();
    const segAfter = await page.locator("#plot-v canvas").screenshot();
    assert.ok(!segBefore.equals(segAfter), "the velocity plot changed with the law");
    await until("the drive check to follow", async () => (await page.textContent("#drive-result")) !== driveBefore);
    assert.match(await page.textContent("#drive-note"), /velocity steps/);
    // Let the dwells adapt, then make the cam continuous in one step.
    await page.selectOption('#seg-grid select[data-row="1"]', "poly-5");
    await page.selectOption('#seg-grid select[data-row="3"]', "poly-5");
    await settled();
    await page.click("#seg-continuous");
    await until("the filled velocity", async () => (await page.inputValue('#seg-grid [data-row="1"][data-field="velocity"]')).startsWith("4.1666"));
    await until("a continuous cam", async () => (await page.textContent("#seg-class")).includes("cam C2"));
    await settled();
    // Drag point 3 up on the displacement plot: the grid follows (its
    // neighbours adapt, so the values just filled in still hold).
    const segOver = page.locator("#plot-s .u-over");
    await segOver.scrollIntoViewIfNeeded();
    const segBox = await segOver.boundingBox();
    const p2 = await page.evaluate(() => {
      const u = charts.s.u;
      const p = state.seg.segment[2];
      return { x: u.valToPos(Number(p.master), "x"), y: u.valToPos(Number(p.slave), "y"), slave: Number(p.slave) };
    });
    await page.mouse.move(segBox.x + p2.x, segBox.y + p2.y);
    await page.mouse.down();
    await page.mouse.move(segBox.x + p2.x, segBox.y + p2.y - 25, { steps: 5 });
    await page.mouse.up();
    const draggedSlave = await until("the grid to follow the drag", async () => {
      const v = await page.inputValue('#seg-grid [data-row="3"][data-field="slave"]');
      return v !== "" && Number(v) > p2.slave ? Number(v) : null;
    });
    await settled();
    await until("the report after the drag", async () => (await page.textContent("#seg-class")).includes("cam C2"));
    // Keep continuous: free values follow every change, shown grey.
    await page.fill('#seg-grid [data-row="1"][data-field="velocity"]', "");
    await page.check("#seg-keep");
    await until("the filled value as a hint", async () =>
      (await page.getAttribute('#seg-grid [data-row="1"][data-field="velocity"]', "placeholder")) === "4.1667");
    await shot("05-segments.png");
    // The address holds the segments; a reload restores them.
    await page.reload();
    await until("the restored segments", async () => (await page.inputValue('#seg-grid [data-row="3"][data-field="slave"]')) === String(draggedSlave));
    await settled();
    // Write the segment cam's table to the PLC (the cam is idle: taken now).
    await page.click("#plc-write");
    await until("the segments written", async () => (await page.textContent("#plc-result")).includes("Written to D2000"))
      .catch(async (err) => { throw new Error(`${err.message}: ${await page.textContent("#plc-result")} ${await page.textContent("#error")}`); });
    const segLoaded = await (await fetch(base + "/api/devices?names=D2038,DD2436,DD2438")).json();
    assert.equal(segLoaded.D2038, 100, "the block holds the segment table's 100 points");
    // Point 99 (the last): master at 40 + 4·99 = 436, slave at 438.
    assert.deepEqual([segLoaded.DD2436, segLoaded.DD2438], [3600, 0]);

    // ---- back to the rotary cut; download it
    await page.goto(url);
    await until("the rotary cut", async () => (await page.textContent("#plots-title")).includes("120 points"));
    await until("a settled plot", async () => !(await page.getAttribute("#plots", "class") || "").includes("updating"));
    await page.check("#show-jerk");
    const [csvDownload] = await Promise.all([page.waitForEvent("download"), page.click("#download-csv")]);
    const csvPath = path.join(ARTIFACTS, "rotary-cut.csv");
    await csvDownload.saveAs(csvPath);
    const csv = fs.readFileSync(csvPath, "utf8").trim().split("\n");
    assert.equal(csv[0], "master,slave,velocity,acceleration,jerk");
    assert.equal(csv.length, 121, "header and 120 points");
    assert.match(csv[120], /^4000,1200,/);
    const shown = execFileSync(ECAM, ["table", "show", csvPath], { encoding: "utf8" });
    assert.match(shown, /4000/, shown);
    const [jsonDownload] = await Promise.all([page.waitForEvent("download"), page.click("#download-json")]);
    const jsonPath = path.join(ARTIFACTS, "rotary-cut.json");
    await jsonDownload.saveAs(jsonPath);
    const doc = JSON.parse(fs.readFileSync(jsonPath, "utf8"));
    assert.equal(doc.generator, "rotary-cut");
    assert.equal(doc.points.length, 120);
    execFileSync(ECAM, ["table", "show", jsonPath], { encoding: "utf8" });

    // ---- a DECAM block the server refuses, named by its kind
    await page.fill("#plc-block", "D9000");
    await page.click("#plc-write");
    await until("the refused block", async () => /past the last data register, D8511/.test(await page.textContent("#plc-result")));
    await page.fill("#plc-block", "M100");
    await page.click("#plc-write");
    await until("the refused relay", async () => /M100 is an auxiliary relay/.test(await page.textContent("#plc-result")));

    // ---- write it to the PLC (the cam is idle: taken now), start the cam
    await page.fill("#plc-block", "D2000");
    await page.click("#plc-write");
    await until("the write", async () => (await page.textContent("#plc-result")).includes("Written to D2000"));
    assert.match(await page.textContent("#plc-result"), /120 points.*taken now/);
    const loaded = await (await fetch(base + "/api/devices?names=D2038,DD2516,DD2518")).json();
    assert.equal(loaded.D2038, 120, "the block holds the table's point count");
    // Point i: master at offset 40 + 4i, slave at 42 + 4i (docs/plc.md).
    assert.equal(loaded.DD2516, 4000, "the last point's master");
    assert.equal(loaded.DD2518, 1200, "the last point's slave");
    await postJson(base, "/api/devices", { DD2009: doc.sync.low, DD2011: doc.sync.high, M0: 1 });

    // ---- the live view shows the cam running and the slave moving
    await until("the running cam", async () => (await page.textContent("#live-state")) === "cam running");
    const slaveAt = async () => Number(await page.textContent("#ro-slave"));
    const first = await slaveAt();
    await until("the slave to move", async () => (await slaveAt()) > first + 500);
    await until("a speed reading", async () => /pulses\/s/.test(await page.textContent("#ro-speed")));
    await page.waitForTimeout(1500);
    await shot("03-designer-live.png");
    await page.screenshot({ path: path.join(ARTIFACTS, "designer-full.png"), fullPage: true });
    if (process.env.ECAM_DOCS_SCREENSHOTS) {
      fs.copyFileSync(path.join(ARTIFACTS, "designer-full.png"), path.join(ROOT, "docs", "img", "designer.png"));
      fs.copyFileSync(path.join(ARTIFACTS, "02-key-points.png"), path.join(ROOT, "docs", "img", "designer-key-points.png"));
    }

    // ---- a second write while the cam runs: 409, then switch at the seam
    await page.click("#plc-write");
    await until("the conflict", async () => page.isVisible("#plc-conflict"));
    assert.match(await page.textContent("#plc-conflict-text"), /running/);
    await shot("04-write-while-running.png", page.locator("aside"));
    await page.click("#plc-at-seam");
    await until("the switch at the seam", async () => (await page.textContent("#plc-result")).includes("next seam"));

    // ---- an upload becomes an editable point table
    await page.setInputFiles("#upload", csvPath);
    await until("the uploaded table", async () => (await page.textContent("#plots-title")).includes("Point table — 120 points"));
    await until("a settled plot", async () => !(await page.getAttribute("#plots", "class") || "").includes("updating"));
    // Its velocity steps at its points are acceleration impulses (Δv),
    // their labels never overlapping; a point table has no jerk to draw.
    const points = await impulsesDrawn(page, "a");
    assert.ok(points.arrows > 50, `arrows at the points (${points.arrows})`);
    assert.ok(points.labels.every((l) => /Δv/.test(l.text)), JSON.stringify(points.labels));
    assert.ok(await page.isDisabled("#show-jerk"), "the jerk switch is off for a point table");
    assert.ok(await page.isHidden("#plot-j"));
    await shot("06-point-table.png", page.locator("#plot-a"));
    // A file the server cannot read is refused with its line and value.
    const bad = path.join(work, "bad.csv");
    fs.writeFileSync(bad, "master,slave\n0,0\n# a comment\n10,x\n");
    await page.setInputFiles("#upload", bad);
    await until("the refused upload", async () => /bad\.csv: line 4: slave `x`/.test(await page.textContent("#error")));

    assert.deepEqual(errors, [], "no script errors on the page");
    console.log("designer browser test: ok (screenshots in target/browser-artifacts)");
  } finally {
    await browser.close();
    server.child.kill("SIGKILL");
    fs.rmSync(work, { recursive: true, force: true });
  }
}

main().catch((err) => {
  console.error("designer browser test FAILED:", err);
  process.exit(1);
});
