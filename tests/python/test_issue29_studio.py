"""Issue 29, the studio: its document (edits, undo, save), its server's
guard (token, origin, host) and the four-bar checks it shows. The
browser tests are in test_issue29_studio_browser.py."""

from __future__ import annotations

import asyncio
import base64
import json
import math
import shutil
import tomllib
from pathlib import Path

import numpy as np
import pytest
from aiohttp import WSMsgType

import camlink
from camlink import _core
from camlink.cli import main
from camlink.studio import BRANCH_NOTE, payload
from camlink.studio.document import Document
from camlink.viz.fourbar import find, transmission
from camlink.viz.scene import Scene
from conftest import STUCK_FOUR_BAR, TOKEN, four_bar_toml, refuses_strangers, studio_client

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


def _copy(tmp_path: Path, name: str) -> Path:
    out = tmp_path / name
    shutil.copy(EXAMPLES / name, out)
    return out


def _pose(doc: Document, body: str, row: int) -> tuple[float, float, float]:
    return doc.solution.pose(body, row)


def test_issue29_studio_drag_writes_body_frame_coordinates(tmp_path: Path) -> None:
    path = _copy(tmp_path, "four_bar.toml")
    doc = Document(path)
    k = 37
    crank, coupler = _pose(doc, "crank", k), _pose(doc, "coupler", k)
    target = (0.05, 0.11)
    doc.move("joint:A", k, *target)
    data = camlink.load(path)  # the file is unchanged until saved
    assert data.bodies[0]["points"]["A"] == pytest.approx([0.12, 0.0])
    doc.save()
    model = camlink.load(path)
    pts = {b["name"]: b["points"] for b in model.bodies}
    for body, q in (("crank", crank), ("coupler", coupler)):
        c, s = math.cos(q[2]), math.sin(q[2])
        dx, dy = target[0] - q[0], target[1] - q[1]
        assert pts[body]["A"] == pytest.approx([c * dx + s * dy, -s * dx + c * dy], abs=1e-9)
    # The crank is driven: at row k its new pin A is where it was dropped.
    res = model.run(points=["crank.A"])
    assert [res["crank.A.x"][k], res["crank.A.y"][k]] == pytest.approx(target, abs=1e-9)


def test_issue29_studio_save_keeps_comments_backup_and_reruns(tmp_path: Path) -> None:
    path = _copy(tmp_path, "four_bar.toml")
    original = path.read_text()
    doc = Document(path)
    doc.set_parameter("b", 0.4)
    doc.move("point:coupler.P", 100, 0.2, 0.3)
    text = doc.save().read_text()
    assert (tmp_path / "four_bar.toml.bak").read_text() == original
    # Every comment line and the other lines kept as they were.
    for line in original.splitlines():
        if line.startswith("#") or line.startswith("[") or line.startswith("c = 0.3"):
            assert line in text.splitlines(), line
    assert "b = 0.4             # coupler A–B (m)" in text
    assert sorted(p.name for p in tmp_path.iterdir()) == ["four_bar.toml", "four_bar.toml.bak"]
    # The saved file reruns as the studio solved it.
    res = camlink.load(path).run(points=["coupler.P", "rocker.B"])
    sol = doc.solution
    for name in ("coupler.P.x", "rocker.phi", "rocker.B.y"):
        assert np.array_equal(res[name], sol.values[:, sol.names.index(name)]), name


def test_issue29_studio_undo_redo_a_drag_is_one_step(tmp_path: Path) -> None:
    path = _copy(tmp_path, "four_bar.toml")
    doc = Document(path)
    first = doc.text()
    for k in range(5):
        doc.move("joint:B", 0, 0.3 + 0.01 * k, 0.25, gesture="g")
    doc.end_gesture()
    moved = doc.text()
    doc.set_parameter("p", 0.12, gesture="s")
    doc.undo()
    assert doc.text() == moved
    doc.undo()
    assert doc.text() == first and doc.undo() is None
    doc.redo()
    assert doc.text() == moved


