// Every text element of a picture as Chromium renders it: node texts.mjs CHROMIUM FILE.svg
// [SELECTOR] prints a JSON array of the texts' contents (entities decoded, as a reader sees
// them), the texts inside the elements SELECTOR names only when it is given. A page
// (FILE.html) gives its headings and paragraphs as a reader sees them instead.
import { chromium } from "playwright-core";

const [executablePath, file, selector] = process.argv.slice(2);
const browser = await chromium.launch({ executablePath, args: ["--no-sandbox"] });
try {
  const page = await browser.newPage();
  await page.goto("file://" + file);
  const tags = file.endsWith(".html") ? ["h1", "h2", "h3", "p", "li"] : ["text"];
  const query = tags.map((t) => (selector ? `${selector} ${t}` : t)).join(", ");
  const texts = await page.$$eval(query, (ts) => ts.map((t) => (t.innerText ?? t.textContent).trim()));
  process.stdout.write(JSON.stringify(texts));
} finally {
  await browser.close();
}
