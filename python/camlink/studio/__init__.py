"""``camlink studio MODEL``: edit a mechanism in the browser, the whole
cycle re-solved in the core on each edit; or a cam design file, its
motion program analysed again on each edit (`camlink.studio.cam`).

An aiohttp server bound to 127.0.0.1 serves the packaged page
(``web/studio.html`` with the body of ``web/studio_model.html`` or, for a
cam design file, ``web/studio_cam.html``; ``web/camlink.js``, the
vendored uPlot) and a websocket for edits and runs. Every request must
carry the session's random token (``?token=…``) and, when it has an
``Origin`` or a ``Host`` header, name this server: anything else gets
403. The page loads nothing from a network (its Content-Security-Policy
allows only this server).

Edits are solved one at a time in a worker thread, off the event loop,
which also makes and encodes the reply (binary, `pack`, for the page;
the event loop only receives and sends); an edit that arrives while
another is solving replaces a pending edit of the same handle, parameter
or segment key, so a fast drag solves only its latest position. Each
reply carries the whole re-solved cycle (`camlink.viz.front.frame_data`),
or the analysed design. The websocket is not compressed. Analyses and
studies started from the page run in a thread of their own
(`camlink.studio.runs`), reporting their progress to the page that
started them.
"""

from __future__ import annotations

import asyncio
import hmac
import json
import math
import secrets
import struct
import time
import webbrowser
from collections import deque
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

import numpy as np
from aiohttp import WSMsgType, web

from camlink._core import ANALYSES, ModelError
from camlink.studio.cam import CamDocument, cam_payload, open_document
from camlink.studio.document import Document, Editable, Floats, Solution, raw
from camlink.studio.runs import Run, Runs, studies_of
from camlink.viz.front import asset, b64, frame_data

__all__ = ["StudioServer", "make_app", "notebook", "pack", "payload", "run", "text"]

TOKEN_KEY = web.AppKey("token", str)
DOC_KEY = web.AppKey("doc", Editable)
EXECUTOR_KEY = web.AppKey("executor", ThreadPoolExecutor)


class _Sockets:
    """The open websockets, closed when the server stops."""

    def __init__(self) -> None:
        self.open: set[web.WebSocketResponse] = set()


SOCKETS_KEY = web.AppKey("sockets", _Sockets)
RUNS_KEY = web.AppKey("runs", Runs)

_TYPES = {".js": "text/javascript", ".css": "text/css", ".html": "text/html"}
_ASSETS = ("camlink.js", "studio.js", "cam.js", "uPlot.iife.min.js", "uPlot.min.css", "studio.css")
_POLICY = ("default-src 'none'; script-src 'self'; style-src 'self' 'unsafe-inline'; "
           "connect-src 'self'; img-src 'self' data:; base-uri 'none'; form-action 'none'; ")
#: Who may show the page in a frame: nobody, or, for a studio started from
#: a notebook (`embed`), pages of this machine (a notebook served on
#: localhost, VS Code's notebook view).
_FRAMES = "frame-ancestors 'none'"
_EMBED_FRAMES = ("frame-ancestors 'self' http://127.0.0.1:* http://localhost:* "
                 "https://127.0.0.1:* https://localhost:* vscode-webview:")
EMBED_KEY = web.AppKey("embed", bool)


#: The line under the stage when an edit kept the assembly branch.
BRANCH_NOTE = ("assembly branch kept through the edit; the file's placement assembles on the "
               "other branch, which `camlink run` of the saved file would follow: move the "
               "bodies' position and angle towards this one")


def info_lines(sol: Solution) -> list[str]:
    """Lines about the mechanism under the stage: its four-bar class and
    transmission angle when it is a four-bar (`camlink.viz.fourbar`)."""
    from camlink.viz.fourbar import describe

    return describe(sol.model, sol.t, sol.names, sol.values, sol.scene)


