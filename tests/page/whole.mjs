// Issue 46: the page's Verify with a program that turns a thread and taps a hole, each named by
// its comment, the thread field left empty: one block per operation, the tapped hole's heading
// naming its tap and where it came from. Usage: node whole.mjs URL OUT CHROMIUM PROGRAM [DIALECT]
// (DIALECT chosen in the Verify tab's dialect list; the shot is named after the program). It
// also reads the control's findings each operation lists and the picture's (issue 63).
import { chromium } from "playwright-core";
import { readFileSync } from "node:fs";
import { join } from "node:path";

const [url, out, executablePath, programFile, dialect] = process.argv.slice(2);
const browser = await chromium.launch({ executablePath, args: ["--no-sandbox"] });
const seen = { console: [] };
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
  page.on("console", (m) => seen.console.push(`${m.type()}: ${m.text()}`));
  page.on("pageerror", (e) => seen.console.push(`pageerror: ${e.message}`));
  await page.goto(url);
  await page.fill("#program", readFileSync(programFile, "utf8"));
  await page.fill("#thread", "");
  await page.selectOption("#insert", "full");
  if (dialect) {
    await page.selectOption("#dialect", dialect);
  }
  seen.dialects = await page.$$eval("#dialect option", (os) => os.map((o) => o.value));
  await page.click("#verify-button");
  await page.waitForSelector("#verify-result:not([hidden])");
  seen.verdict = await page.textContent("#verdict");
  seen.headings = await page.$$eval(".operation h2", (hs) => hs.map((h) => h.textContent));
  seen.verdicts = await page.$$eval(".operation .verdict-small", (ps) => ps.map((p) => p.textContent));
  seen.tap_checks = await page.$$eval(".operation:nth-of-type(2) table.checks tbody tr", (rows) => rows.map((r) => r.cells[0].textContent));
  // Every operation's check rows, each as its cells' text (issue 64: a form tap's hole).
  seen.check_rows = await page.$$eval(".operation table.checks tbody tr", (rows) => rows.map((r) => [...r.cells].map((c) => c.textContent.trim())));
  // Issue 63: what the control will refuse, under the operation it concerns and in the picture.
  seen.control = await page.$$eval(".operation .control li", (ls) => ls.map((l) => ({ level: l.className, text: l.textContent })));
  // The program's notes (issue 65: where each option came from).
  seen.notes = await page.$$eval("ul.notes li", (ls) => ls.map((l) => l.textContent));
  // The picture is an <img> of the SVG the API gives: read that SVG as the page loaded it.
  await page.waitForFunction(() => document.querySelector("#picture").complete && document.querySelector("#picture").src);
  const svg = await page.evaluate(async () => (await fetch(document.querySelector("#picture").src)).text());
  const doc = await page.evaluate((text) => {
    const d = new DOMParser().parseFromString(text, "image/svg+xml");
    return {
      control: [...d.querySelectorAll("#control text")].map((t) => t.textContent.trim()),
      verdict: d.querySelector("#program-verdict text")?.textContent.trim() ?? null,
      text: [...d.querySelectorAll("text")].map((t) => t.textContent.trim()),
    };
  }, svg);
  seen.picture_control = doc.control;
  seen.picture_verdict = doc.verdict;
  seen.picture_text = doc.text;
  seen.shot = join(out, "whole.png");
  await page.screenshot({ path: seen.shot, fullPage: true });
} finally {
  await browser.close();
}
process.stdout.write(JSON.stringify(seen));
