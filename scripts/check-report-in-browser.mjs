// Opens a report folder's index.html in headless Chromium and checks what an engineer would
// see: the page loads with no console error, no uncaught exception and no failed request,
// asks for nothing outside the folder, runs no script from an input (a dialog is a problem:
// markup from an input ran), every picture shows something, and the 3D view loads its scene,
// draws it, plays (the time advances and the picture changes) and seeks, and its worst-moment
// button turns the camera to the worst spot and rings it. The installation sheet
// (install.html), when there is one, is checked like the page and printed to PDF: it must fit
// one A4 landscape page.
//
//   node scripts/check-report-in-browser.mjs REPORT_DIR
//
// playwright-core is found in PLAYWRIGHT_CORE_DIR (a folder whose node_modules holds it, as
// scripts/check-report-in-browser.sh sets up) or through the usual lookup; the browser is
// CHROMIUM (default /usr/bin/chromium). Exit 0: all good; 1: a problem, each one printed;
// 2: the check could not run.

import { existsSync } from "node:fs";
import { createRequire } from "node:module";
import path from "node:path";
import { pathToFileURL } from "node:url";

// Share of a picture's pixels that must differ from its most common colour: a blank image, or
// one with only a frame, has (almost) none.
const MIN_DRAWN_SHARE = 0.01;

function loadPlaywright() {
  const dir = process.env.PLAYWRIGHT_CORE_DIR;
  const base = dir ? path.join(path.resolve(dir), "package.json") : import.meta.url;
  return createRequire(base)("playwright-core");
}

// Records console errors, page errors, failed requests and any request leaving file://.
function watch(page, problems) {
  page.on("console", (message) => {
    if (message.type() === "error") problems.push(`console error: ${message.text()}`);
  });
  page.on("pageerror", (error) => problems.push(`uncaught exception: ${error.message}`));
  // The page has no script of its own: a dialog means markup from an input ran as code.
  page.on("dialog", (dialog) => {
    problems.push(`a script ran and opened a dialog (${dialog.type()}): ${dialog.message()}`);
    return dialog.dismiss();
  });
  page.on("requestfailed", (request) =>
    problems.push(`failed request: ${request.url()} (${request.failure()?.errorText})`),
  );
  return page.route("**/*", (route) => {
    const url = route.request().url();
    if (url.startsWith("file:")) return route.continue();
    problems.push(`request outside the folder: ${url}`);
    return route.abort();
  });
}

// Share of the PNG's pixels that differ from its most common colour, decoded in a blank page.
async function drawnShare(blank, png) {
  return blank.evaluate(async (base64) => {
    const image = new Image();
    image.src = `data:image/png;base64,${base64}`;
    await image.decode();
    const canvas = document.createElement("canvas");
    canvas.width = image.naturalWidth;
    canvas.height = image.naturalHeight;
    const context = canvas.getContext("2d");
    context.drawImage(image, 0, 0);
    const { data } = context.getImageData(0, 0, canvas.width, canvas.height);
    const counts = new Map();
    for (let i = 0; i < data.length; i += 4) {
      const key = (data[i] << 16) | (data[i + 1] << 8) | data[i + 2];
      counts.set(key, (counts.get(key) ?? 0) + 1);
    }
    const pixels = data.length / 4;
    return pixels ? 1 - Math.max(...counts.values()) / pixels : 0;
  }, png.toString("base64"));
}

// naturalWidth, load state and drawn share of every <img>; problems for the bad ones.
async function checkImages(page, blank, problems) {
  const images = page.locator("img");
  const count = await images.count();
  if (count === 0) problems.push("the page shows no picture");
  for (let i = 0; i < count; i++) {
    const image = images.nth(i);
    const src = await image.getAttribute("src");
    const { complete, width } = await image.evaluate((img) => ({
      complete: img.complete,
      width: img.naturalWidth,
    }));
    if (!complete || width === 0) {
      problems.push(`${src}: not loaded (naturalWidth ${width})`);
      continue;
    }
    // Without the page's frame around images: only what the picture itself draws counts.
    const png = await image.screenshot({ style: "img { border: 0 !important; }" });
    const share = await drawnShare(blank, png);
    const percent = (100 * share).toFixed(1);
    if (share < MIN_DRAWN_SHARE) problems.push(`${src}: blank (${percent} % of it drawn)`);
    console.log(`  ${src}: ${width} px wide, ${percent} % of its pixels drawn`);
  }
  return count;
}

