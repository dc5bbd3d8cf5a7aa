"""The studio's edit loop in Chromium: scripted drags, timed from the edit
sent to the page redrawn with the re-solved cycle (issue 29).

For each model, `camlink studio` is started on a copy of the file, the page
is opened in Debian's chromium (Playwright, headless, every request off
127.0.0.1 blocked), and a handle is dragged through 200 positions, one
edit at a time: each time is from the websocket send to the end of the
page's redraw of the reply (the server rebuilding the model from the
edited text, solving the whole cycle in the core and sending it; the page
decoding it and drawing the stage and the plots). The server's own share
(edit + solve + reply data of the default plots, no browser) is timed too,
in-process, in wall time and in the thread's CPU time.

Models: examples/four_bar.toml (401 times), a six-bar
(examples/whitworth_global.toml, 201 times), the seed's cam
(examples/cam_seed_example_3_4_3.toml, 401 times), and a chain of 100
bodies and 100 pins (200 joints with its drivers; 361 times).

Each browser time is split as the page records it (`camlinkStudio.phases`):
*wait*, from the send to the reply's arrival, of which *server* is the
server's share (from the request's arrival to its reply made: edit, solve,
reply data); *page*, the page's own work (parsing the reply and drawing
it). *Chromium CPU* is the CPU time of every Chromium process over the
drags, per edit (the renderer's layout, paint and raster, the compositor,
the network service, DevTools' reports to Playwright), from /proc.

With ``--base DIR`` (another checkout, its extension built, e.g. a
``git worktree`` of main), each model's drags are run against that
checkout's studio and this one's in turn, ``--rounds`` times, in the same
browser and the same minutes, for an A/B comparison on a machine whose
load changes: a second table gives both sides' page median and p95 over
all their rounds (a side whose page records no phases shows none).

    uv run python bench/studio_drag.py [--drags 200] [--models four-bar,cam]
                                       [--base ../main --rounds 3]
"""

from __future__ import annotations

import argparse
import math
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))

from camlink.studio import payload  # noqa: E402
from camlink.studio.document import Document  # noqa: E402

MODELS = [
    ("four-bar", "four_bar.toml", "joint:B"),
    ("six-bar (Whitworth)", "whitworth_global.toml", "joint:O2"),
    ("seed cam 3.4.3", "cam_seed_example_3_4_3.toml", "joint:cam_pivot"),
]


def chain_toml(n: int) -> str:
    """A serial chain of n links of 0.05 m, pinned end to end from the
    ground, each pin driven to swing ±0.1 rad at 1 Hz."""
    lines = ['[model]\nname = "chain"\n[ground]\npoints = { O = [0, 0] }\n']
    for k in range(n):
        lines.append(f'[[bodies]]\nname = "b{k}"\nposition = [{0.05 * k}, 0]\n'
                     'points = { P = [0, 0], Q = [0.05, 0] }\n')
    for k in range(n):
        prev, point = ("ground", "O") if k == 0 else (f"b{k - 1}", "Q")
        lines.append(f'[[joints]]\nname = "j{k}"\ntype = "revolute"\nbody_i = "{prev}"\n'
                     f'point_i = "{point}"\nbody_j = "b{k}"\npoint_j = "P"\n')
    for k in range(n):
        lines.append(f'[[drivers]]\nname = "d{k}"\ntype = "revolute_angle"\njoint = "j{k}"\n'
                     'f = "0.1*sin(2*pi*t)"\n')
    lines.append(f'[analysis]\nt_end = 1\nstep = {1 / 360!r}\npoints = ["b{n - 1}.Q"]\n')
    return "".join(lines)


def pct(values: list[float], q: float) -> float:
    s = sorted(values)
    return s[min(len(s) - 1, math.ceil(q * len(s)) - 1)]


class Studio:
    """`camlink studio FILE --no-browser` in a process of its own, as a user
    runs it (not in this process, where Playwright's client would share
    its interpreter), from the checkout `root` (default this one)."""

    def __init__(self, path: Path, root: Path = ROOT) -> None:
        env = {**os.environ, "PYTHONPATH": str(root / "python")}
        self.proc = subprocess.Popen([sys.executable, "-m", "camlink", "studio", str(path),
                                      "--no-browser"], stdout=subprocess.PIPE, text=True, env=env)
        assert self.proc.stdout is not None
        line = self.proc.stdout.readline()
        if not line.startswith("camlink studio: "):
            self.proc.kill()
            raise RuntimeError(f"camlink studio did not start: {line!r}")
        self.url = line.split(": ", 1)[1].strip()

    def close(self) -> None:
        self.proc.send_signal(signal.SIGINT)
        try:
            self.proc.wait(30)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()


