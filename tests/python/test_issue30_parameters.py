"""Issue 30 snag: `Model.with_parameters` takes expression strings, as the
file's ``[parameters]`` do (evaluated by camlink's expression evaluator,
reading the other parameters with their new values), and names the
parameter of one that does not evaluate."""

from __future__ import annotations

import math
import pickle

import pytest

import camlink
from camlink.records import BodyRecord
from conftest import ROOT

FOUR_BAR = ROOT / "examples" / "four_bar.toml"


def _crank(model: camlink.Model) -> BodyRecord:
    return {b["name"]: b for b in model.bodies}["crank"]


def test_issue30_with_parameters_takes_expressions() -> None:
    base = camlink.load(FOUR_BAR)
    variant = base.with_parameters(w="3*pi", theta0="deg(30)")
    assert _crank(variant)["angle"] == pytest.approx(math.pi / 6, abs=1e-15)
    res = variant.run(t_end=0.1, step=0.05)
    assert res["crank.omega"][0] == pytest.approx(3 * math.pi, rel=1e-12)
    # An expression reads the other parameters, with their new values.
    linked = base.with_parameters(d=0.5, a="d/4")
    assert _crank(linked)["points"]["A"] == [0.125, 0.0]
    # Numbers and number strings give the same model.
    assert _crank(base.with_parameters(a="0.1"))["points"]["A"] == [0.1, 0.0]
    # A pickled variant keeps its expressions.
    back = pickle.loads(pickle.dumps(linked))
    assert _crank(back)["points"]["A"] == [0.125, 0.0]


@pytest.mark.parametrize(("value", "says"), [
    ("3*", "expected a value"),
    ("2*nope", "nope"),
    ("w + 1", "cycle"),
    ("__import__('os')", "unexpected character"),
    ("1/0", "division by zero"),
    ("exp(1000)", "not finite"),
])
def test_issue30_with_parameters_bad_expression_names_the_parameter(value: str, says: str) -> None:
    with pytest.raises(camlink.ModelError, match=says) as e:
        camlink.load(FOUR_BAR).with_parameters(w=value)
    assert "parameters.w" in str(e.value)
    # Not placed at a line of the file, which holds the file's own value.
    assert str(e.value).startswith(f"{FOUR_BAR}: parameters.w: "), str(e.value)


@pytest.mark.parametrize("value", [None, [1.0], True])
def test_issue30_with_parameters_refuses_other_values(value: object) -> None:
    with pytest.raises(camlink.ModelError, match="is not a number or an expression string"):
        camlink.load(FOUR_BAR).with_parameters(w=value)  # type: ignore[arg-type]
