"""Issue 29, the studio on a cam design file: a motion program's segments
edited in place, SVAJ, the profile and the limits from the core
(`camlink.cam.design`), saving with comments, and the server's guard on
the cam page. The browser test is in test_issue29_studio_browser.py."""

from __future__ import annotations

import asyncio
import json
import math
import shutil
import tomllib
from pathlib import Path

import numpy as np
import pytest

import camlink
from camlink.cam.design import (
    CamDesignError,
    Report,
    analyse,
    from_data,
    json_safe,
    load,
    sample,
)
from camlink.cli import main
from camlink.studio.cam import SAMPLES, CamDocument, cam_payload, open_document
from camlink.studio.document import Document
from conftest import TOKEN, refuses_strangers, studio_client

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
#: 4-5-6-7 polynomial: peak s′ = C_v h / β with C_v = 35/16.
CV_4567 = 35.0 / 16.0


def _copy(tmp_path: Path, name: str) -> Path:
    out = tmp_path / name
    shutil.copy(EXAMPLES / name, out)
    return out


def test_issue29_studio_cam_lift_edit_saved_and_rerun(tmp_path: Path) -> None:
    path = _copy(tmp_path, "cam_design_valve.toml")
    doc = open_document(path)
    assert isinstance(doc, CamDocument)
    h = 0.0105
    # The rise alone: the program no longer closes; the edit is kept (so the
    # return can be mended next), shown with the loader's message, not saved.
    sol = doc.set_segment(1, "lift", h, gesture="g1")
    assert sol.error is not None and "does not close" in sol.error
    data = cam_payload(doc)
    assert data["error"] == sol.error and "s" not in data and data["dirty"]
    with pytest.raises(CamDesignError, match="not saved"):
        doc.save()
    doc.end_gesture()
    sol = doc.set_segment(3, "lift", -h, gesture="g2")
    assert sol.error is None
    data = cam_payload(doc)
    # Peaks against the closed form of the 4-5-6-7 rise over 100°.
    beta = math.radians(100.0)
    assert data["peaks"]["s"][0] == pytest.approx(h, abs=1e-12)
    assert data["peaks"]["s"][1] == pytest.approx(250.0, abs=1e-9)
    assert abs(data["peaks"]["v"][0]) == pytest.approx(CV_4567 * h / beta, rel=1e-9)
    # The largest convex curvature sampled is 1 / the report's least convex
    # radius (the core's search between samples) to 1e-3, never above it.
    least = {c["name"]: c for c in data["report"]["checks"]}["least radius of curvature (convex)"]
    kappa = data["peaks"]["k"][0]
    assert kappa <= 1 / least["value"] * (1 + 1e-12)
    assert kappa == pytest.approx(1 / least["value"], rel=1e-3)
    assert data["curvature_limit"] == pytest.approx(1 / 0.003, rel=1e-15)
    doc.save()
    text = path.read_text()
    assert "# Pa, the designer's allowable for this pair" in text
    assert "# Automotive-style valve cam" in text
    backup = tmp_path / "cam_design_valve.toml.bak"
    assert backup.read_text() == (EXAMPLES / "cam_design_valve.toml").read_text()
    segs = tomllib.loads(text)["segments"]
    assert [s.get("lift", 0.0) for s in segs] == [0.0, h, 0.0, -h]
    # The saved file read and analysed as `camlink cam` does: the same
    # SVAJ (1e-9) and the same report.
    design = load(path)
    th, motion = sample(design.core(), SAMPLES)
    assert np.array_equal(th, doc.solution.theta)
    assert np.max(np.abs(motion - doc.solution.motion)) <= 1e-9 * np.max(np.abs(motion))
    assert json_safe(analyse(design).to_dict()) == data["report"]
    # Undo twice: the file as opened.
    doc.undo()
    doc.undo()
    assert [s.get("lift", 0.0) for s in doc._data["segments"]] == [0.0, 0.009, 0.0, -0.009]
    assert not doc.can_undo and doc.can_redo


def _report(report: Report | None) -> object:
    """A report as plain data (NaN as None), to compare two reports."""
    assert report is not None
    return json_safe(report.to_dict())