// Longest wait for the 3D view's scene to load and for its animation to move (ms).
const VIEW_TIMEOUT_MS = 60000;

// The 3D view: the scene loads, the canvas shows something, playing advances the time and
// moves the robot, the slider seeks, and the clamp labels are there. Returns a description.
async function checkView(page, blank, problems) {
  const viewer = page.locator("model-viewer#view");
  if ((await viewer.count()) === 0) {
    problems.push("the page has no 3D view");
    return "no 3D view";
  }
  try {
    await page.waitForFunction(() => document.body.dataset.viewLoaded === "true", null, {
      timeout: VIEW_TIMEOUT_MS,
    });
  } catch {
    problems.push("the 3D view's scene did not load");
    return "3D view not loaded";
  }
  await viewer.scrollIntoViewIfNeeded();
  const before = await viewer.screenshot();
  const share = await drawnShare(blank, before);
  if (share < MIN_DRAWN_SHARE) problems.push(`3D view: blank (${(100 * share).toFixed(1)} % drawn)`);
  const labels = await page.locator("model-viewer#view .clamp-label").count();
  if (labels === 0) problems.push("3D view: no clamp label");
  const hasAnimation = await page.evaluate(() => !!window.cableDictView.clips[0].animation);
  let moved = "no animation";
  if (hasAnimation) {
    const t0 = await page.evaluate(() => document.getElementById("view").currentTime);
    await page.click("#view-play");
    await page.waitForTimeout(1500);
    const t1 = await page.evaluate(() => document.getElementById("view").currentTime);
    await page.click("#view-play");
    if (!(t1 > t0)) problems.push(`3D view: playing did not advance the time (${t0} → ${t1} s)`);
    // Seek to the worst moment: the time follows, and the picture changes.
    const worst = await page.evaluate(() => window.cableDictView.clips[0].worst?.time_s ?? null);
    const target = worst ?? t1 / 2;
    await page.evaluate((t) => {
      const slider = document.getElementById("view-time");
      slider.value = String(t);
      slider.dispatchEvent(new Event("input"));
    }, target);
    await page.waitForTimeout(500);
    const t2 = await page.evaluate(() => document.getElementById("view").currentTime);
    if (Math.abs(t2 - target) > 0.02) problems.push(`3D view: seeking to ${target} s gave ${t2} s`);
    const after = await viewer.screenshot();
    if (after.equals(before)) problems.push("3D view: the picture did not change over the motion");
    moved = `played ${t0.toFixed(2)} → ${t1.toFixed(2)} s, sought ${target.toFixed(2)} s`;
  }
  // The installation pose: its animation takes over, and the picture still shows something.
  const installation = await page.evaluate(() => window.cableDictView.installation);
  if (installation) {
    await page.click("#view-install");
    await page.waitForTimeout(500);
    const shown = await page.evaluate(() => document.getElementById("view").animationName);
    if (shown !== installation) problems.push(`3D view: the installation pose shows '${shown}'`);
    const still = await drawnShare(blank, await viewer.screenshot());
    if (still < MIN_DRAWN_SHARE) problems.push("3D view: blank at the installation pose");
    moved += ", installation pose shown";
    if (hasAnimation) {
      // And back to the motion test by the slider.
      const back = await page.evaluate(async () => {
        const slider = document.getElementById("view-time");
        slider.value = "0.5";
        slider.dispatchEvent(new Event("input"));
        await new Promise((resolve) => setTimeout(resolve, 500));
        const v = document.getElementById("view");
        return { name: v.animationName, t: v.currentTime, want: window.cableDictView.clips[0].animation };
      });
      if (back.name !== back.want || Math.abs(back.t - 0.5) > 0.02) {
        problems.push(`3D view: back from the installation pose shows '${back.name}' at ${back.t} s`);
      }
    }
  }
  moved += await checkWorstButton(page, viewer, problems);
  moved += await checkMotionPicker(page, viewer, problems);
  moved += await checkColouring(page, viewer, problems);
  return `3D view: loaded, ${(100 * share).toFixed(1)} % drawn, ${labels} clamp labels, ${moved}`;
}