DRAG = """async ([id, n]) => {
  const S = camlinkStudio, F = S.front;
  const start = F.handle(id), times = [], phases = [], scale = F.scale();
  for (let i = 0; i < n; i++) {
    const a = 2 * Math.PI * i / n, r = 12 / scale;
    const t0 = performance.now();
    const seq = S.send({ op: "move", handle: id, row: F.frame(), gesture: "bench",
                         x: start[0] + r * Math.sin(a), y: start[1] + r * (1 - Math.cos(a)) });
    await S.after(seq);
    times.push(performance.now() - t0);
    phases.push(S.phases ? S.phases[seq] : null);  // null: a page that does not record them
  }
  return [times, phases];
}"""


def chromium_cpu() -> float:
    """CPU time (ms, user + system) of the Chromium processes this process
    started (through Playwright's driver), from /proc; 0 without /proc."""
    procs: dict[int, tuple[int, str, int]] = {}
    for entry in Path("/proc").glob("[0-9]*"):
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue
        name, rest = stat[stat.index("(") + 1: stat.rindex(")")], stat[stat.rindex(")") + 2:].split()
        procs[int(entry.name)] = (int(rest[1]), name, int(rest[11]) + int(rest[12]))
    mine = {os.getpid()}
    grew = True
    while grew:
        grew = False
        for pid, (parent, _, _) in procs.items():
            if parent in mine and pid not in mine:
                mine.add(pid)
                grew = True
    ticks = sum(procs[p][2] for p in mine if "chrom" in procs[p][1].lower())
    return 1e3 * ticks / os.sysconf("SC_CLK_TCK")


class BrowserRun:
    """The times (ms) of one model's drags in the page: each edit's total,
    wait, server share and page work; the Chromium CPU per edit."""

    def __init__(self, browser: object, path: Path, handle: str, drags: int,
                 root: Path = ROOT) -> None:
        studio = Studio(path, root)
        try:
            page = browser.new_page(viewport={"width": 1300, "height": 900})  # type: ignore[attr-defined]
            page.route("**/*", lambda r: r.continue_()
                       if r.request.url.startswith("http://127.0.0.1:") else r.abort())
            page.goto(studio.url)
            page.wait_for_function("() => window.camlinkStudio && camlinkStudio.answered >= 1")
            page.evaluate(DRAG, [handle, 10])  # warm up
            c0 = chromium_cpu()
            self.total, phases = page.evaluate(DRAG, [handle, drags])
            self.chromium_cpu = (chromium_cpu() - c0) / drags
            page.close()
        finally:
            studio.close()
        split = [p for p in phases if p is not None]
        self.wait = [p[0] for p in split]
        self.page = [p[1] + p[2] for p in split]
        self.server = [p[3] for p in split]


def server_times(path: Path, handle: str, drags: int) -> tuple[list[float], list[float]]:
    """Wall and thread CPU time (ms) of each edit in-process: the CPU time
    is the work itself, which a loaded machine does not inflate."""
    doc = Document(path)
    h = next(x for x in doc.solution.handles if x.id == handle)
    q = doc.solution.pose(h.body, 0)
    c, s = math.cos(q[2]), math.sin(q[2])
    x0, y0 = q[0] + c * h.local[0] - s * h.local[1], q[1] + s * h.local[0] + c * h.local[1]
    wall, cpu = [], []
    for i in range(drags):
        a = 2 * math.pi * i / drags
        t0, c0 = time.perf_counter(), time.thread_time()
        doc.move(handle, 0, x0 + 0.002 * math.sin(a), y0 + 0.002 * (1 - math.cos(a)), gesture="b")
        payload(doc, [])
        wall.append(1e3 * (time.perf_counter() - t0))
        cpu.append(1e3 * (time.thread_time() - c0))
    return wall, cpu


def med(xs: list[float]) -> float:
    return statistics.median(xs) if xs else math.nan


