/**
 * The console's list pages (the administrator's, a department lecturer's classes): copy
 * buttons for links, and a confirmation before a form that cannot be undone (data-confirm).
 * Times (past rounds) are written in the reader's language and time zone. Everything works
 * without it but the copying; it only adds.
 */
import "./console.css";
import { pageWords } from "./common";
import { localizeTimes, readerLocale } from "./times";

const words = pageWords();

/** Copy a link; the button says so for a moment (the box beside it is selected too). */
async function copy(button: HTMLButtonElement): Promise<void> {
  const text = button.dataset["copy"] ?? "";
  const box = button.parentElement?.querySelector<HTMLInputElement>("input.link");
  box?.select();
  try {
    await navigator.clipboard.writeText(text);
  } catch {
    document.execCommand("copy"); // an http:// page on a LAN has no clipboard API
  }
  button.textContent = words["console.copied"] ?? "";
  button.classList.add("on");
  setTimeout(() => {
    button.textContent = words["console.copy"] ?? "";
    button.classList.remove("on");
  }, 2000);
}

for (const b of document.querySelectorAll<HTMLButtonElement>("button[data-copy]"))
  b.onclick = () => void copy(b);
for (const f of document.querySelectorAll<HTMLFormElement>("form[data-confirm]"))
  f.onsubmit = (ev) => {
    if (!window.confirm(f.dataset["confirm"] ?? words["console.sure"] ?? "")) ev.preventDefault();
  };
localizeTimes(document, readerLocale(document.documentElement.lang, navigator.languages));
