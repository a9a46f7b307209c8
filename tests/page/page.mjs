// Drives threadcheck serve's page in Debian's Chromium as a machinist would, through
// playwright-core (no bundled browser): paste a program, choose the thread and the insert, click
// Verify, read the verdict and the correction, download the corrected program and the report;
// upload a file; a bad designation; the compare, fit, limits, tap and thread-mill tabs.
// Screenshots go to OUT.
// Prints one JSON object of what it saw; tests/page.rs checks it.
//
// usage: node page.mjs URL OUT CHROMIUM PROGRAM_FILE UPLOAD_FILE TAP_FILE MILL_FILE MISFIT_FILE
import { chromium } from "playwright-core";
import { readFileSync } from "node:fs";
import { join } from "node:path";

const [url, out, executablePath, programFile, uploadFile, tapFile, millFile, misfitFile] = process.argv.slice(2);
const seen = { console: [], shots: {}, layout: {} };
let step = "load"; // which step a console message came in

const browser = await chromium.launch({ executablePath, headless: true, args: ["--no-sandbox", "--disable-gpu"] });
try {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 }, acceptDownloads: true });
  const page = await context.newPage();
  page.on("console", (m) => seen.console.push(`${step}: ${m.type()}: ${m.text()}`));
  page.on("pageerror", (e) => seen.console.push(`${step}: uncaught: ${e.message}`));
  page.on("requestfailed", (r) => seen.console.push(`${step}: request failed: ${r.url()}`));

  // What a screenshot should show: nothing wider than the window, every picture loaded and
  // inside it.
  const layout = (name) => page.evaluate((name) => {
    const vw = document.documentElement.clientWidth;
    const pics = [...document.querySelectorAll("img")].filter((i) => i.offsetParent !== null);
    return {
      name,
      scroll_width: document.documentElement.scrollWidth,
      viewport_width: vw,
      pictures: pics.map((i) => {
        const r = i.getBoundingClientRect();
        return { id: i.id, loaded: i.complete && i.naturalWidth > 0, left: r.left, right: r.right, width: r.width, height: r.height };
      }),
    };
  }, name);
  const shot = async (name) => {
    const path = join(out, name + ".png");
    await page.screenshot({ path, fullPage: true });
    seen.shots[name] = path;
    seen.layout[name] = await layout(name);
  };
  const pictureLoaded = (id) => page.waitForFunction((id) => {
    const i = document.getElementById(id);
    return i && i.complete && i.naturalWidth > 0;
  }, id);

  await page.goto(url);
  seen.title = await page.title();

  step = "verify";
  // 1. Paste a program and verify, every other field as a new user finds it (issue 59: the
  // thread was pre-filled and checked every pasted program against M20x1.5-6g).
  seen.fields_as_found = await page.evaluate(() => ({
    thread: document.getElementById("thread").value,
    insert: document.getElementById("insert").value,
    tap_tools: document.getElementById("tap-tools").value,
    mill_thread: document.getElementById("mill-thread").value,
    mill_diameter: document.getElementById("mill-diameter").value,
  }));
  await page.fill("#program", readFileSync(programFile, "utf8"));
  await page.click("#verify-button");
  await page.waitForSelector("#verify-result:not([hidden])");
  await pictureLoaded("picture");
  seen.verdict = await page.textContent("#verdict");
  // The picture's own title names the pasted program.
  seen.pasted_heading = await page.evaluate(async () => {
    const svg = await (await fetch(document.getElementById("picture").src)).text();
    return svg.slice(0, 2000);
  });
  seen.correction = await page.textContent(".operation .correction");
  seen.checks = await page.$$eval("table.checks tr", (rows) => rows.map((r) => [...r.cells].map((c) => c.textContent)));
  seen.passes = await page.$$eval("table.passes tbody tr", (rows) => rows.map((r) => [...r.cells].map((c) => c.textContent)));
  await shot("verify");
  // The window as the machinist sees it (the README's picture, reports/serve-page.png).
  await page.evaluate(() => document.getElementById("verdict").scrollIntoView());
  await page.evaluate(() => window.scrollBy(0, -40));
  await page.screenshot({ path: join(out, "verify-window.png") });

  // Nothing to download as a corrected program: the correction waits for the insert.
  seen.fixed_visible_as_found = await page.evaluate(() => !document.getElementById("download-fixed").hidden);
  step = "insert";
  // 2. The insert chosen: the correction is offered.
  await page.selectOption("#insert", "full");
  await page.click("#verify-button");
  await page.waitForFunction(() => document.getElementById("verify-result").dataset.run === "2");
  seen.correction_full = await page.textContent(".operation .correction");

  step = "downloads";
  // Downloads: the corrected program and the HTML report.
  for (const [button, file] of [["#download-fixed", "fixed.nc"], ["#download-html", "report.html"], ["#download-json", "report.json"]]) {
    const [download] = await Promise.all([page.waitForEvent("download"), page.click(button)]);
    const path = join(out, file);
    await download.saveAs(path);
    seen[file] = { path, suggested: download.suggestedFilename() };
  }

  step = "upload";
  // 3. Upload a LinuxCNC file: the dialect follows its name.
  await page.setInputFiles("#program-file", uploadFile);
  await page.waitForFunction(() => document.getElementById("program").value.includes("G76"));
  await page.fill("#thread", "1/4-20 UNC-2A");
  await page.selectOption("#insert", "partial");
  await page.click("#verify-button");
  await page.waitForFunction(() => document.getElementById("verify-result").dataset.run === "3");
  seen.upload_notes = await page.$$eval(".notes li", (l) => l.map((x) => x.textContent));
  seen.upload_heading = await page.textContent(".operation h2");

  step = "bad-designation";
  // 4. A designation that does not exist: one line, the CLI's.
  await page.fill("#thread", "M20x1.5-6q");
  await page.click("#verify-button");
  await page.waitForSelector("#verify-error:not([hidden])");
  seen.error = await page.textContent("#verify-error");
  // Nothing of the last answer may stand beside the error (issue 43).
  seen.after_error = await page.evaluate(() => {
    const visible = (id) => { const e = document.getElementById(id); return !!e && !e.hidden && e.offsetParent !== null; };
    return {
      result_visible: visible("verify-result"),
      verdict: document.getElementById("verdict").textContent,
      next_visible: visible("next"),
      fixed_visible: visible("download-fixed"),
      operations: document.querySelectorAll("#operations .operation").length,
      picture: document.getElementById("picture").getAttribute("src"),
    };
  });
  await shot("after-error");
  // Issue 59: a real M30x1.5 program checked against a designation typed by mistake: refused
  // naming both diameters, and no next step (it advised a 5 mm plunge).
  step = "misfit";
  await page.fill("#program", ""); // forget the uploaded file's name (and its dialect)
  await page.fill("#program", readFileSync(misfitFile, "utf8"));
  await page.fill("#thread", "M20x1.5-6g");
  await page.click("#verify-button");
  await page.waitForFunction(() => !document.getElementById("verify-error").hidden
    && document.getElementById("verify-error").textContent.includes("Ø30"));
  seen.misfit = {
    error: await page.textContent("#verify-error"),
    next_visible: await page.evaluate(() => { const e = document.getElementById("next"); return !e.hidden && e.offsetParent !== null; }),
    corrections: await page.$$eval(".correction", (l) => l.filter((e) => e.offsetParent !== null).map((e) => e.textContent)),
  };
  await shot("misfit");
  // A size outside the series: the error names the page's own control, which accepts it (a
  // generated plan: the program field emptied).
  step = "nonstandard";
  await page.fill("#program", "");
  await page.fill("#thread", "M20x1.25-6g");
  await page.click("#verify-button");
  await page.waitForSelector("#verify-error:not([hidden])");
  seen.nonstandard_error = await page.textContent("#verify-error");
  await page.check("#allow-nonstandard");
  await page.click("#verify-button");
  await page.waitForFunction(() => document.getElementById("verify-result").dataset.run === "4");
  seen.nonstandard_verdict = await page.textContent("#verdict");
  seen.nonstandard_hint = await page.textContent(".operation .hint");
  await shot("form-only");
  await page.uncheck("#allow-nonstandard");

  step = "compare";
  // 5. Compare.
  await page.click("#tab-compare");
  await page.click("#compare-button");
  await page.waitForSelector("#compare-result:not([hidden])");
  seen.compare_rows = await page.$$eval("#compare-table tbody tr", (rows) => rows.length);
  seen.compare_recommended = await page.textContent("#compare-recommended");
  await shot("compare");

  step = "fit";
  // 6. Fit.
  await page.click("#tab-fit");
  await page.click("#fit-button");
  await page.waitForSelector("#fit-result:not([hidden])");
  await pictureLoaded("fit-picture");
  seen.fit = await page.textContent("#fit-verdict");
  await shot("fit");

  step = "limits";
  // 7. Limits.
  await page.click("#tab-limits");
  await page.click("#limits-button");
  await page.waitForSelector("#limits-table:not([hidden])");
  seen.limits = await page.$$eval("#limits-table tbody tr", (rows) => rows.map((r) => [...r.cells].map((c) => c.textContent)));
  await shot("limits");
  // A rolled thread's blank (issue 64).
  await page.check("#limits-rolled");
  await page.click("#limits-button");
  await page.waitForFunction(() => [...document.querySelectorAll("#limits-table tbody tr")].some((r) => r.cells[0].textContent === "rolled"));
  seen.limits_rolled = await page.$$eval("#limits-table tbody tr", (rows) => rows.filter((r) => r.cells[0].textContent === "rolled").map((r) => [...r.cells].map((c) => c.textContent)));

  step = "tap";
  // 8. Tap: a program with its drilling and tapping cycles, uploaded; a tool table typed.
  await page.click("#tab-tap");
  await page.setInputFiles("#tap-program-file", tapFile);
  await page.waitForFunction(() => document.getElementById("tap-program").value.length > 0);
  await page.fill("#tap-tools", '[tools]\n5 = "drill:8.5"\n6 = "tap:M10x1.5-6H"\n');
  // The workpiece and the tap's kind: each hole's torque (issue 64).
  await page.selectOption("#tap-material", "ck45");
  await page.selectOption("#tap-kind", "hand-plug");
  await page.click("#tap-button");
  await page.waitForSelector("#tap-result:not([hidden])");
  await pictureLoaded("tap-picture");
  seen.tap = await page.textContent("#tap-verdict");
  seen.tap_rows = await page.$$eval("#tap-table tbody tr", (rows) => rows.map((r) => [...r.cells].map((c) => c.textContent)));
  await shot("tap");

  step = "mill";
  // 9. Thread mill: a program pasted, its thread and an Ø14 cutter typed.
  await page.click("#tab-mill");
  await page.fill("#mill-program", readFileSync(millFile, "utf8"));
  await page.fill("#mill-thread", "M20x1.5-6H");
  await page.fill("#mill-diameter", "14");
  await page.click("#mill-button");
  await page.waitForSelector("#mill-result:not([hidden])");
  await pictureLoaded("mill-picture");
  seen.mill = await page.textContent("#mill-verdict");
  seen.mill_distortion = await page.textContent("#mill-distortion");
  seen.mill_rows = await page.$$eval("#mill-table tbody tr", (rows) => rows.map((r) => [...r.cells].map((c) => c.textContent)));
  await shot("mill");

  step = "narrow";
  // 10. A narrow window (a tablet at the machine): the verify page still fits.
  await page.setViewportSize({ width: 800, height: 900 });
  await page.click("#tab-verify");
  await shot("verify-narrow");
} finally {
  await browser.close();
}
process.stdout.write(JSON.stringify(seen));