// The colouring by damage per cycle, when the scene offers it (a cable with a predicted life):
// the list is shown, picking it changes the picture and shows its legend, and the margins come
// back.
async function checkColouring(page, viewer, problems) {
  const offered = await page.evaluate(() => !document.getElementById("view-colour").hidden);
  if (!offered) return ", one colouring";
  const before = await viewer.screenshot();
  await page.selectOption("#view-colour", { index: 1 });
  await page.waitForTimeout(800);
  const state = await page.evaluate(() => ({
    variant: document.getElementById("view").variantName,
    legend: !document.getElementById("view-damage-legend").hidden,
  }));
  if (state.variant !== "damage per cycle") problems.push(`3D view: the damage colouring shows variant '${state.variant}'`);
  if (!state.legend) problems.push("3D view: the damage colouring shows no legend");
  const damage = await viewer.screenshot();
  if (damage.equals(before)) problems.push("3D view: colouring by damage did not change the picture");
  await page.selectOption("#view-colour", { index: 0 });
  await page.waitForTimeout(800);
  const back = await page.evaluate(() => document.getElementById("view").variantName);
  if (back !== "margins") problems.push(`3D view: back to margins shows variant '${back}'`);
  return ", coloured by damage and back";
}

// The worst-moment button: the time goes there, the camera turns to the spot (its target moves
// onto it) and the red ring is shown there; the picture changes.
async function checkWorstButton(page, viewer, problems) {
  const worst = await page.evaluate(() => window.cableDictView.clips[0].worst);
  if (!worst || !worst.spot_m) return ", no worst spot to show";
  const before = await viewer.screenshot();
  await page.click("#view-worst");
  await page.waitForTimeout(1500);
  const state = await page.evaluate(() => {
    const v = document.getElementById("view");
    const target = v.getCameraTarget();
    const ring = v.querySelector(".worst-ring");
    return {
      t: v.currentTime,
      target: [target.x, target.y, target.z],
      ringShown: !!ring && !ring.hidden && ring.getBoundingClientRect().width > 0,
    };
  });
  if (Math.abs(state.t - worst.time_s) > 0.02) {
    problems.push(`3D view: the worst-moment button went to ${state.t} s, not ${worst.time_s} s`);
  }
  const off = Math.hypot(...state.target.map((v, i) => v - worst.spot_m[i]));
  if (off > 0.005) problems.push(`3D view: the camera looks ${off.toFixed(3)} m away from the worst spot`);
  if (!state.ringShown) problems.push("3D view: the worst spot is not ringed");
  const after = await viewer.screenshot();
  if (after.equals(before)) problems.push("3D view: the worst-moment button changed nothing");
  return `, worst spot shown at ${state.t.toFixed(2)} s (camera ${(1000 * off).toFixed(1)} mm from it)`;
}

