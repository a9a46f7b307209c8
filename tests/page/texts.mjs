// Every text element of a picture as Chromium renders it: node texts.mjs CHROMIUM FILE.svg
// prints a JSON array of the texts' contents (entities decoded, as a reader sees them).
import { chromium } from "playwright-core";

const [executablePath, file] = process.argv.slice(2);
const browser = await chromium.launch({ executablePath, args: ["--no-sandbox"] });
try {
  const page = await browser.newPage();
  await page.goto("file://" + file);
  const texts = await page.$$eval("text", (ts) => ts.map((t) => t.textContent.trim()));
  process.stdout.write(JSON.stringify(texts));
} finally {
  await browser.close();
}