def payload(doc: Document, shown: list[str] | None = None,
            encode: Callable[..., Any] = b64) -> dict[str, Any]:
    """The page's data for the document's current cycle: every channel's
    name, the poses, and the values of the traces, the default plots and
    the channels `shown` (all when None); each array as `encode` gives it
    (base64 text by default; with `raw`, for a binary reply, the scene's
    shapes too)."""
    sol = doc.solution
    points = [str(p) for p in (sol.model.analysis.get("points") or [])]
    channels = None
    if shown is not None:
        have = set(sol.names)
        traced = [f"{p}.{c}" for p in points for c in ("x", "y")]
        channels = [c for c in [*traced, *shown] if c in have]
    data = frame_data(sol.model, sol.scene, sol.t, sol.names, sol.values, sol.ok, points=points,
                      channels=channels, all_names=True, units=sol.units,
                      plots=doc.default_plots(points), encode=encode,
                      flat=None if encode is b64 else lambda a: encode(np.ravel(a), "f64"))
    data["handles"] = [{"id": h.id, "label": h.label, "body": h.body, "s": list(h.local)}
                       for h in sol.handles]
    data["parameters"] = doc.parameters()
    data["segments"] = doc.motion_segments()
    data["info"] = info_lines(sol)
    if sol.kept_branch:
        data["info"].append(BRANCH_NOTE)
    data["file"] = doc.path.name
    data["analysis"] = sol.model.analysis_type
    data["error"] = sol.error
    data["dirty"] = doc.dirty
    data["undo"] = doc.can_undo
    data["redo"] = doc.can_redo
    return data


def pack(msg: dict[str, Any]) -> bytes:
    """`msg` as one binary websocket message, for a page that asked for
    them (``"binary": true`` in its ``hello``): a little-endian uint32 n,
    n bytes of UTF-8 JSON (padded with spaces so that what follows starts
    at a multiple of 8 bytes), then the float64 arrays of `msg` back to
    back. Each array `msg` carries as `Floats` (`raw`) is in the JSON as
    ``{"buf": [k, m]}``: m values from the k-th float64 of the block."""
    blobs: list[bytes] = []
    at = 0

    def ref(v: object) -> dict[str, list[int]]:
        nonlocal at
        if not isinstance(v, Floats):
            raise TypeError(f"{type(v).__name__} in a studio reply")
        n = len(v.data) // 8
        blobs.append(v.data)
        at += n
        return {"buf": [at - n, n]}

    head = json.dumps(msg, separators=(",", ":"), allow_nan=False, default=ref).encode()
    head += b" " * (-(4 + len(head)) % 8)
    return struct.pack("<I", len(head)) + head + b"".join(blobs)


def _allowed(request: web.Request) -> bool:
    token = request.app[TOKEN_KEY]
    given = request.query.get("token", "")
    if not hmac.compare_digest(given.encode(), token.encode()):
        return False
    host = request.headers.get("Host")
    port = request.url.port
    names = {f"127.0.0.1:{port}", f"localhost:{port}"}
    if host is not None and host not in names:
        return False
    origin = request.headers.get("Origin")
    return origin is None or origin in {f"http://{n}" for n in names}


@web.middleware
async def _guard(request: web.Request, handler: Any) -> web.StreamResponse:
    if not _allowed(request):
        return web.Response(status=403, text="forbidden: wrong token or origin\n")
    response = await handler(request)
    frames = _EMBED_FRAMES if request.app[EMBED_KEY] else _FRAMES
    response.headers["Content-Security-Policy"] = _POLICY + frames
    response.headers["X-Content-Type-Options"] = "nosniff"
    response.headers["Cache-Control"] = "no-store"
    response.headers["Referrer-Policy"] = "no-referrer"
    return response


async def _index(request: web.Request) -> web.Response:
    cam = isinstance(request.app[DOC_KEY], CamDocument)
    body = asset("studio_cam.html" if cam else "studio_model.html")
    page = asset("studio.html").replace("__BODY__", body)
    page = page.replace("__SCRIPT__", "cam.js" if cam else "studio.js")
    text = page.replace("__TOKEN__", request.app[TOKEN_KEY])
    return web.Response(text=text, content_type="text/html")