def test_issue29_studio_unassemblable_rows_missing(tmp_path: Path) -> None:
    # A crank of 1 on a non-Grashof linkage cannot pass ±119.6°: those rows
    # are missing, and the rows where it assembles again are solved.
    path = tmp_path / "stuck.toml"
    path.write_text(four_bar_toml(**STUCK_FOUR_BAR))
    doc = Document(path)
    sol = doc.solution
    assert sol.ok[0] and not sol.ok.all()
    crank = (60 + 360 * sol.t) % 360  # the crank angle (°)
    limit = math.degrees(math.acos(-(12.96 - 10) / 6))
    reach = (crank <= limit - 0.5) | (crank >= 360 - limit + 0.5)
    beyond = (crank >= limit + 0.5) & (crank <= 360 - limit - 0.5)
    assert not sol.ok[beyond].any()
    assert sol.ok[reach].mean() > 0.9
    assert np.isnan(sol.values[~sol.ok]).all() and np.isfinite(sol.values[sol.ok]).all()
    # The page data has the mask and finite JSON (NaN only inside base64).
    data = payload(doc)
    assert data["ok"] == [int(v) for v in sol.ok]
    json.dumps(data, allow_nan=False)


def test_issue29_studio_json_saved_plainly(tmp_path: Path) -> None:
    src = tmp_path / "m.json"
    text = four_bar_toml()
    src.write_text(json.dumps(tomllib.loads(text), indent=1))
    doc = Document(src)
    doc.set_parameter("L", 2.7)
    doc.save()
    assert json.loads(src.read_text())["parameters"]["L"] == 2.7
    assert (tmp_path / "m.json.bak").exists()


def test_issue29_studio_global_points_drag(tmp_path: Path) -> None:
    # A body given by global points: the dragged point's global position
    # in the drawing (the placement, φ₀ = 0) is written, such that the
    # body point is at the dropped place at row k.
    path = _copy(tmp_path, "whitworth_global.toml")
    doc = Document(path)
    k = 20
    rod = _pose(doc, "rod", k)
    x0, y0, phi0 = doc.solution.scene.placement["rod"]
    assert phi0 == 0.0
    target = (-0.05, -0.09)
    doc.move("joint:B", k, *target)
    doc.save()
    c, s = math.cos(rod[2]), math.sin(rod[2])
    dx, dy = target[0] - rod[0], target[1] - rod[1]
    saved = tomllib.loads(path.read_text())
    b = next(x for x in saved["bodies"] if x["name"] == "rod")["global_points"]["B"]
    assert b == pytest.approx([x0 + c * dx + s * dy, y0 - s * dx + c * dy], abs=1e-9)
    lever = next(x for x in saved["bodies"] if x["name"] == "lever")["global_points"]
    assert lever["O4"] == [0, 0] and "B" in lever
    assert len(camlink.load(path).run()) > 0


def test_issue29_fourbar_grashof_and_transmission() -> None:
    # d + a < b + c with the crank shortest: a crank-rocker.
    assert _core.fourbar_class(0.4, 0.12, 0.38, 0.3) == "crank-rocker"
    assert _core.fourbar_class(3.0, 1.0, 2.6, 1.0) == "triple-rocker"
    assert _core.fourbar_class(0.12, 0.4, 0.38, 0.3) == "double-crank"
    model = camlink.load(EXAMPLES / "four_bar.toml")
    res = model.run(points=["coupler.A", "coupler.B"])
    loop = find(model, Scene.of(model))
    assert loop is not None and (loop.crank, loop.coupler, loop.rocker) == ("crank", "coupler", "rocker")
    names = ["t", *res.channels]
    values = np.column_stack([res[c] for c in names])
    mu = transmission(loop, names, values)
    # μ: the angle at B between B→A and B→O4, from the solved positions.
    ax, ay, bx, by = (res[c] for c in ("coupler.A.x", "coupler.A.y", "coupler.B.x", "coupler.B.y"))
    u = np.column_stack([ax - bx, ay - by])
    v = np.column_stack([0.4 - bx, 0.0 - by])
    cos = np.sum(u * v, axis=1) / np.hypot(*u.T) / np.hypot(*v.T)
    assert mu == pytest.approx(np.arccos(cos), abs=1e-9)


