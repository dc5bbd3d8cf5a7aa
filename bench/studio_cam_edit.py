"""The studio's cam design page in Chromium: segment edits timed from the
edit sent to the page redrawn with the analysed design (issue 29).

For each design file a studio server is started on a copy, the page is
opened in Debian's chromium (Playwright, headless) and one segment's law
is switched between two laws, one edit at a time (the design stays
valid): each time is from the websocket send to the next animation frame
after the reply was shown (the server reading the edited design and
analysing it as `camlink cam` does, every check of its report included;
the page decoding SVAJ, the pressure angle and the profile and drawing
them and the report).

    uv run python bench/studio_cam_edit.py [--edits 40]
"""

from __future__ import annotations

import argparse
import asyncio
import shutil
import statistics
import sys
import tempfile
import threading
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))

from camlink.studio import StudioServer  # noqa: E402

#: (design file, segment, the two laws it switches between).
CASES = (
    ("cam_design_valve.toml", 1, "4-5-6-7", "cycloidal"),
    ("cam_design_indexing.toml", 0, "modified-sine", "cycloidal"),
)

EDITS = """async ([n, i, a, b]) => {
  const S = camlinkCam, times = [];
  for (let k = 0; k < n; k++) {
    const t0 = performance.now();
    const seq = S.send({ op: "segment", index: i, key: "law", value: k % 2 ? a : b, gesture: "b" + k });
    await S.after(seq);
    await new Promise(requestAnimationFrame);
    times.push(performance.now() - t0);
  }
  return times;
}"""


def times(browser: object, path: Path, index: int, a: str, b: str, n: int) -> list[float]:
    server = StudioServer(path)
    loop = asyncio.new_event_loop()
    thread = threading.Thread(target=loop.run_forever, daemon=True)
    thread.start()
    url = asyncio.run_coroutine_threadsafe(server.start(), loop).result(30)
    try:
        page = browser.new_page(viewport={"width": 1240, "height": 1020})  # type: ignore[attr-defined]
        page.route("**/*", lambda r: r.continue_() if r.request.url.startswith("http://127.0.0.1:")
                   else r.abort())
        page.goto(url)
        page.wait_for_function("() => window.camlinkCam && camlinkCam.answered >= camlinkCam.sent()"
                               " && camlinkCam.sent() > 0", timeout=30_000)
        out: list[float] = page.evaluate(EDITS, [n, index, a, b])
        page.close()
        return out
    finally:
        asyncio.run_coroutine_threadsafe(server.stop(), loop).result(30)
        loop.call_soon_threadsafe(loop.stop)
        thread.join(10)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--edits", type=int, default=40)
    args = ap.parse_args()
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p, tempfile.TemporaryDirectory() as tmp:
        browser = p.chromium.launch(executable_path=shutil.which("chromium"), args=["--no-sandbox"])
        for name, index, a, b in CASES:
            path = Path(tmp) / name
            shutil.copy(ROOT / "examples" / name, path)
            t = sorted(times(browser, path, index, a, b, args.edits))
            p95 = t[max(0, int(0.95 * len(t)) - 1)]
            print(f"{name}: {len(t)} law edits, median {statistics.median(t):.1f} ms, "
                  f"95th percentile {p95:.1f} ms")
        browser.close()


if __name__ == "__main__":
    main()
