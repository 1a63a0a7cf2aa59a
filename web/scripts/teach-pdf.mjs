// The teacher tips' activities as PDFs (issue 48): each "### N. ..." section of the docs'
// teach page printed on its own by headless Chromium (page.pdf), with the page's print style.
//
//   node web/scripts/teach-pdf.mjs site/teach/index.html site/teach
//
// Writes activity-1.pdf, activity-2.pdf, ... into the folder, and activities.json: for each,
// its file, its title and the text that was on the page when it was printed (the tests read
// it). CI runs it on the built site (.github/workflows/pages.yml); tests/test_docs.py on a
// page made from docs/teach.md.
import { writeFileSync } from "node:fs";
import { join, resolve } from "node:path";
import { pathToFileURL } from "node:url";
import { launch } from "../test/e2e/browser.mjs";

const [page, out] = process.argv.slice(2);
if (!page || !out) {
  console.error("usage: node web/scripts/teach-pdf.mjs PAGE.html OUT_DIR");
  process.exit(2);
}

const browser = await launch();
try {
  const tab = await browser.context.newPage();
  await tab.goto(pathToFileURL(resolve(page)).href);
  await tab.emulateMedia({ media: "print" });
  const titles = await tab.$$eval("article.md-typeset h3", (hs) =>
    hs.map((h) => h.textContent.replace("¶", "").trim()),
  );
  const activities = titles.filter((title) => /^\d+\./.test(title));
  if (activities.length === 0) throw new Error(`no activity (### 1. ...) in ${page}`);
  const made = [];
  for (const [k, title] of activities.entries()) {
    // Only this activity: its heading and what follows it up to the next heading of its rank.
    const text = await tab.evaluate((wanted) => {
      const body = document.querySelector("article.md-typeset");
      const kids = [...body.children];
      const start = kids.findIndex(
        (el) => el.tagName === "H3" && el.textContent.replace("¶", "").trim() === wanted,
      );
      let keep = true;
      kids.forEach((el, i) => {
        if (i === start) keep = true;
        else if (i > start && /^H[1-3]$/.test(el.tagName)) keep = false;
        el.style.display = i >= start && keep ? "" : "none";
      });
      return body.innerText;
    }, title);
    const file = `activity-${k + 1}.pdf`;
    await tab.pdf({ path: join(out, file), format: "A4", printBackground: false });
    made.push({ file, title, text });
  }
  writeFileSync(join(out, "activities.json"), JSON.stringify(made, null, 1) + "\n");
  console.log(`wrote ${made.length} activities to ${out}`);
} finally {
  await browser.close();
}