def test_issue29_studio_cam_search_reused_for_data_seen_before(tmp_path: Path) -> None:
    # The indexing design searches for its smallest base circle: a law
    # tried and tried back, undo and redo reuse the analysis of data seen
    # before (the search with it), equal to analysing that data afresh.
    path = _copy(tmp_path, "cam_design_indexing.toml")
    doc = open_document(path)
    assert isinstance(doc, CamDocument)
    first = doc.solution
    assert first.report is not None and first.report.smallest_base_radius is not None

    def fresh() -> object:
        design = from_data(tomllib.loads(doc.text()), path)
        return _report(analyse(design))

    assert _report(first.report) == fresh()
    tried = doc.set_segment(0, "law", "cycloidal", gesture="a")
    assert tried is not first and tried.report is not None
    # A new program: searched again (the cycloidal rise needs another base circle).
    assert tried.report.smallest_base_radius != first.report.smallest_base_radius
    assert _report(tried.report) == fresh()
    doc.end_gesture()
    back = doc.set_segment(0, "law", "modified-sine", gesture="b")
    assert back is first and _report(back.report) == fresh()
    assert doc.undo() is tried and _report(doc.solution.report) == fresh()
    assert doc.undo() is first and _report(doc.solution.report) == fresh()
    assert doc.redo() is tried
    np.testing.assert_array_equal(doc.solution.surface, tried.surface)


def test_issue29_studio_cam_bad_edits_are_shown(tmp_path: Path) -> None:
    path = _copy(tmp_path, "cam_design_valve.toml")
    doc = CamDocument(path)
    # A law with a velocity jump at its ends: C0 boundaries reported.
    doc.set_segment(1, "law", "constant-velocity")
    bounds = cam_payload(doc)["report"]["boundaries"]
    assert [b["continuity"] for b in bounds] == [3, 0, 0, 3]
    assert "infinite acceleration" in bounds[1]["text"]
    doc.undo()
    # A lift the base circle cannot carry: the curvature limit fails.
    doc.set_segment(1, "lift", 0.012)
    doc.set_segment(3, "lift", -0.012)
    report = cam_payload(doc)["report"]
    checks = {c["name"]: c for c in report["checks"]}
    radius = checks["least radius of curvature (convex)"]
    assert radius["ok"] is False and radius["margin"] < 0
    assert checks["undercut ranges"]["ok"] is False and report["undercut_deg"]
    assert report["ok"] is False
    # A span that breaks the turn, an unknown law: the message names the field.
    doc.set_segment(0, "span_deg", 140)
    assert "360" in (doc.solution.error or "")
    doc.undo()
    doc.set_segment(0, "law", "septic")
    assert "segments[0].law" in (doc.solution.error or "")
    doc.undo()
    assert doc.solution.error is None
    with pytest.raises(KeyError, match="no segment 9"):
        doc.set_segment(9, "lift", 0.0)
    with pytest.raises(KeyError, match="not one of"):
        doc.set_segment(0, "base_radius", 0.0)
    with pytest.raises(ValueError, match="finite"):
        doc.set_segment(1, "lift", math.inf)


def test_issue29_studio_cam_oscillating_swing(tmp_path: Path) -> None:
    path = _copy(tmp_path, "cam_design_indexing.toml")
    doc = CamDocument(path)
    assert doc.oscillating
    # Two rises and two returns of 30°: make each 25° (degrees of swing).
    for k, v in ((0, 25), (2, -25), (4, 25), (6, -25)):
        doc.set_segment(k, "lift", v)
    assert doc.solution.error is None
    data = cam_payload(doc)
    assert data["peaks"]["s"][0] == pytest.approx(math.radians(25.0), abs=1e-12)
    # The pressure angle over the turn, sampled every 0.25°: its peak is
    # the report's (found by the core's search between samples) to 1e-3°,
    # never above it; the limit is the file's 35°.
    rise = {c["name"]: c for c in data["report"]["checks"]}["pressure angle, rise"]
    peak = math.degrees(data["peaks"]["p"][0])
    assert peak <= rise["value"] + 1e-9 and peak == pytest.approx(rise["value"], abs=1e-3)
    assert data["pressure_limit"] == pytest.approx(math.radians(35.0), abs=1e-15)
    assert "pressure" not in cam_payload(CamDocument(EXAMPLES / "cam_design_valve.toml"))
    doc.save()
    saved = tomllib.loads(path.read_text())["segments"]
    assert [s.get("swing_deg") for s in saved[::2]] == [25, -25, 25, -25]


