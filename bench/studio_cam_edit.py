"""The studio's cam design page in Chromium: segment edits timed from the
edit sent to the page redrawn with the analysed design (issue 29).

For each design file `camlink studio` is started on a copy (in a process
of its own), the page is opened in Debian's chromium (Playwright,
headless) and segment laws are edited one at a time (the design stays
valid): each time is from the websocket send to the next animation frame
after the reply was shown (the server reading the edited design and
analysing it as `camlink cam` does, every check of its report included;
the page decoding SVAJ, the pressure angle and the profile and drawing
them and the report). Two runs of edits:

- *new programs*: each edit gives a motion program not seen before (the
  rises and returns take the laws of `LAWS` in turn), so the server
  analyses it, the base circle search of ``base_radius_search`` included;
- *back and forth*: one segment's law switched between two laws, so every
  edit after the first two returns to data seen before, whose analysis
  the server keeps (`camlink.studio.cam.CACHED`).

    uv run python bench/studio_cam_edit.py [--edits 8]   # at most 4 per edited segment
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import tempfile
import tomllib
from pathlib import Path

from studio_drag import ROOT, Studio, pct

#: (design file, its rises and returns, the two laws one switches between).
CASES = (
    ("cam_design_valve.toml", (1, 3), "4-5-6-7", "cycloidal"),
    ("cam_design_indexing.toml", (0, 2, 4, 6), "modified-sine", "cycloidal"),
)
#: Laws of a rise or return that need no end conditions.
LAWS = ("cycloidal", "modified-trapezoid", "modified-sine", "3-4-5", "4-5-6-7")

EDITS = """async (edits) => {
  const S = camlinkCam, times = [];
  for (let k = 0; k < edits.length; k++) {
    const t0 = performance.now();
    const [index, law] = edits[k];
    const seq = S.send({ op: "segment", index: index, key: "law", value: law, gesture: "b" + k });
    await S.after(seq);
    await new Promise(requestAnimationFrame);
    times.push(performance.now() - t0);
  }
  return times;
}"""


def new_programs(path: Path, segments: tuple[int, ...], n: int) -> list[tuple[int, str]]:
    """n edits, each giving a program not seen before (nor the file's
    own): edit k gives segment k mod m (of the m `segments`) the next of
    the laws of `LAWS` other than its law in the design file `path`, so
    every segment moves on one law every m edits; n ≤ m (len(LAWS) − 1)."""
    m = len(segments)
    if n > m * (len(LAWS) - 1):
        raise SystemExit(f"at most {m * (len(LAWS) - 1)} new programs for {m} segments")
    given = tomllib.loads(path.read_text())["segments"]
    others = {s: [law for law in LAWS if law != given[s]["law"]] for s in segments}
    return [(segments[k % m], others[segments[k % m]][k // m]) for k in range(n)]


def times(browser: object, path: Path, edits: list[tuple[int, str]]) -> list[float]:
    studio = Studio(path)
    try:
        page = browser.new_page(viewport={"width": 1240, "height": 1020})  # type: ignore[attr-defined]
        page.route("**/*", lambda r: r.continue_() if r.request.url.startswith("http://127.0.0.1:")
                   else r.abort())
        page.goto(studio.url)
        page.wait_for_function("() => window.camlinkCam && camlinkCam.answered >= camlinkCam.sent()"
                               " && camlinkCam.sent() > 0", timeout=30_000)
        out: list[float] = page.evaluate(EDITS, edits)
        page.close()
        return out
    finally:
        studio.close()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--edits", type=int, default=8)
    args = ap.parse_args()
    from playwright.sync_api import sync_playwright

    print("| design | edits | kind | page median (ms) | page p95 (ms) |")
    print("|---|---:|---|---:|---:|")
    with sync_playwright() as p, tempfile.TemporaryDirectory() as tmp:
        browser = p.chromium.launch(executable_path=shutil.which("chromium"), args=["--no-sandbox"])
        for name, segments, a, b in CASES:
            path = Path(tmp) / name
            runs = (("new programs", new_programs(ROOT / "examples" / name, segments, args.edits)),
                    ("back and forth", [(segments[0], b if k % 2 == 0 else a)
                                        for k in range(args.edits)]))
            for kind, edits in runs:
                shutil.copy(ROOT / "examples" / name, path)
                t = times(browser, path, edits)
                print(f"| {name} | {len(t)} | {kind} | {statistics.median(t):.1f} "
                      f"| {pct(t, 0.95):.1f} |", flush=True)
        browser.close()


if __name__ == "__main__":
    main()
