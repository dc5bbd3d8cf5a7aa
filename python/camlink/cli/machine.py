"""`camlink machine MODEL`: shaking force and moment, counterweights,
flywheel and motor of a linkage at its design speed (the model file's
``[machine]`` table; `docs/machine.md`).

Exit status: 0 every check holds; 1 a check fails; 2 bad input.
"""

from __future__ import annotations

import argparse
import json
import sys
from dataclasses import asdict
from pathlib import Path
from typing import TYPE_CHECKING

from camlink._core import AnalysisError, ModelError
from camlink.io.output import check_not_input, replacing

if TYPE_CHECKING:
    from camlink.study.balance import PartialBalance

EXIT_OK, EXIT_FAIL, EXIT_INPUT = 0, 1, 2


def add_parser(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """Registers the `machine` subcommand."""
    p = sub.add_parser(
        "machine",
        help="shaking force, balancing, flywheel and motor sizing of a linkage",
        description="Run one cycle of MODEL at the design speed of its [machine] table and report "
        "the shaking force and moment on the frame, the counterweights of a full force balance, the "
        "flywheel for the speed band and the motor checks. Exit 0 when every check holds, 1 when one "
        "fails, 2 for bad input.",
    )
    p.add_argument("model", metavar="MODEL", help="model file (.toml or .json) with a [machine] table")
    p.add_argument("--json", action="store_true", help="print the report as JSON")
    p.add_argument("--plot", metavar="PNG", help="write the polar plot of the shaking force")
    p.add_argument(
        "--balanced",
        metavar="TOML",
        help="write a copy of the (TOML) model with the counterweights on its bodies "
        "(those of the partial balance with --partial)",
    )
    p.add_argument(
        "--partial",
        metavar="WF,WM,WT",
        help="partial balance: the counterweights of the full balance scaled to minimise "
        "WF·F/F0 + WM·M/M0 + WT·ΔT/ΔT0 (shaking force, shaking moment, input torque swing, each "
        "relative to the unbalanced machine), e.g. 1,1,1",
    )


def _weights(text: str) -> tuple[float, float, float]:
    parts = text.split(",")
    try:
        w = tuple(float(x) for x in parts)
    except ValueError:
        w = ()
    if len(w) != 3:
        raise ModelError(f"--partial: give three weights WF,WM,WT such as 1,1,1, not '{text}'")
    return (w[0], w[1], w[2])


def _partial_text(p: PartialBalance) -> str:
    """The partial balance as text."""
    wf, wm, wt = p.weights
    lines = [
        f"partial balance ({p.linkage}), J = {wf:g}·F/F0 + {wm:g}·M/M0 + {wt:g}·ΔT/ΔT0 "
        "(F peak |F_s − W|, M peak |M|, ΔT input torque swing; study optimiser):"
    ]
    for name, f in (("unbalanced", p.unbalanced), ("full balance", p.full), ("partial", p.figures)):
        lines.append(
            f"  {name:12s} F {f.force:.6g} N, M {f.moment:.6g} N·m, "
            f"ΔT {f.torque_swing:.6g} N·m, J {f.objective:.4g}"
        )
    for c in p.counterweights:
        k = p.factors[c["body"]]
        lines.append(
            f"  {c['body']}: factor {k:.4g} of the full counterweight: {c['mass']:.6g} kg at "
            f"({c['at'][0]:.6g}, {c['at'][1]:.6g}) m in its frame; body mass {c['new_mass']:.6g} kg, "
            f"centroid ({c['new_centroid'][0]:.6g}, {c['new_centroid'][1]:.6g}) m, "
            f"inertia {c['new_inertia']:.6g} kg·m²"
        )
    return "\n".join(lines)


def run(args: argparse.Namespace) -> int:
    """Runs `camlink machine`."""
    # Imported here, not at the top: the study stack (pandas) and the
    # machine's pictures (matplotlib) are not needed to build the parser.
    from camlink import machine
    from camlink.study.balance import partial_balance

    src = Path(args.model)
    part: PartialBalance | None = None
    try:
        weights = _weights(args.partial) if args.partial else None
        r = machine.report(src)
        if weights is not None:
            part = partial_balance(src, weights)
        if args.plot:
            target = Path(args.plot)
            check_not_input(target, [src])
            with replacing(target) as temp:
                machine.save(machine.polar(r, title=f"{src.stem}: shaking force"), temp)
        if args.balanced:
            target = Path(args.balanced)
            check_not_input(target, [src])
            if src.suffix.lower() != ".toml":
                raise ModelError(f"--balanced: {src} is not a TOML model file")
            text = src.read_text(encoding="utf-8")
            if part is not None:
                text = machine.counterweights_text(text, part.counterweights)
            else:
                text = machine.balanced_text(text, r)
            with replacing(target) as temp:
                Path(temp).write_text(text, encoding="utf-8")
    except (ModelError, AnalysisError) as e:
        print(f"camlink: error: {e}", file=sys.stderr)
        return EXIT_INPUT
    except OSError as e:
        print(f"camlink: error: {e.filename or ''}: {e.strerror}", file=sys.stderr)
        return EXIT_INPUT
    if args.json:
        out = machine.to_json(r)
        if part is not None:
            out["partial_balance"] = {
                "weights": list(part.weights),
                "factors": part.factors,
                "counterweights": part.counterweights,
                **{k: asdict(getattr(part, k)) for k in ("figures", "unbalanced", "full")},
            }
        print(json.dumps(out, indent=2))
    else:
        print(machine.format_report(r, src.stem))
        if part is not None:
            print(_partial_text(part))
    return EXIT_OK if r["ok"] else EXIT_FAIL