def test_issue29_fourbar_not_found_in_a_six_bar() -> None:
    model = camlink.load(EXAMPLES / "whitworth_global.toml")
    assert find(model, Scene.of(model)) is None


async def _guard_checks(path: Path) -> None:
    token = TOKEN
    async with studio_client(Document(path)) as (client, port):
        ok = await client.get(f"/?token={token}")
        assert ok.status == 200
        assert "default-src 'none'" in ok.headers["Content-Security-Policy"]
        await refuses_strangers(client, token, "/static/camlink.js")
        ws = await client.ws_connect(f"/ws?token={token}", headers={"Origin": f"http://127.0.0.1:{port}"})
        await ws.send_str(json.dumps({"op": "hello", "seq": 1}))
        reply = json.loads((await ws.receive()).data)
        assert reply["type"] == "frames" and reply["data"]["title"] == "four_bar"
        # A slider value that is no number is dropped; the socket goes on.
        await ws.send_str(json.dumps({"op": "param", "name": "a", "value": "abc", "seq": 9}))
        await ws.send_str(json.dumps({"op": "move", "handle": "nope", "row": 0, "x": 0, "y": 0, "seq": 2}))
        reply = json.loads((await ws.receive()).data)
        assert reply == {"type": "error", "seq": 2, "message": "no handle 'nope'"}
        await ws.close()


def test_issue29_studio_refuses_without_token_or_from_another_origin(tmp_path: Path) -> None:
    asyncio.run(_guard_checks(_copy(tmp_path, "four_bar.toml")))