// A cell's report: the list picks each other motion, whose animation then plays from its
// start, its slider as long as its clip, and the picture changes.
async function checkMotionPicker(page, viewer, problems) {
  const clips = await page.evaluate(() =>
    window.cableDictView.clips.map((c) => ({ animation: c.animation, end: c.times_s[c.times_s.length - 1] })),
  );
  const shown = await page.evaluate(() => !document.getElementById("view-motion").hidden);
  if (clips.length < 2) {
    if (shown) problems.push("3D view: a motion list for a single motion");
    return "";
  }
  if (!shown) problems.push("3D view: no motion list for a cell of several motions");
  for (let k = 1; k < clips.length; k++) {
    const before = await viewer.screenshot();
    await page.selectOption("#view-motion", String(k));
    await page.waitForTimeout(800);
    const state = await page.evaluate(() => {
      const v = document.getElementById("view");
      return { name: v.animationName, t: v.currentTime, max: Number(document.getElementById("view-time").max) };
    });
    if (state.name !== clips[k].animation) problems.push(`3D view: motion ${k} shows '${state.name}', not '${clips[k].animation}'`);
    if (Math.abs(state.max - clips[k].end) > 1e-6) problems.push(`3D view: motion ${k}'s slider ends at ${state.max} s, not ${clips[k].end} s`);
    if ((await viewer.screenshot()).equals(before)) problems.push(`3D view: picking motion ${k} changed nothing`);
  }
  return `, ${clips.length} motions to pick from`;
}

// The sheet printed as its page asks (A4 landscape): the number of pages of the PDF.
async function printedPages(page) {
  await page.emulateMedia({ media: "print" });
  const pdf = await page.pdf({ preferCSSPageSize: true, printBackground: true });
  return (pdf.toString("latin1").match(/\/Type\s*\/Page[^s]/g) || []).length;
}

async function main() {
  const dir = process.argv[2];
  const index = dir && path.resolve(dir, "index.html");
  if (!index || !existsSync(index)) {
    console.error(`usage: check-report-in-browser.mjs REPORT_DIR (with an index.html)`);
    return 2;
  }
  const started = Date.now();
  const { chromium } = loadPlaywright();
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
    // Root in a container: Chromium's sandbox needs user namespaces it may not have.
    args: ["--no-sandbox"],
  });
  try {
    const page = await browser.newPage({ viewport: { width: 1200, height: 900 } });
    const blank = await browser.newPage();
    const problems = [];
    await watch(page, problems);
    await page.goto(pathToFileURL(index).href, { waitUntil: "load" });
    console.log(`${index}:`);
    let count = await checkImages(page, blank, problems);
    const view = await checkView(page, blank, problems);
    console.log(`  ${view}`);
    // The installation sheet, a page of its own (a report of no path has none).
    const sheet = path.resolve(dir, "install.html");
    if (existsSync(sheet)) {
      const sheetPage = await browser.newPage({ viewport: { width: 1200, height: 900 } });
      await watch(sheetPage, problems);
      await sheetPage.goto(pathToFileURL(sheet).href, { waitUntil: "load" });
      console.log(`${sheet}:`);
      count += await checkImages(sheetPage, blank, problems);
      const pages = await printedPages(sheetPage);
      if (pages !== 1) problems.push(`install.html prints on ${pages} pages, not one`);
      // Readable on paper: no text of the page smaller than 8 pt (10.67 px).
      const smallest = await sheetPage.evaluate(() => {
        let least = Infinity;
        for (const element of document.body.querySelectorAll("*")) {
          const own = [...element.childNodes].some(
            (n) => n.nodeType === Node.TEXT_NODE && n.textContent.trim(),
          );
          if (own) least = Math.min(least, parseFloat(getComputedStyle(element).fontSize));
        }
        return least;
      });
      if (!(smallest >= 10.6)) problems.push(`install.html has text of ${smallest} px (below 8 pt)`);
      console.log(`  printed: ${pages} A4 landscape page(s), smallest text ${(smallest * 0.75).toFixed(1)} pt`);
    }
    const seconds = ((Date.now() - started) / 1000).toFixed(1);
    for (const problem of problems) console.log(`PROBLEM ${problem}`);
    console.log(
      problems.length
        ? `${problems.length} problem(s) (${seconds} s)`
        : `ok: ${count} pictures loaded and drawn, the 3D view plays, no console error, no failed request (${seconds} s)`,
    );
    return problems.length ? 1 : 0;
  } finally {
    await browser.close();
  }
}

main().then(
  (code) => process.exit(code),
  (error) => {
    console.error(`could not check the page: ${error.stack ?? error}`);
    process.exit(2);
  },
);