async def _asset(request: web.Request) -> web.Response:
    name = request.match_info["name"]
    if name not in _ASSETS:
        raise web.HTTPNotFound()
    return web.Response(text=asset(name), content_type=_TYPES[Path(name).suffix])


def _edit(doc: Editable, op: object, msg: dict[str, Any]) -> bool:
    """Applies the edit request `msg` to `doc`; False when `op` is no edit
    of this kind of document."""
    if isinstance(doc, CamDocument):
        if op != "segment":
            return False
        doc.set_segment(int(msg["index"]), str(msg["key"]), msg["value"], msg.get("gesture"))
        return True
    assert isinstance(doc, Document)
    if op == "move":
        doc.move(str(msg["handle"]), int(msg["row"]), float(msg["x"]), float(msg["y"]),
                 msg.get("gesture"))
    elif op == "param":
        doc.set_parameter(str(msg["name"]), float(msg["value"]), msg.get("gesture"))
    elif op == "segments":
        doc.set_segments([(str(c["curve"]), int(c["index"]), str(c["key"]), c["value"])
                          for c in msg["changes"]])
    else:
        return False
    return True


def text(msg: dict[str, Any]) -> str:
    """`msg` as one text websocket message (JSON; arrays as base64)."""
    return json.dumps(msg, separators=(",", ":"), allow_nan=False)


def _answer(doc: Editable, msg: dict[str, Any], came: float, binary: bool) -> bytes | str:
    """One message from the page, which arrived at `came` (`time.perf_counter`,
    s), in the worker thread: the reply as the websocket sends it, binary
    (`pack`) or text. A reply of frames carries the server's share of the
    edit (``server_ms``: from its arrival to the reply made, before it is
    encoded), for the page's timing of edits."""
    reply = _handle(doc, msg, raw if binary else b64)
    if reply.get("type") == "frames":
        reply["server_ms"] = round(1e3 * (time.perf_counter() - came), 3)
    return pack(reply) if binary else text(reply)


def _handle(doc: Editable, msg: dict[str, Any],
            encode: Callable[..., Any] = b64) -> dict[str, Any]:
    """One message from the page: the reply, its arrays as `encode` gives them."""
    op = msg.get("op")
    try:
        if op in ("undo", "redo", "save", "end"):
            reply = _common(doc, str(op), msg)
            if reply is not None:
                return reply
        elif op != "hello" and not _edit(doc, op, msg):
            return {"type": "error", "seq": msg.get("seq"), "message": f"unknown request {op!r}"}
    except (ModelError, ValueError, KeyError, TypeError, OSError) as e:
        return _error(msg, e)
    if isinstance(doc, CamDocument):
        return {"type": "frames", "seq": msg.get("seq"), "data": cam_payload(doc, encode)}
    assert isinstance(doc, Document)
    plots = msg.get("plots")
    shown = [str(p) for p in plots] if isinstance(plots, list) else []
    data = payload(doc, shown, encode)
    if op == "hello":
        data["analyses"] = list(ANALYSES)
        data["studies"] = studies_of(doc.path)
    return {"type": "frames", "seq": msg.get("seq"), "data": data}


def _common(doc: Editable, op: str, msg: dict[str, Any]) -> dict[str, Any] | None:
    """The requests every document answers (hello, end, undo, redo, save):
    the reply for those that have their own, else None (send the frames)."""
    if op == "end":
        doc.end_gesture()
        return {"type": "ack", "seq": msg.get("seq")}
    if op == "undo":
        doc.undo()
    elif op == "redo":
        doc.redo()
    elif op == "save":
        path = doc.save()
        return {"type": "saved", "seq": msg.get("seq"), "file": path.name, "dirty": doc.dirty}
    return None


def _error(msg: dict[str, Any], e: Exception) -> dict[str, Any]:
    text = e.args[0] if e.args and isinstance(e.args[0], str) else str(e)
    return {"type": "error", "seq": msg.get("seq"), "message": text}