def test_issue29_studio_cli_usage_errors(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # In-process: `camlink.cli.main` as the command runs it.
    with pytest.raises(SystemExit) as e:
        main(["studio", str(EXAMPLES / "four_bar.toml"), "--port", "70000", "--no-browser"])
    assert e.value.code == 2 and "not a port number" in capsys.readouterr().err
    broken = tmp_path / "broken.toml"
    broken.write_text('[model]\nname = "x"\n[[bodies]]\nname = 3\n')
    assert main(["studio", str(broken), "--no-browser"]) == 2
    err = capsys.readouterr().err
    assert "broken.toml" in err and "Traceback" not in err
    assert main(["studio", str(tmp_path / "nope.toml"), "--no-browser"]) == 2
    assert "nope.toml" in capsys.readouterr().err
    other = tmp_path / "model.yaml"
    other.write_text("x: 1\n")
    with pytest.raises(camlink.ModelError, match=r"\.toml and \.json"):
        Document(other)


def test_issue29_studio_model_not_fully_driven_shows_placement(tmp_path: Path) -> None:
    doc = Document(_copy(tmp_path, "dyn_pendulum.toml"))
    data = payload(doc)
    assert data["error"] is not None and "driven" in data["error"]
    assert data["ok"] == [1]
    json.dumps(data, allow_nan=False)


def _freudenstein_rocker(d: float, a: float, b: float, c: float, th2: np.ndarray,
                         sign: float) -> np.ndarray:
    """θ₄ of the four-bar (ground d, crank a, coupler b, rocker c) at crank
    angles θ₂, open (`sign` −1) or crossed (+1) branch."""
    k1, k2 = d / a, d / c
    k3 = (a * a - b * b + c * c + d * d) / (2 * a * c)
    cs, sn = np.cos(th2), np.sin(th2)
    aa, bb, cc = cs - k1 - k2 * cs + k3, -2 * sn, k1 - (k2 + 1) * cs + k3
    return 2 * np.arctan2(-bb + sign * np.sqrt(bb * bb - 4 * aa * cc), 2 * aa)


def _wrap(a: np.ndarray) -> np.ndarray:
    return (a + np.pi) % (2 * np.pi) - np.pi


def test_issue29_studio_edit_keeps_the_branch(tmp_path: Path) -> None:
    # Placed with the rocker along the ground line and the coupler upright,
    # the file's placement assembles on the other branch for a rocker of
    # 0.27 to 0.285 m; the studio's slider keeps the branch it started on.
    path = tmp_path / "four_bar.toml"
    text = (EXAMPLES / "four_bar.toml").read_text()
    path.write_text(text.replace('angle = "deg(80)"', 'angle = "deg(0)"')
                    .replace('angle = "deg(30)"', 'angle = "deg(90)"'))
    doc = Document(path)

    def branch(names: list[str], values: np.ndarray, c: float) -> float:
        th2 = values[:, names.index("crank.phi")]
        th4 = values[:, names.index("rocker.phi")]
        for sign in (-1.0, 1.0):
            if np.abs(_wrap(th4 - _freudenstein_rocker(0.4, 0.12, 0.38, c, th2, sign))).max() < 1e-9:
                return sign
        raise AssertionError("on neither branch")

    kept = branch(doc.solution.names, doc.solution.values, 0.3)
    flipped = 0
    for c in (0.2925, 0.285, 0.2775, 0.27):
        doc.set_parameter("c", c, gesture="slide")
        assert doc.solution.ok.all()
        assert branch(doc.solution.names, doc.solution.values, c) == kept
        res = doc.model().run()
        cli = ["t", *res.channels]
        other = branch(cli, np.column_stack([res[n] for n in cli]), c) != kept
        flipped += other
        # The page says so when the file's placement goes the other way.
        assert doc.solution.kept_branch == other
        assert (BRANCH_NOTE in payload(doc, [])["info"]) == other
    assert flipped >= 2


async def _run_checks(path: Path) -> None:
    token = TOKEN
    doc = Document(path)
    async with studio_client(doc) as (client, port):
        await refuses_strangers(client, token, "/static/studio.js")
        ws = await client.ws_connect(f"/ws?token={token}", headers={"Origin": f"http://127.0.0.1:{port}"})
        await ws.send_str(json.dumps({"op": "runchannel", "name": "t", "seq": 1}))
        assert json.loads((await ws.receive()).data) == {"type": "error", "seq": 1, "message": "no run yet"}
        await ws.send_str(json.dumps({"op": "run", "analysis": "statics", "seq": 2}))
        reply = json.loads((await ws.receive()).data)
        assert reply["type"] == "error" and "unknown analysis 'statics'" in reply["message"]
        await ws.send_str(json.dumps({"op": "run", "analysis": "inverse_dynamics", "seq": 3,
                                      "plots": ["O2.fx"]}))
        last: dict[str, object] = {}
        while last.get("state") in (None, "running"):
            msg = json.loads((await ws.receive(timeout=30)).data)
            assert msg["type"] == "run"
            if not last or (msg["id"], msg["n"]) > (last["id"], last["n"]):
                last = msg
        assert last["state"] == "done" and last["done"] == last["total"] == 401
        expected = doc.solution.model.inverse_dynamics()
        channels = last["channels"]
        assert isinstance(channels, dict) and "O2.fx" in channels
        got = np.frombuffer(base64.b64decode(channels["O2.fx"]["f64"]), "<f8")
        assert np.array_equal(got, expected["O2.fx"])
        await ws.send_str(json.dumps({"op": "runchannel", "name": "motor.effort", "seq": 4}))
        # Progress reports of the run sent before it finished may still be
        # on their way (they are posted from the run's thread).
        reply = json.loads((await ws.receive(timeout=30)).data)
        while reply["type"] == "run":
            assert reply["id"] == last["id"] and reply["n"] <= last["n"], reply
            reply = json.loads((await ws.receive(timeout=30)).data)
        got = np.frombuffer(base64.b64decode(reply["values"]["f64"]), "<f8")
        assert reply["name"] == "motor.effort" and np.array_equal(got, expected["motor.effort"])
        await ws.close()


def test_issue29_studio_runs_over_the_socket(tmp_path: Path) -> None:
    asyncio.run(_run_checks(_copy(tmp_path, "four_bar.toml")))


def test_issue29_studio_stopped_run_keeps_its_rows(tmp_path: Path) -> None:
    # A long dynamics run stopped from the page keeps the rows computed up
    # to the stop, the time it stopped at in its message: the rows of a
    # run of the same model to that time; nothing is left in the folder.
    from camlink.studio.runs import Run

    path = tmp_path / "long.toml"
    path.write_text((EXAMPLES / "dyn_pendulum.toml").read_text().replace(
        "t_end = 3.0", "t_end = 1000.0"))
    model = camlink.load(path)
    run = Run(model, "dynamics", folder=tmp_path)

    def report(r: Run) -> None:
        if r.done > 0:
            r.stop.set()

    run.execute(report)
    res = run.results
    assert run.state == "stopped" and res is not None and 0 < len(res) < run.total
    assert len(res) <= run.done
    assert res.complete is False and res.mechanism is run.model
    t_stop = float(res["t"][-1])
    assert f"at t = {t_stop:.6g} s: the {len(res)} rows computed are kept" in run.message
    assert sorted(p.name for p in tmp_path.iterdir()) == ["long.toml"]
    whole = model.run(analysis="dynamics", t_end=t_stop)
    assert len(whole) == len(res) and list(whole.channels) == list(res.channels)
    for c in res.channels:
        np.testing.assert_allclose(res[c], whole[c], rtol=0, atol=1e-12, err_msg=c)
    status = run.status(["arm.omega"])
    assert status["state"] == "stopped" and status["names"] == list(res.channels)
    got = np.frombuffer(base64.b64decode(status["channels"]["arm.omega"]["f64"]), "<f8")
    assert np.array_equal(got, res["arm.omega"])


def test_issue29_studio_study_run_stops_between_batches(tmp_path: Path) -> None:
    from camlink.studio.runs import Run, studies_of

    for name in ("four_bar.toml", "study_four_bar.toml"):
        shutil.copy(EXAMPLES / name, tmp_path / name)
    assert studies_of(tmp_path / "four_bar.toml") == ["study_four_bar.toml"]
    model = camlink.load(tmp_path / "four_bar.toml")
    seen: list[tuple[str, int, int]] = []
    run = Run(model, "study", tmp_path / "study_four_bar.toml")

    def report(r: Run) -> None:
        seen.append((r.state, r.done, r.total))
        if r.done >= 3:
            r.stop.set()

    run.execute(report)
    # Three variants a batch: stopped after the first.
    assert run.state == "stopped" and run.done == 3 and run.total == 9
    assert run.message == "study stopped after 3 of 9 variants"
    assert seen[0] == ("running", 0, 9) and seen[-1] == ("stopped", 3, 9)


def test_issue29_studio_notebook_shows_the_page_and_stops(tmp_path: Path) -> None:
    # In a Jupyter kernel: the studio object shows as an iframe of its
    # page (the tokened URL on 127.0.0.1), which answers until stop().
    import nbformat
    from nbclient import NotebookClient

    path = _copy(tmp_path, "four_bar.toml")
    nb = nbformat.v4.new_notebook()
    nb.cells = [
        nbformat.v4.new_code_cell(
            "import urllib.request\n"
            "import camlink.studio\n"
            f"studio = camlink.studio.notebook({str(path)!r}, height=640)\n"
            "studio"),
        nbformat.v4.new_code_cell(
            "print(urllib.request.urlopen(studio.url, timeout=10).status)\n"
            "studio.stop()\n"
            "studio"),
    ]
    NotebookClient(nb, timeout=120, kernel_name="python3").execute()
    shown = nb.cells[0].outputs[0]["data"]["text/html"]
    assert shown.startswith('<iframe src="http://127.0.0.1:') and 'height="640"' in shown
    assert "?token=" in shown
    out = nb.cells[1].outputs
    assert out[0]["text"] == "200\n"
    assert out[1]["data"]["text/html"] == "<p>camlink studio for four_bar.toml: stopped</p>"


def _unpack(data: bytes) -> dict[str, object]:
    """A binary reply (`camlink.studio.pack`) read as the page reads it:
    each ``{"buf": [k, m]}`` the m float64s from the k-th of the block."""
    n = int.from_bytes(data[:4], "little")
    block = np.frombuffer(data[4 + n:], "<f8")

    def walk(v: object) -> object:
        if isinstance(v, dict):
            if isinstance(v.get("buf"), list):
                k, m = v["buf"]
                return block[k:k + m]
            return {key: walk(x) for key, x in v.items()}
        if isinstance(v, list):
            return [walk(x) for x in v]
        return v

    out = walk(json.loads(data[4:4 + n]))
    assert isinstance(out, dict)
    return out


def _decoded(v: object) -> object:
    """A text reply's arrays (base64 float64) as arrays, the rest as it is."""
    if isinstance(v, dict):
        if set(v) == {"f64"}:
            return np.frombuffer(base64.b64decode(v["f64"]), "<f8")
        return {key: _decoded(x) for key, x in v.items()}
    if isinstance(v, list):
        return [_decoded(x) for x in v]
    return v


def _same(a: object, b: object, where: str = "") -> None:
    if isinstance(a, dict):
        assert isinstance(b, dict) and set(a) == set(b), where
        for key in a:
            _same(a[key], b[key], f"{where}.{key}")
    elif isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        # The text reply rounds the scene's shapes to 1e-12 m.
        np.testing.assert_allclose(np.asarray(b, dtype=float), np.asarray(a, dtype=float),
                                   rtol=0, atol=1e-12, err_msg=where)
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), where
        for k, (x, y) in enumerate(zip(a, b, strict=True)):
            _same(x, y, f"{where}[{k}]")
    else:
        assert a == b, where


