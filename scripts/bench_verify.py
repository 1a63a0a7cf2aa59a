"""Verification cost per classic game (issue 22): replay of autopilot recordings, median ms.

Run: python scripts/bench_verify.py [GAMES]  (fast and reference engines interleaved).

Then the class server's whole check of each game (issue 47: decode, replay and path, the
result's record; `classroom.verifier.check_submission`), in CPU time (time.process_time,
which a shared machine's other processes do not add to), median of five per game.
"""

from __future__ import annotations

import statistics
import sys
import time

from evapcool.game.replay import Settings, record_autopilot, verify


def main() -> None:
    games = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    recs = [record_autopilot("demo", Settings(), seed=s, engine="fast") for s in range(games)]
    verify(recs[0], engine="fast")  # compile once
    cost: dict[str, list[float]] = {"fast": [], "reference": []}
    for rec in recs:
        for engine in cost:
            t = time.perf_counter()
            verify(rec, engine=engine)
            cost[engine].append((time.perf_counter() - t) * 1e3)
    frames = statistics.median(r.frames for r in recs)
    for engine, ms in cost.items():
        med = statistics.median(ms)
        print(
            f"{engine:>9}: median {med:.0f} ms per game ({frames:.0f} frames), "
            f"{1e3 / med:.1f} games/s on one core, n={len(ms)}"
        )
    whole_check(recs)


def whole_check(recs: list) -> None:
    """The server's check of each code (issue 47's target: <= 12 ms of CPU)."""
    from evapcool.classroom.verifier import check_submission
    from evapcool.game.replay import encode

    for label, make in (("desktop's codes", encode), ("page-like codes", page_like_code)):
        per_game = [check_cost(make(rec), rec, check_submission) for rec in recs]
        print(
            f"whole check (decode, replay and path), {label}: median "
            f"{statistics.median(per_game):.1f} ms of CPU per game (per game: "
            f"{', '.join(f'{m:.1f}' for m in per_game)})"
        )


def page_like_code(rec) -> str:
    """A code as the page writes it: JSON.stringify's numbers (450, not 450.0), fields
    unsorted, deflated at zlib's default level (CompressionStream): the server packs its
    text again (the desktop's code it keeps as sent)."""
    import base64
    import json
    import zlib

    from evapcool.game.replay import CODE_PREFIX

    def js(x):
        return int(x) if isinstance(x, float) and x.is_integer() else x

    doc = rec.to_json()
    doc["moves"] = [[js(h), n] for h, n in doc["moves"]]
    doc["settings"] = {k: js(v) for k, v in doc["settings"].items()}
    text = json.dumps(doc, separators=(",", ":"))
    payload = base64.urlsafe_b64encode(zlib.compress(text.encode(), 6)).decode().rstrip("=")
    crc = zlib.crc32(payload.encode("ascii")) & 0xFFFFFFFF  # any version's checksum
    return f"{CODE_PREFIX}.{payload}.{crc:08x}"


def check_cost(code: str, rec, check_submission) -> float:
    """Median CPU ms of five checks of one code (the challenge its game was played in)."""
    from evapcool.classroom.verifier import SETTING_NAMES

    challenge = {
        "settings": {name: getattr(rec.settings, name) for name in SETTING_NAMES},
        "seed": rec.seed,
        "max_frames": rec.n_frames,
        "lost": True,
    }
    runs = []
    for _ in range(5):
        t = time.process_time()
        got = check_submission(code, "code", challenge)
        runs.append((time.process_time() - t) * 1e3)
        assert got.get("score") == rec.score, got
    return statistics.median(runs)


if __name__ == "__main__":
    main()
