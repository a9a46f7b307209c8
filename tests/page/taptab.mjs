// The page's Tap tab as a machinist uses it: node taptab.mjs URL CHROMIUM PROGRAM pastes the
// program, checks it with the fields as a new user leaves them and prints the table's rows
// (JSON) and the console's messages.
import { chromium } from "playwright-core";
import { readFileSync } from "node:fs";

const [url, executablePath, program] = process.argv.slice(2);
const browser = await chromium.launch({ executablePath, args: ["--no-sandbox"] });
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 1000 } });
  const console_ = [];
  page.on("console", (m) => console_.push(m.text()));
  await page.goto(url);
  await page.click("#tab-tap");
  await page.fill("#tap-program", readFileSync(program, "utf8"));
  await page.click("#tap-button");
  await page.waitForSelector("#tap-result:not([hidden])");
  const rows = await page.$$eval("#tap-table tbody tr", (rs) => rs.map((r) => [...r.cells].map((c) => c.textContent)));
  process.stdout.write(JSON.stringify({ rows, console: console_ }));
} finally {
  await browser.close();
}
