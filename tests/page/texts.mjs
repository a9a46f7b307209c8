// Every text element of a picture as Chromium renders it: node texts.mjs CHROMIUM FILE.svg
// [SELECTOR] prints a JSON array of the texts' contents (entities decoded, as a reader sees
// them), the texts inside the elements SELECTOR names only when it is given.
import { chromium } from "playwright-core";

const [executablePath, file, selector] = process.argv.slice(2);
const browser = await chromium.launch({ executablePath, args: ["--no-sandbox"] });
try {
  const page = await browser.newPage();
  await page.goto("file://" + file);
  const texts = await page.$$eval(selector ? `${selector} text` : "text", (ts) => ts.map((t) => t.textContent.trim()));
  process.stdout.write(JSON.stringify(texts));
} finally {
  await browser.close();
}