def _same_target(a: dict[str, Any], b: dict[str, Any]) -> bool:
    if a.get("op") != b.get("op") or a.get("op") not in ("move", "param", "segment"):
        return False
    return all(a.get(k) == b.get(k) for k in ("handle", "name", "curve", "index", "key"))


async def _socket(request: web.Request) -> web.WebSocketResponse:
    # Uncompressed: on the loopback, deflating a reply (1.8 ms for the
    # four-bar's 53 kB) and inflating it in the browser cost more than
    # they save.
    ws = web.WebSocketResponse(max_msg_size=1 << 20, compress=False)
    await ws.prepare(request)
    doc = request.app[DOC_KEY]
    executor = request.app[EXECUTOR_KEY]
    loop = asyncio.get_running_loop()
    # Requests waiting to be solved, each with when it came (perf_counter, s).
    queue: deque[tuple[dict[str, Any], float]] = deque()
    binary = False  # whether the page reads binary replies (`pack`)
    wake = asyncio.Event()

    async def worker() -> None:
        while True:
            await wake.wait()
            wake.clear()
            while queue:
                msg, came = queue.popleft()
                # Solved and encoded in the worker thread: the loop only sends.
                reply = await loop.run_in_executor(executor, _answer, doc, msg, came, binary)
                if ws.closed:
                    return
                if isinstance(reply, bytes):
                    await ws.send_bytes(reply)
                else:
                    await ws.send_str(reply)

    def report(run: Run) -> None:
        # In the run's thread: its status to this page, from the loop
        # (unless the page or the server has gone).
        msg = run.status(shown)
        if ws.closed or loop.is_closed():
            return
        coro = _send(ws, msg)
        try:
            asyncio.run_coroutine_threadsafe(coro, loop)
        except RuntimeError:
            coro.close()

    # The runs this page started: stopped when it goes.
    mine: set[int] = set()

    shown: list[str] = []
    runs = request.app[RUNS_KEY]
    task = asyncio.create_task(worker())
    request.app[SOCKETS_KEY].open.add(ws)
    try:
        async for m in ws:
            if m.type != WSMsgType.TEXT:
                continue
            try:
                msg = json.loads(m.data)
            except ValueError:
                continue
            if not isinstance(msg, dict):
                continue
            if msg.get("op") == "hello" and msg.get("binary") is True:
                binary = True
            if msg.get("op") == "param" and not _finite(msg.get("value")):
                continue
            if msg.get("op") in ("run", "stop", "runchannel"):
                # Runs go on beside the edits: answered here, off the queue.
                if isinstance(msg.get("plots"), list):
                    shown[:] = [str(p) for p in msg["plots"]]
                reply = _run_request(doc, runs, msg, report, shown)
                if reply.get("type") == "run":
                    mine.add(int(reply["id"]))
                await _send(ws, reply)
                continue
            # A newer edit of the same point or parameter replaces the
            # one still waiting (and its time of arrival): only the latest
            # is solved.
            item = (msg, time.perf_counter())
            if queue and _same_target(queue[-1][0], msg):
                queue[-1] = item
            else:
                queue.append(item)
            wake.set()
    finally:
        task.cancel()
        request.app[SOCKETS_KEY].open.discard(ws)
        if runs.current is not None and runs.current.id in mine:
            runs.stop()
    return ws


def _finite(v: object) -> bool:
    """Whether `v` is a finite number (or a number's text)."""
    try:
        return math.isfinite(float(v))  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return False


async def _send(ws: web.WebSocketResponse, msg: dict[str, Any]) -> None:
    if not ws.closed:
        await ws.send_str(text(msg))