async def _coalesced_checks(path: Path) -> None:
    doc = Document(path)
    h = next(x for x in doc.solution.handles if x.id == "joint:B")
    x0, y0, phi = doc.solution.pose(h.body, 0)
    x0 += math.cos(phi) * h.local[0] - math.sin(phi) * h.local[1]
    y0 += math.sin(phi) * h.local[0] + math.cos(phi) * h.local[1]
    async with studio_client(doc) as (client, port):
        # Offered permessage-deflate (as Chromium does), the server declines.
        ws = await client.ws_connect(f"/ws?token={TOKEN}", headers={"Origin": f"http://127.0.0.1:{port}"},
                                     compress=15)
        assert ws.compress == 0
        await ws.send_str(json.dumps({"op": "hello", "binary": True, "seq": 1}))
        first = await ws.receive()
        assert first.type == WSMsgType.BINARY
        # Thirty positions of one drag sent at once: the server solves the
        # first and then the latest waiting, never every one.
        for n in range(1, 31):
            await ws.send_str(json.dumps({"op": "move", "handle": "joint:B", "row": 0, "seq": 1 + n,
                                          "x": x0 + 2e-4 * n, "y": y0 - 1e-4 * n, "gesture": "g"}))
        await ws.send_str(json.dumps({"op": "end", "gesture": "g", "seq": 32}))
        seqs: list[int] = []
        last: dict[str, object] | None = None
        while True:
            m = await ws.receive(timeout=60)
            assert m.type == WSMsgType.BINARY
            reply = _unpack(m.data)
            if reply["type"] == "ack":
                assert reply["seq"] == 32
                break
            seq = reply["seq"]
            assert reply["type"] == "frames" and isinstance(seq, int)
            seqs.append(seq)
            last = reply
        assert seqs == sorted(seqs) and seqs[-1] == 31 and len(seqs) < 30
        # The binary reply is the text one of the same cycle, its arrays as
        # they are.
        assert last is not None
        got = {k: v for k, v in last.items() if k != "server_ms"}
        _same(_decoded({"type": "frames", "seq": 31, "data": payload(doc, [])}), got)
        # The state of the last edit: the same file as that one move alone,
        # and one undo step.
        alone = Document(path)
        alone.move("joint:B", 0, x0 + 6e-3, y0 - 3e-3)
        assert doc.text() == alone.text()
        doc.undo()
        assert doc.text() == path.read_text()
        await ws.close()


def test_issue29_studio_coalesced_edits_end_in_the_last(tmp_path: Path) -> None:
    asyncio.run(_coalesced_checks(_copy(tmp_path, "four_bar.toml")))
