"""Shared models for the Python tests.

The models are written out as TOML here so that the tests do not depend on
the examples; `test_examples.py` covers those.
"""

from __future__ import annotations

import contextlib
import math
import os
import shutil
import subprocess
import sys
from collections.abc import AsyncIterator, Iterator
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[2]


def four_bar_toml(r=1.0, L=2.6, b=2.5, d=3.0, speed="2*pi", t_end=1.0, step=0.01) -> str:
    """A four-bar driven at its crank O: ground O–C = d, crank r, coupler L,
    rocker b, starting with the crank at 60°. Bodies are placed exactly."""
    th = math.radians(60)
    ax, ay = r * math.cos(th), r * math.sin(th)
    # B: intersection of |B − A| = L and |B − C| = b, elbow up.
    dx, dy = d - ax, -ay
    e = math.hypot(dx, dy)
    a = (L * L - b * b + e * e) / (2 * e)
    h = math.sqrt(max(L * L - a * a, 0.0))
    bx = ax + a * dx / e - h * dy / e
    by = ay + a * dy / e + h * dx / e
    coupler = math.atan2(by - ay, bx - ax)
    rocker = math.atan2(by, bx - d)
    return f"""
[model]
name = "four_bar"
gravity = [0, -9.81]

[parameters]
r = {r}
L = {L}
b = {b}
d = {d}
w = "{speed}"

[ground]
points = {{ O = [0, 0], C = ["d", 0] }}

[[bodies]]
name = "crank"
angle = "deg(60)"
mass = 1.0
inertia = 0.1
points = {{ O = [0, 0], A = ["r", 0] }}

[[bodies]]
name = "coupler"
position = [{ax!r}, {ay!r}]
angle = {coupler!r}
mass = 2.6
inertia = 1.5
points = {{ A = [0, 0], B = ["L", 0], P = ["L/2", 0.5] }}

[[bodies]]
name = "rocker"
position = ["d", 0]
angle = {rocker!r}
mass = 2.5
inertia = 1.3
points = {{ C = [0, 0], B = ["b", 0] }}

[[joints]]
name = "O"
type = "revolute"
body_i = "ground"
point_i = "O"
body_j = "crank"
point_j = "O"

[[joints]]
name = "A"
type = "revolute"
body_i = "crank"
point_i = "A"
body_j = "coupler"
point_j = "A"

[[joints]]
name = "B"
type = "revolute"
body_i = "coupler"
point_i = "B"
body_j = "rocker"
point_j = "B"

[[joints]]
name = "C"
type = "revolute"
body_i = "rocker"
point_i = "C"
body_j = "ground"
point_j = "C"

[[drivers]]
name = "motor"
type = "revolute_angle"
joint = "O"
f = "deg(60) + w*t"

[analysis]
t_end = {t_end}
step = {step}
points = ["coupler.P", "crank.A"]
"""


#: A non-Grashof four-bar: the crank cannot turn past about 119.6°, which a
#: crank at 2π rad/s from 60° reaches at t ≈ 0.166 s.
STUCK_FOUR_BAR = dict(r=1.0, L=2.6, b=1.0, d=3.0)
STUCK_TIME = (math.degrees(math.acos(-(12.96 - 10) / 6)) - 60) / 360


@pytest.fixture
def four_bar_file(tmp_path: Path) -> Path:
    path = tmp_path / "four_bar.toml"
    path.write_text(four_bar_toml())
    return path


@pytest.fixture
def stuck_file(tmp_path: Path) -> Path:
    path = tmp_path / "stuck.toml"
    path.write_text(four_bar_toml(**STUCK_FOUR_BAR))
    return path


def run_cli(*args: str | os.PathLike[str], cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    """`python -m camlink ARGS`, capturing output."""
    return subprocess.run(
        [sys.executable, "-m", "camlink", *map(str, args)],
        capture_output=True,
        text=True,
        cwd=cwd,
        timeout=120,
    )


def _chromium() -> str:
    """Debian's chromium, which the browser tests drive through Playwright
    (`.ci/run` installs it)."""
    for name in ("chromium", "chromium-browser"):
        found = shutil.which(name)
        if found:
            return found
    raise pytest.fail.Exception(
        "no chromium on PATH: apt-get install -y chromium (or deselect with -m 'not browser')"
    )


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    """A headless chromium for the tests of one module."""
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=_chromium(), args=["--no-sandbox"])
        yield b
        b.close()


async def refuses_strangers(client: Any, token: str, asset: str) -> None:
    """The studio server behind the aiohttp test `client` answers its page
    and `asset` (a path) with `token` only, and refuses them and its
    websocket (403) without the token, with a wrong one, or from another
    origin or host."""
    port = client.server.port
    for url in ("/", "/?token=wrong", f"{asset}?token={token}x", asset, "/ws"):
        assert (await client.get(url)).status == 403, url
    for url in ("/", asset):
        assert (await client.get(f"{url}?token={token}")).status == 200, url
        for headers in ({"Origin": "http://evil.example"}, {"Host": "evil.example"},
                        {"Origin": f"http://localhost:{port + 1}"}):
            assert (await client.get(f"{url}?token={token}", headers=headers)).status == 403, headers
    with pytest.raises(Exception, match="403"):
        await client.ws_connect(f"/ws?token={token}", headers={"Origin": "http://evil.example"})
    with pytest.raises(Exception, match="403"):
        await client.ws_connect(f"/ws?token={token}", headers={"Host": "evil.example"})
    with pytest.raises(Exception, match="403"):
        await client.ws_connect("/ws?token=nope")


#: The token of the studio servers the tests start in-process.
TOKEN = "s3cret-token"


@contextlib.asynccontextmanager
async def studio_client(doc: Any) -> AsyncIterator[tuple[Any, int]]:
    """An aiohttp test client of a studio server for `doc` answering with
    `TOKEN`, and the server's port."""
    from aiohttp.test_utils import TestClient, TestServer

    from camlink.studio import make_app

    async with TestClient(TestServer(make_app(doc, TOKEN), host="127.0.0.1")) as client:
        port = client.server.port
        assert port is not None
        yield client, port
