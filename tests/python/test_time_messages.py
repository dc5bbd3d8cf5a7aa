"""Times in error messages are written short (issue 27): ``1e-300``, not
298 digits; ``1e-7``, not ``0.00000010000000000000001``."""

from __future__ import annotations

import pytest

import camlink

ARM = """
[[bodies]]
name = "arm"
points = {{ tip = [1, 0] }}

[[joints]]
name = "pivot"
type = "revolute"
body_i = "ground"
body_j = "arm"

[[drivers]]
name = "motor"
type = "revolute_angle"
joint = "pivot"
f = "{f}"
"""


@pytest.mark.parametrize(
    ("f", "t", "shown"),
    [("log(-t)", 1e-300, "1e-300"), ("sqrt(-t)", 1.0000000000000001e-7, "1e-7")],
)
def test_issue27_time_messages_are_short(f: str, t: float, shown: str) -> None:
    model = camlink.loads(ARM.format(f=f))
    with pytest.raises(camlink.AnalysisError) as e:
        model.run(analysis="kinematics", times=[t])
    text = str(e.value)
    assert text.startswith(f"at t = {shown} s: "), text
    assert f"at t = {shown};" in text, text
    assert "0.0000" not in text, text