def _run_request(doc: Editable, runs: Runs, msg: dict[str, Any], report: Any,
                 shown: list[str]) -> dict[str, Any]:
    """A ``run``, ``stop`` or ``runchannel`` request: the reply (the run
    itself reports through `report` from its thread; a reply, as a report,
    carries the channels `shown` of a finished run)."""
    op = msg.get("op")
    seq = msg.get("seq")
    try:
        if not isinstance(doc, Document):
            raise ModelError("a cam design file has no analyses to run; run `camlink cam` on it")
        if op == "run":
            analysis, study = str(msg.get("analysis")), None
            if analysis.startswith("study:"):
                name = analysis[len("study:"):]
                if name not in studies_of(doc.path):
                    raise ModelError(f"no study file {name!r} naming {doc.path.name} beside it")
                analysis, study = "study", doc.path.parent / name
            run = runs.start(doc.solution.model, analysis, report, study, doc.path.parent)
            return {**run.status(shown), "seq": seq}
        if op == "stop":
            runs.stop()
            return {"type": "ack", "seq": seq}
        if runs.current is None:
            raise KeyError("no run yet")
        return {**runs.current.channel(str(msg.get("name"))), "seq": seq}
    except (ModelError, ValueError, KeyError) as e:
        return _error(msg, e)


def make_app(doc: Editable, token: str, embed: bool = False) -> web.Application:
    """The studio's application for `doc`, answering only with `token`;
    with `embed`, its page may be shown in a frame of a page of this
    machine (a notebook's)."""
    app = web.Application(middlewares=[_guard])
    app[TOKEN_KEY] = token
    app[EMBED_KEY] = embed
    app[DOC_KEY] = doc
    app[EXECUTOR_KEY] = ThreadPoolExecutor(max_workers=1, thread_name_prefix="camlink-studio")
    app[SOCKETS_KEY] = _Sockets()
    app[RUNS_KEY] = Runs()
    app.router.add_get("/", _index)
    app.router.add_get("/ws", _socket)
    app.router.add_get("/static/{name}", _asset)

    async def close(app: web.Application) -> None:
        app[EXECUTOR_KEY].shutdown(wait=False, cancel_futures=True)
        app[RUNS_KEY].close()

    async def shutdown(app: web.Application) -> None:
        for ws in list(app[SOCKETS_KEY].open):
            await ws.close(code=1001, message=b"server stopped")

    app.on_shutdown.append(shutdown)
    app.on_cleanup.append(close)
    return app


class StudioServer:
    """A running studio on 127.0.0.1 (`url` carries the token); with
    `embed`, its page may be framed by a page of this machine (`make_app`)."""

    def __init__(self, path: str | Path, port: int = 0, embed: bool = False) -> None:
        self.doc = open_document(path)
        self.token = secrets.token_urlsafe(24)
        self.port = port
        self.embed = embed
        self.url = ""
        self._runner: web.AppRunner | None = None

    async def start(self) -> str:
        self._runner = web.AppRunner(make_app(self.doc, self.token, self.embed), access_log=None)
        await self._runner.setup()
        site = web.TCPSite(self._runner, "127.0.0.1", self.port)
        await site.start()
        sockets = getattr(site._server, "sockets", None) or []
        self.port = int(sockets[0].getsockname()[1])
        self.url = f"http://127.0.0.1:{self.port}/?token={self.token}"
        return self.url

    async def stop(self) -> None:
        if self._runner is not None:
            await self._runner.cleanup()


def run(path: str | Path, port: int = 0, browser: bool = True) -> None:
    """Serves the studio for the model file `path` until interrupted."""
    server = StudioServer(path, port)

    async def main() -> None:
        url = await server.start()
        print(f"camlink studio: {url}", flush=True)
        print("press Ctrl+C to stop", flush=True)
        if browser:
            webbrowser.open(url)
        try:
            await asyncio.Event().wait()
        finally:
            await server.stop()

    try:
        asyncio.run(main())
    except KeyboardInterrupt:
        pass


def notebook(path: str | Path, *, port: int = 0, height: int = 760) -> Any:
    """The studio for `path` in a Jupyter notebook: served from a thread of
    this process and shown as an iframe (`camlink.studio.embed.notebook`,
    which returns a `NotebookStudio`; call ``.stop()`` when done)."""
    from camlink.studio.embed import notebook as serve

    return serve(path, port=port, height=height)
