"""`camlink cam DESIGN.toml`: synthesise a cam, check its limits, write
its pictures and manufacturing files.

Exit status: 0 every limit holds; 1 a limit fails; 2 bad input.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

from camlink import cam_design, cam_export, cam_plots

EXIT_OK, EXIT_FAIL, EXIT_INPUT = 0, 1, 2


def add_parser(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """Registers the `cam` subcommand."""
    p = sub.add_parser(
        "cam",
        help="synthesise a cam from a motion program and check its design limits",
        description="Read a cam design file (motion program, follower, limits), synthesise the cam, "
        "print the report and write the SVAJ and profile pictures, CSV, DXF and SVG. "
        "Exit 0 when every limit holds, 1 when one fails, 2 for bad input.",
    )
    p.add_argument("design", metavar="DESIGN", help="cam design file (.toml)")
    p.add_argument("--json", action="store_true", help="print the report as JSON")
    p.add_argument(
        "-o",
        "--out",
        metavar="DIR",
        default=".",
        help="directory for the files written (default: .)",
    )
    p.add_argument(
        "--no-files", action="store_true", help="write no pictures or exports"
    )


def _write_files(design: cam_design.Design, out: Path) -> list[str]:
    core = design.core()
    ex = design.export
    out.mkdir(parents=True, exist_ok=True)
    written: list[str] = []
    if ex.svaj:
        fig = cam_plots.svaj(
            core, oscillating=design.oscillating, title=f"{design.name}: SVAJ"
        )
        cam_plots.save(fig, out / ex.svaj)
        written.append(str(out / ex.svaj))
    if ex.profile:
        colour = "rho" if design.follower.endswith("flat") else "pressure_angle"
        fig = cam_plots.profile(
            core,
            base_radius=design.base_radius,
            colour_by=colour,
            title=f"{design.name}: profile",
        )
        cam_plots.save(fig, out / ex.profile)
        written.append(str(out / ex.profile))
    if ex.csv:
        th = (
            cam_export.angles_by_chord(core, ex.csv_chord)
            if ex.csv_chord is not None
            else cam_export.angles_by_step(ex.csv_step)
        )
        cam_export.write_csv(core, out / ex.csv, th, ex.tool_radius)
        written.append(str(out / ex.csv))
    if ex.dxf:
        cam_export.write_dxf(
            core, out / ex.dxf, ex.tolerance, ex.dxf_mode, ex.tool_radius
        )
        written.append(str(out / ex.dxf))
    if ex.svg:
        cam_export.write_svg(core, out / ex.svg, ex.tolerance, ex.tool_radius)
        written.append(str(out / ex.svg))
    return written


def _clean(v: object) -> object:
    """JSON-safe values: infinities and NaN become null."""
    if isinstance(v, float) and not math.isfinite(v):
        return None
    if isinstance(v, dict):
        return {k: _clean(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_clean(x) for x in v]
    return v


def run(args: argparse.Namespace) -> int:
    """Runs `camlink cam`."""
    try:
        design = cam_design.load(args.design)
        report = cam_design.analyse(design)
    except cam_design.CamDesignError as e:
        print(f"camlink: error: {e}", file=sys.stderr)
        return EXIT_INPUT
    if not args.no_files:
        files = _write_files(design, Path(args.out))
        report = cam_design.Report(**{**report.__dict__, "files": tuple(files)})
    if args.json:
        print(json.dumps(_clean(report.to_dict()), indent=2))
    else:
        print(cam_design.format_report(report))
    return EXIT_OK if report.ok else EXIT_FAIL
