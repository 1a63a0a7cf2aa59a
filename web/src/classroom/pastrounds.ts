/**
 * The class's past rounds on the lecturer's page (issue 45), in both kinds of server: each
 * with when it ended, its players and games, and its links (reopened on the projector, its
 * CSV and JSON exports), newest first. The department's list of classes shows the same.
 */
import { byId, fill, getJson, type Words } from "./common";
import { readerTime } from "./times";

interface Round {
  id: number;
  students: number;
  games: number;
  closes_at: number | null;
}

function link(text: string, href: string, download: boolean): HTMLAnchorElement {
  const a = document.createElement("a");
  a.className = "button";
  a.textContent = text;
  a.href = href;
  if (download) a.download = "";
  else a.target = "_blank";
  return a;
}

/** One round's row: when, what, and its three links. */
function roundRow(words: Words, r: Round, base: string, projector: string): HTMLTableRowElement {
  const tr = document.createElement("tr");
  tr.dataset.round = String(r.id);
  const when = document.createElement("td");
  if (r.closes_at !== null) when.append(readerTime(r.closes_at));
  const what = document.createElement("td");
  what.textContent = fill(words["console.projector.round_line"], { n: r.id, ...r });
  const links = document.createElement("span");
  links.className = "round-links";
  const sep = projector.includes("?") ? "&" : "?";
  const api = `${base}/api/export`;
  links.append(
    link(words["console.lecturer.round_projector"], `${projector}${sep}round=${r.id}`, false),
    link("CSV", `${api}.csv?challenge=${r.id}`, true),
    link("JSON", `${api}.json?challenge=${r.id}`, true),
  );
  const cell = document.createElement("td");
  cell.append(links);
  tr.append(when, what, cell);
  return tr;
}

/** Draw the past rounds into #rounds (hidden while there are none). */
export async function showRounds(words: Words, base: string, projector: string): Promise<void> {
  const got = await getJson<{ rounds: Round[] }>(base + "/api/rounds");
  if (!got.ok) return;
  const table = byId("rounds");
  table.replaceChildren(...got.body.rounds.map((r) => roundRow(words, r, base, projector)));
  byId("rounds-box").hidden = got.body.rounds.length === 0;
}