def test_issue29_studio_opens_model_or_design(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert isinstance(open_document(EXAMPLES / "four_bar.toml"), Document)
    assert isinstance(open_document(EXAMPLES / "cam_motion_roller.toml"), Document)
    broken = tmp_path / "design.toml"
    broken.write_text('[cam]\nbase_radius = 0.02\n[follower]\ntype = "translating-flat"\n'
                      '[[segments]]\nlaw = "dwell"\nspan_deg = 350\n')
    assert main(["studio", str(broken), "--no-browser"]) == 2
    err = capsys.readouterr().err
    assert "design.toml" in err and "360" in err and "Traceback" not in err


async def _cam_guard_checks(path: Path) -> None:
    token = TOKEN
    async with studio_client(CamDocument(path)) as (client, port):
        ok = await client.get(f"/?token={token}")
        assert ok.status == 200 and "static/cam.js" in await ok.text()
        await refuses_strangers(client, token, "/static/cam.js")
        ws = await client.ws_connect(f"/ws?token={token}", headers={"Origin": f"http://127.0.0.1:{port}"})
        await ws.send_str(json.dumps({"op": "hello", "seq": 1}))
        reply = json.loads((await ws.receive()).data)
        assert reply["type"] == "frames" and reply["data"]["kind"] == "cam"
        assert reply["data"]["title"] == "valve cam"
        await ws.send_str(json.dumps({"op": "segment", "index": 7, "key": "lift", "value": 0, "seq": 2}))
        reply = json.loads((await ws.receive()).data)
        assert reply == {"type": "error", "seq": 2, "message": "no segment 7 (the program has 4)"}
        await ws.send_str(json.dumps({"op": "move", "handle": "x", "seq": 3}))
        reply = json.loads((await ws.receive()).data)
        assert reply == {"type": "error", "seq": 3, "message": "unknown request 'move'"}
        await ws.close()


def test_issue29_studio_cam_refuses_without_token_or_from_another_origin(tmp_path: Path) -> None:
    asyncio.run(_cam_guard_checks(_copy(tmp_path, "cam_design_valve.toml")))


def test_issue29_studio_motion_curve_segments(tmp_path: Path) -> None:
    path = _copy(tmp_path, "cam_motion_roller.toml")
    doc = Document(path)
    assert [(g["law"], g["span"], g["lift"]) for g in doc.motion_segments()] == [
        ("dwell", "pi/3", 0.0), ("cycloidal", "2*pi/3", "lift"), ("dwell", "pi/3", 0.0),
        ("3-4-5", "2*pi/3", "-lift")]
    before = doc.text()
    with pytest.raises(camlink.ModelError, match=r"curves\[0\]\.segments: the program does not close"):
        doc.set_segments([("profile", 1, "lift", 0.015)])
    assert doc.text() == before and not doc.can_undo
    for bad, match in (
        (("nope", 1, "lift", 0.0), "no motion curve 'nope'"),
        (("roller", 1, "lift", 0.0), "no motion curve 'roller'"),
        (("profile", 4, "lift", 0.0), "has no segment 4"),
        (("profile", 1, "offset", 0.0), "not one of law, span, lift"),
    ):
        with pytest.raises(KeyError, match=match):
            doc.set_segments([bad])
    with pytest.raises(ValueError, match="not finite"):
        doc.set_segments([("profile", 1, "lift", math.nan)])
    # A rise and its return at once, the return as an expression; the
    # follower's stroke (y along its guide) is the new lift.
    doc.set_segments([("profile", 1, "lift", 0.015), ("profile", 3, "lift", "-1.25*lift")])
    y = doc.solution.values[:, doc.solution.names.index("follower.y")]
    assert np.ptp(y) == pytest.approx(0.015, abs=1e-9)
    doc.save()
    saved = camlink.load(path).run()
    assert np.max(np.abs(saved["follower.y"] - y)) <= 1e-12
    doc.undo()
    assert doc.text() == before