def head_of(root: Path) -> str:
    """The short commit of the checkout `root` ("?" when not a git one)."""
    out = subprocess.run(["git", "-C", str(root), "rev-parse", "--short", "HEAD"],
                         capture_output=True, text=True).stdout.strip()
    return out or "?"


def compare(browser: object, cases: list[tuple[str, Path, str]], base: Path, drags: int,
            rounds: int) -> None:
    """The drags of each case against the checkout `base` and this one in
    turn, `rounds` times: both sides' page median and p95 (ms) over all
    their drags, and the medians of their phases."""
    print(f"\nA/B, back to back: base {base} ({head_of(base)}) against this checkout "
          f"({head_of(ROOT)}), {rounds} rounds of {drags} drags each, alternating")
    print("| model | side | page median (ms) | page p95 (ms) | wait median | server median "
          "| page work median | Chromium CPU per edit |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for label, path, handle in cases:
        runs: dict[str, list[BrowserRun]] = {"base": [], "this": []}
        for _ in range(rounds):
            for side, root in (("base", base), ("this", ROOT)):
                shutil.copy(path.with_suffix(".orig"), path)
                runs[side].append(BrowserRun(browser, path, handle, drags, root))
        for side, done in runs.items():
            total = [x for r in done for x in r.total]
            cpu = statistics.mean(r.chromium_cpu for r in done)
            print(f"| {label} | {side} | {med(total):.1f} | {pct(total, 0.95):.1f} "
                  f"| {med([x for r in done for x in r.wait]):.1f} "
                  f"| {med([x for r in done for x in r.server]):.1f} "
                  f"| {med([x for r in done for x in r.page]):.1f} | {cpu:.1f} |", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--drags", type=int, default=200)
    ap.add_argument("--models", default="four-bar,six-bar,cam,chain",
                    help="comma-separated: four-bar, six-bar, cam, chain")
    ap.add_argument("--base", type=Path, default=None,
                    help="another checkout (its extension built) to compare with, back to back")
    ap.add_argument("--rounds", type=int, default=2, help="rounds of the comparison (--base)")
    args = ap.parse_args()
    from playwright.sync_api import sync_playwright

    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    wanted = set(args.models.split(","))
    print(f"{time.strftime('%Y-%m-%d %H:%M', time.gmtime())} UTC, commit {head_of(ROOT)}, "
          f"load average {os.getloadavg()[0]:.1f} at the start, {args.drags} drags, "
          f"{os.cpu_count()} cores")
    with tempfile.TemporaryDirectory() as tmp, sync_playwright() as p:
        folder = Path(tmp)
        cases = []
        for key, (label, name, handle) in zip(("four-bar", "six-bar", "cam"), MODELS, strict=True):
            if key in wanted:
                shutil.copy(ROOT / "examples" / name, folder / name)
                cases.append((label, folder / name, handle))
        if "chain" in wanted:
            (folder / "chain.toml").write_text(chain_toml(100))
            cases.append(("chain of 100 pins", folder / "chain.toml", "joint:j50"))
        browser = p.chromium.launch(executable_path=chromium, args=["--no-sandbox"])
        print(f"Chromium {browser.version}, headless; Python {sys.version.split()[0]}")
        print("| model | times | page median (ms) | page p95 (ms) | wait median | server median "
              "| page work median | Chromium CPU per edit | in-process median | p95 "
              "| in-process CPU median | p95 |")
        print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
        for label, path, handle in cases:
            shutil.copy(path, path.with_suffix(".orig"))
            run = BrowserRun(browser, path, handle, args.drags)
            shutil.copy(path.with_suffix(".orig"), path)
            server, cpu = server_times(path, handle, args.drags)
            rows = len(Document(path).solution.t)
            print(f"| {label} | {rows} | {med(run.total):.1f} | {pct(run.total, 0.95):.1f} "
                  f"| {med(run.wait):.1f} | {med(run.server):.1f} | {med(run.page):.1f} "
                  f"| {run.chromium_cpu:.1f} | {med(server):.1f} | {pct(server, 0.95):.1f} "
                  f"| {med(cpu):.1f} | {pct(cpu, 0.95):.1f} |", flush=True)
        if args.base is not None:
            compare(browser, cases, args.base.resolve(), args.drags, args.rounds)
        browser.close()
    print(f"load average {os.getloadavg()[0]:.1f} at the end")


if __name__ == "__main__":
    main()
