"""`camlink cam DESIGN.toml`: synthesise a cam, check its limits, write
its pictures and manufacturing files.

Exit status: 0 every limit holds; 1 a limit fails; 2 bad input.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from camlink._core import ModelError
from camlink.io.output import check_not_input, replacing
from camlink.units import parse_units

if TYPE_CHECKING:
    from camlink.cam import design as cam_design
    from camlink.cam import export as cam_export

# The cam design, its plots and exports (matplotlib, ezdxf) are imported by
# the functions that use them, so that building the parser of every
# `camlink` command stays cheap.

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
    p.add_argument(
        "--units",
        metavar="LENGTH,ANGLE",
        help="units of the report, pictures and exports: 'mm,deg' or 'm,deg' (default: "
        "[export] units of the design file, else m; angles are always in degrees)",
    )
    p.add_argument(
        "--force",
        action="store_true",
        help="replace existing files of the default names (<design>.csv, …); files named in "
        "[export] are replaced anyway, the design file never",
    )


def _targets(design: cam_design.Design, out: Path, force: bool) -> dict[str, Path]:
    """The files to write by their ``[export]`` key, checked before any is
    written: none is the design file, and none of a default name exists
    unless `force`."""
    from camlink.cam import design as cam_design

    ex = design.export
    names = {
        "svaj_plot": ex.svaj,
        "profile_plot": ex.profile,
        "csv": ex.csv,
        "dxf": ex.dxf,
        "svg": ex.svg,
        "svaj_time_plot": ex.svaj_time,
        "vibration_plot": ex.vibration,
    }
    targets: dict[str, Path] = {}
    existing: list[str] = []
    for key, name in names.items():
        if name is None:
            continue
        path = out / name
        try:
            check_not_input(path, [design.path])
        except ModelError:
            raise cam_design.CamDesignError(
                f"{design.path}: export.{key}: '{path}' is the design file; "
                "choose another file name"
            ) from None
        if key not in ex.given and not force and path.exists():
            existing.append(f"{path} (export.{key})")
        targets[key] = path
    if existing:
        raise cam_design.CamDesignError(
            f"{', '.join(existing)} {'exists' if len(existing) == 1 else 'exist'}; pass --force "
            f"to replace the files of default names, or name them in [export] of {design.path}"
        )
    return targets


def _write_files(design: cam_design.Design, out: Path, force: bool = False) -> list[str]:
    """Writes the pictures and exports into `out`, each to a temporary file
    renamed over its name when complete; returns the paths written."""
    from camlink.cam import design as cam_design
    from camlink.cam import export as cam_export
    from camlink.cam import plots as cam_plots

    core = design.core()
    ex = design.export
    if out.exists() and not out.is_dir():
        raise cam_design.CamDesignError(f"--out {out}: not a folder")
    targets = _targets(design, out, force)
    out.mkdir(parents=True, exist_ok=True)
    written: list[str] = []
    for key, path in targets.items():
        with replacing(path) as temp:
            if key == "svaj_plot":
                fig = cam_plots.svaj(
                    core,
                    oscillating=design.oscillating,
                    title=f"{design.name}: SVAJ",
                    units=ex.units,
                )
                cam_plots.save(fig, temp)
            elif key == "svaj_time_plot":
                assert design.dynamics is not None
                fig = cam_plots.svaj_time(
                    core,
                    design.dynamics.speed,
                    oscillating=design.oscillating,
                    title=f"{design.name}: SVAJ at {design.dynamics.speed / cam_design.RPM:g} rpm",
                    units=ex.units,
                )
                cam_plots.save(fig, temp)
            elif key == "vibration_plot":
                fig = cam_plots.vibration(
                    core,
                    design,
                    title=f"{design.name}: follower train at "
                    f"{design.dynamics.speed / cam_design.RPM:g} rpm"
                    if design.dynamics
                    else design.name,
                )
                cam_plots.save(fig, temp)
            elif key == "profile_plot":
                colour = "rho" if design.follower.endswith("flat") else "pressure_angle"
                fig = cam_plots.profile(
                    core,
                    base_radius=design.base_radius,
                    colour_by=colour,
                    title=f"{design.name}: profile",
                )
                cam_plots.save(fig, temp)
            elif key == "csv":
                th = (
                    cam_export.angles_by_chord(core, ex.csv_chord)
                    if ex.csv_chord is not None
                    else cam_export.angles_by_step(ex.csv_step)
                )
                cam_export.write_csv(core, temp, th, ex.tool_radius, ex.units)
            elif key == "dxf":
                cam_export.write_dxf(
                    core, temp, ex.tolerance, ex.dxf_mode, ex.tool_radius, ex.units, _hub(design)
                )
            else:
                cam_export.write_svg(core, temp, ex.tolerance, ex.tool_radius, _hub(design))
        written.append(str(path))
    return written


def _hub(design: cam_design.Design) -> cam_export.Hub | None:
    """The bore, keyway and timing mark of `design`, or None."""
    import numpy as np

    from camlink.cam import export as cam_export

    ex = design.export
    if ex.bore_radius is None:
        return None
    p = design.core().surface(np.zeros(1))[0]
    mark = math.atan2(float(p[1]), float(p[0]))
    return cam_export.Hub(
        ex.bore_radius,
        ex.keyway_width,
        ex.keyway_depth,
        mark + ex.keyway_angle,
        mark if ex.timing_mark else None,
    )


def _run_timing(args: argparse.Namespace) -> int:
    """`camlink cam TIMING.toml`: clearances, the timing diagram and the
    servo cam tables."""
    from dataclasses import asdict

    from camlink.cam import design as cam_design
    from camlink.cam import timing as cam_timing

    try:
        timing = cam_timing.load(args.design)
        if args.units is not None:
            timing = dataclasses.replace(timing, units=_units(args.units))
        report = cam_timing.clearances(timing)
        files = [] if args.no_files else cam_timing.write(timing, Path(args.out), report, args.force)
    except cam_design.CamDesignError as e:
        print(f"camlink: error: {e}", file=sys.stderr)
        return EXIT_INPUT
    ok = all(c.ok for c in report)
    if args.json:
        d = {
            "ok": ok,
            "name": timing.name,
            "axes": [a.name for a in timing.axes],
            "clearances": [asdict(c) for c in report],
            "files": files,
        }
        print(json.dumps(cam_design.json_safe(d), indent=2))
    else:
        print(cam_timing.format_report(timing, report, files))
    return EXIT_OK if ok else EXIT_FAIL


def _units(text: str) -> str:
    """The length unit of ``--units LENGTH,ANGLE`` (read as `camlink run
    --units` reads it, `camlink.units.parse_units`): m or mm, angles in
    degrees (a length alone means degrees too)."""
    from camlink.cam import design as cam_design

    try:
        units = parse_units(text if "," in text else f"{text},deg")
    except ModelError:
        units = None
    if units is None or units.length not in ("m", "mm") or units.angle != "deg":
        raise cam_design.CamDesignError(
            f"--units {text}: give a length unit (m or mm) and deg, e.g. --units mm,deg"
        )
    return units.length


def run(args: argparse.Namespace) -> int:
    """Runs `camlink cam`."""
    from camlink.cam import design as cam_design
    from camlink.cam import timing as cam_timing

    if cam_timing.is_timing(args.design):
        return _run_timing(args)
    try:
        design = cam_design.load(args.design)
        if args.units is not None:
            units = _units(args.units)
            design = dataclasses.replace(
                design, export=dataclasses.replace(design.export, units=units)
            )
        report = cam_design.analyse(design)
        if not args.no_files:
            files = _write_files(design, Path(args.out), args.force)
            report = cam_design.Report(**{**report.__dict__, "files": tuple(files)})
    except cam_design.CamDesignError as e:
        print(f"camlink: error: {e}", file=sys.stderr)
        return EXIT_INPUT
    report = cam_design.in_units(report, design.export.units)
    if args.json:
        print(json.dumps(cam_design.json_safe(report.to_dict()), indent=2))
    else:
        print(cam_design.format_report(report))
    return EXIT_OK if report.ok else EXIT_FAIL
