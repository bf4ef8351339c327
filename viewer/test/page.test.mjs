// The animation page in a real headless browser (Debian's Chromium driven by playwright-core):
// it loads offline with no console error and no network request, draws a non-blank canvas,
// Play advances the time label, scrubbing to the end shows the run's last tip values (checked
// against the run's CSV), and the canvas at two times differs where the beam moved.
//
//   node test/page.test.mjs PAGE.html RUN.csv [SCREENSHOT_DIR]

import { chromium } from "playwright-core";
import { readFileSync, mkdirSync } from "node:fs";
import { pathToFileURL } from "node:url";
import assert from "node:assert/strict";

const [page_path, csv_path, shots = null] = process.argv.slice(2);
if (!page_path || !csv_path) {
  console.error("usage: node test/page.test.mjs PAGE.html RUN.csv [SCREENSHOT_DIR]");
  process.exit(2);
}

// the run's last row, by column name
const lines = readFileSync(csv_path, "utf8").trim().split(/\r?\n/);
const header = lines[0].split(",");
const last = Object.fromEntries(lines[lines.length - 1].split(",").map((v, i) => [header[i], Number(v)]));

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  args: [
    "--no-sandbox",
    "--disable-gpu",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
    "--disable-quic",
  ],
});
let failed = false;
try {
  const context = await browser.newContext({ viewport: { width: 1000, height: 700 } });
  const page = await context.newPage();
  const errors = [];
  const requests = [];
  page.on("console", (m) => {
    if (m.type() === "error") errors.push(m.text());
  });
  page.on("pageerror", (e) => errors.push(String(e)));
  // offline: anything but the page itself (and data: URLs) is a failure
  await page.route("**/*", (route) => {
    const url = route.request().url();
    if (url.startsWith("file:") || url.startsWith("data:")) return route.continue();
    requests.push(url);
    return route.abort();
  });
  await page.goto(pathToFileURL(page_path).href);
  await page.waitForFunction(() => window.hybeam && document.getElementById("time").textContent.startsWith("t = "));

  // the canvas' pixels (through a 2D copy of the WebGL canvas), kept in the page: the number
  // of distinct colours, and how many pixels differ from the first frame kept
  const look = (keep) =>
    page.evaluate(async (keep) => {
      await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
      const src = document.getElementById("view");
      const c = document.createElement("canvas");
      c.width = src.width;
      c.height = src.height;
      const g = c.getContext("2d");
      g.drawImage(src, 0, 0);
      const px = g.getImageData(0, 0, c.width, c.height).data;
      const colours = new Set();
      for (let i = 0; i < px.length; i += 4) colours.add((px[i] << 16) | (px[i + 1] << 8) | px[i + 2]);
      let differ = 0;
      const first = window.__first;
      if (first) {
        for (let i = 0; i < px.length; i += 4) {
          if (Math.abs(px[i] - first[i]) + Math.abs(px[i + 1] - first[i + 1]) + Math.abs(px[i + 2] - first[i + 2]) > 30) differ++;
        }
      }
      if (keep) window.__first = px;
      return { colours: colours.size, differ };
    }, keep);
  const start = await look(true);
  assert.ok(start.colours > 50, `canvas nearly blank: ${start.colours} colours`);
  if (shots) {
    mkdirSync(shots, { recursive: true });
    await page.screenshot({ path: `${shots}/page_start.png` });
  }

  // Play advances the time label
  const time = async () => Number((await page.textContent("#time")).match(/t = ([0-9.eE+-]+)/)[1]);
  const t0 = await time();
  await page.click("#play");
  await page.waitForTimeout(800);
  const t1 = await time();
  assert.ok(t1 > t0, `play did not advance the time: ${t0} -> ${t1}`);
  await page.click("#play"); // pause

  // scrub to the end: the last tip values of the run
  await page.$eval("#scrub", (s) => {
    s.value = s.max;
    s.dispatchEvent(new Event("input"));
  });
  const tip = await page.textContent("#tip");
  const shown = Object.fromEntries(
    tip.split("\n").map((l) => {
      const [k, v] = l.split(" = ");
      return [k.trim(), Number(v)];
    }),
  );
  const names = Object.keys(shown);
  assert.ok(names.includes("tip.position.x"), `tip values: ${tip}`);
  for (const k of names) {
    const want = last[k];
    assert.ok(Number.isFinite(want), `${k} not in the CSV`);
    assert.ok(Math.abs(shown[k] - want) <= 1e-6 * Math.max(Math.abs(want), 1e-12), `${k}: page ${shown[k]} vs CSV ${want}`);
  }
  assert.ok(Math.abs((await time()) - last.time) < 1e-4, "time label at the end");

  // the canvas at the end differs from the start where the beam moved
  const { differ } = await look(false);
  assert.ok(differ > 200, `the beam did not move on screen: ${differ} pixels differ`);
  if (shots) await page.screenshot({ path: `${shots}/page_end.png` });

  assert.deepEqual(errors, [], "console errors");
  assert.deepEqual(requests, [], "network requests of an offline page");
  console.log(`page ok: ${start.colours} colours, play ${t0} -> ${t1} s, ${names.length} tip values at t = ${last.time} s, ${differ} pixels moved`);
} catch (e) {
  failed = true;
  console.error(e);
} finally {
  await browser.close();
}
process.exit(failed ? 1 : 0);
