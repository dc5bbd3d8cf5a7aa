"""The model's self-description returns typed records whose keys are
exactly the binding's: `Model.bodies`, `joints`, `forces`, `analysis`,
`check()` and `design_check()`."""

from __future__ import annotations

import typing
from pathlib import Path

import pytest
from test_dynamics import flat_follower_on_the_seed_cam

import camlink
from camlink import records
from camlink.model import Model

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _keys(record: type) -> set[str]:
    return set(typing.get_type_hints(record))


@pytest.mark.parametrize(
    "member, record, many",
    [
        ("bodies", records.BodyRecord, True),
        ("joints", records.JointRecord, True),
        ("forces", records.ForceRecord, True),
        ("analysis", records.AnalysisSettings, False),
        ("check", records.CheckReport, False),
        ("design_check", records.DesignFinding, True),
    ],
)
def test_records_are_typed_and_match_the_binding(member: str, record: type, many: bool) -> None:
    attr = getattr(Model, member)
    hints = typing.get_type_hints(attr.fget if isinstance(attr, property) else attr)
    want = list[record] if many else record  # type: ignore[valid-type]
    assert hints["return"] == want
    if member == "design_check":
        model = camlink.loads(flat_follower_on_the_seed_cam(), "toml", "flat.toml")
    else:
        model = camlink.load(EXAMPLES / "dyn_spring_pendulum.toml")
    value = getattr(model, member)
    value = value() if callable(value) else value
    items = value if many else [value]
    assert items, f"{member} is empty in the example"
    for item in items:
        assert set(item) == _keys(record)


def test_check_report_nests_typed_records() -> None:
    report = camlink.load(EXAMPLES / "four_bar.toml").check()
    assert set(report["joints"][0]) == _keys(records.ConstraintCount)
    hints = typing.get_type_hints(records.CheckReport)
    assert hints["joints"] == list[records.ConstraintCount]
    assert hints["redundant"] == list[records.RedundantEquation]
