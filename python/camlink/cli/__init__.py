"""The `camlink` command.

Exit status: 0 success; 1 the analysis could not proceed (results up to the
failure are still written); 2 bad input (a model file, an argument, a path);
3 an internal error (a bug in camlink; set CAMLINK_TRACEBACK=1 to see where).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import signal
import sys
import warnings
from pathlib import Path
from typing import NoReturn, TextIO

import camlink
from camlink._core import AnalysisError, ModelError
from camlink.cli import cam as cam_cli
from camlink.cli import convert as cli_convert
from camlink.cli import machine as machine_cli
from camlink.cli import studio as cli_studio
from camlink.cli import study as cli_study
from camlink.cli import synth as cli_synth
from camlink.cli import visuals as cli_visuals
from camlink.io.output import check_not_input
from camlink.model import ANALYSES
from camlink.settings import check_settings
from camlink.signals import Terminated, stop_on_termination
from camlink.units import SI, parse_units

EXIT_OK, EXIT_ANALYSIS, EXIT_INPUT, EXIT_INTERNAL = 0, 1, 2, 3

#: Subcommands registered from their own modules.
COMMANDS: dict[str, cli_visuals.Command] = {}


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="camlink",
        description="Planar multibody kinematics and dynamics: load a model file, check it, run it.",
    )
    p.add_argument("--version", action="version", version=f"camlink {camlink.__version__}")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")

    run = sub.add_parser(
        "run",
        help="run the model's analysis and write the results",
        description="Run the analysis the model file asks for ([analysis] type: "
        "kinematics, inverse_dynamics, equilibrium or dynamics), or the one given "
        "with --analysis. Settings left out come from the model file's [analysis] table.",
    )
    run.add_argument(
        "model",
        metavar="MODEL",
        help="model file (.toml, .json or simEngine2D .adm); - reads standard input",
    )
    run.add_argument(
        "--acf", metavar="FILE", help="simEngine2D analysis file for a .adm model (default: beside it)"
    )
    run.add_argument(
        "-a",
        "--analysis",
        choices=ANALYSES,
        metavar="TYPE",
        help=f"analysis to run instead of the file's: {', '.join(ANALYSES)}",
    )
    run.add_argument(
        "-o",
        "--output",
        metavar="FILE",
        help="results file, .csv or .parquet; - writes CSV to standard output "
        "(default: MODEL's name with .csv, in the current directory)",
    )
    run.add_argument(
        "--force",
        action="store_true",
        help="replace an existing file at the default output path",
    )
    run.add_argument(
        "--units",
        metavar="LENGTH,ANGLE",
        help="units of the results written, e.g. mm,deg (lengths, angles and their rates; "
        "forces, torques and energies stay SI; default: m,rad)",
    )
    _data_option(run)
    run.add_argument("--t-end", type=float, metavar="T", help="end time (s)")
    run.add_argument("--step", type=float, metavar="H", help="output time step (s)")
    run.add_argument(
        "--time", type=float, metavar="T", help="equilibrium: time of the drivers and forces (s)"
    )
    run.add_argument("--tol", type=float, metavar="TOL", help="Newton tolerance")
    run.add_argument("--max-iter", type=int, metavar="N", help="Newton iterations per step")
    run.add_argument("--h", type=float, metavar="H", help="dynamics: integration step (s)")
    run.add_argument(
        "--atol", type=float, metavar="A", help="adaptive dynamics: absolute error tolerance (m or rad)"
    )
    run.add_argument(
        "--rtol", type=float, metavar="R", help="adaptive dynamics: relative error tolerance"
    )
    run.add_argument(
        "--h-min", type=float, metavar="H", help="adaptive dynamics: smallest step (s)"
    )
    run.add_argument(
        "--rho-inf", type=float, metavar="R", help="dynamics: numerical damping ρ∞ in [0, 1]"
    )
    run.add_argument(
        "--adaptive",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="dynamics: error-controlled steps (--no-adaptive: fixed steps)",
    )
    run.add_argument(
        "--jerk",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="kinematics: also output the exact jerk, <body>.jx .jy .jphi and "
        "<point>.jx .jy (default: [analysis] jerk)",
    )
    run.add_argument(
        "-p",
        "--point",
        action="append",
        dest="points",
        metavar="BODY.POINT",
        help="a body point to output instead of the model's [analysis] points "
        "(repeatable: the points given are the only ones output)",
    )
    run.add_argument("-q", "--quiet", action="store_true", help="print nothing on success")
    run.add_argument(
        "-v",
        "--verbose",
        action="store_true",
        help="also print how assembly moved the bodies and the solver counts",
    )

    check = sub.add_parser(
        "check",
        help="count bodies, coordinates and constraints; find the degrees of freedom",
    )
    check.add_argument("model", metavar="MODEL", help="model file (.toml, .json or simEngine2D .adm)")
    check.add_argument(
        "--acf", metavar="FILE", help="simEngine2D analysis file for a .adm model (default: beside it)"
    )
    check.add_argument("--json", action="store_true", help="print the report as JSON")
    _data_option(check)

    sub.add_parser("schema", help="print the JSON Schema of model files")
    cli_convert.add_parser(sub)
    COMMANDS.update(cli_visuals.add_parsers(sub))
    cam_cli.add_parser(sub)
    machine_cli.add_parser(sub)
    COMMANDS["study"] = cli_study.add_parser(sub)
    COMMANDS["synth"] = cli_synth.add_parser(sub)
    COMMANDS["studio"] = cli_studio.add_parser(sub)
    return p


def _data_option(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--allow-outside-data",
        action="store_true",
        help="let the model read data files outside its folder",
    )


def _error(message: str) -> None:
    print(f"camlink: error: {message}", file=sys.stderr)


def _os_message(e: OSError) -> str:
    if e.filename is not None:
        return f"{e.filename}: {e.strerror or e}"
    return str(e)


def _cmd_run(args: argparse.Namespace) -> int:
    model = _load(args)
    for lw in model.warnings:
        print(f"camlink: warning: {lw['text']}", file=sys.stderr)
    kind = args.analysis or model.analysis_type
    to_stdout = args.output == "-"
    stem = "stdin" if args.model == "-" else Path(args.model).stem
    output = Path(args.output) if args.output else Path(stem + ".csv")
    if not to_stdout:
        check_not_input(output, model.inputs)
    if not args.output and not args.force and output.exists():
        _error(
            f"{output} exists; pass --force to replace it, or -o to name another output"
        )
        return EXIT_INPUT
    try:
        units = parse_units(args.units)
    except ModelError as e:
        _error(f"--units: {e}")
        return EXIT_INPUT
    settings = {
        "t_end": args.t_end,
        "step": args.step,
        "time": args.time,
        "tol": args.tol,
        "max_iter": args.max_iter,
        "points": args.points,
        "h": args.h,
        "rho_inf": args.rho_inf,
        "adaptive": args.adaptive,
        "atol": args.atol,
        "rtol": args.rtol,
        "h_min": args.h_min,
        "jerk": args.jerk,
    }
    given = {k: v for k, v in settings.items() if v is not None}
    for key, value in given.items():
        try:
            check_settings({key: value})
        except ModelError as e:
            _error(f"--{key.replace('_', '-')}: {e}")
            return EXIT_INPUT
    _print_design(model)
    from camlink.progress import Progress

    total = 1 if kind == "equilibrium" else len(model.times(args.t_end, args.step))
    try:
        with Progress(total, f"{kind} of {model.name}", quiet=args.quiet) as bar:
            res = model.run(
                analysis=kind,
                output=None if to_stdout else output,
                on_rows=bar.update,
                **given,
            )
    except AnalysisError as e:
        _error(str(e))
        details = []
        if e.joints:
            details.append(f"joints involved: {', '.join(e.joints)}")
        # A residual of 0 means the error is not about residuals.
        if "residual" not in str(e) and e.residual > 0:
            details.append(f"largest residual: {e.residual:.3g}")
        if details:
            print(f"camlink: {'; '.join(details)}", file=sys.stderr)
        partial = e.results
        where = getattr(e, "output", None) or output
        if units != SI and getattr(e, "output", None) is not None:
            partial.save(where, units=units)
        if len(partial):
            print(
                f"camlink: {len(partial)} steps (t = {partial.t[0]:g} … {partial.t[-1]:g} s) "
                f"written to {where}",
                file=sys.stderr,
            )
        else:
            print(f"camlink: no step completed; {where} holds only the header", file=sys.stderr)
        return EXIT_ANALYSIS
    summary = res.summary
    if args.verbose:
        for body, (dx, dy, dphi) in summary.get("assembly_moves", []):
            print(
                f"camlink: assembly moved '{body}' by Δx = {dx:.6g} m, Δy = {dy:.6g} m, "
                f"Δφ = {dphi:.6g} rad",
                file=sys.stderr,
            )
    for w in summary.get("warnings", []):
        print(f"camlink: warning: {w}", file=sys.stderr)
    if args.verbose:
        counts = ", ".join(
            f"{k.replace('_', ' ')} {summary[k]}"
            for k in ("steps", "newton_iterations", "factorizations", "halvings")
            if k in summary
        )
        print(f"camlink: {kind}: {counts}", file=sys.stderr)
    if to_stdout:
        _write_csv_to_stdout(res.in_units(units))
        return EXIT_OK
    if units != SI:
        # The file was written in SI as the run went: write it over.
        res.in_units(units).save(output)
    if not args.quiet:
        what = f"{kind} of {model.name}"
        if kind == "equilibrium":
            print(f"{what}: at t = {res.t[0]:g} s, {len(res.channels)} channels → {output}")
        else:
            print(
                f"{what}: {len(res)} steps, t = {res.t[0]:g} … {res.t[-1]:g} s, "
                f"{len(res.channels)} channels → {output}"
            )
        if "energy_drift" in summary:
            print(
                f"  energy drift {summary['energy_drift']:.3g} J, "
                f"max |Φ| {summary['constraint_drift']:.3g}, "
                f"max |Φ_q q̇ − ν| {summary['velocity_drift']:.3g}"
            )
        from camlink.cam.jump import flight_summary

        flights = flight_summary(res, model.joints)
        if flights is not None:
            print(f"  {flights}")
    return EXIT_OK


def _load(args: argparse.Namespace) -> camlink.Model:
    """The model of `args.model`; ``-`` reads TOML (or JSON, if it starts
    with ``{``) from standard input, with data files in the current folder."""
    if args.model != "-":
        return camlink.load(args.model, acf=args.acf, allow_outside=args.allow_outside_data)
    text = sys.stdin.read()
    fmt = "json" if text.lstrip().startswith("{") else "toml"
    return camlink.loads(
        text, fmt, "<stdin>", base_dir=Path.cwd(), allow_outside=args.allow_outside_data
    )


def _write_csv_to_stdout(res: camlink.Results) -> None:
    """The results as CSV on standard output (``-o -``)."""
    import csv as _csv
    import io

    header = io.StringIO()
    _csv.writer(header, lineterminator="\n").writerow(["t", *res.channels])
    out = sys.stdout.buffer
    out.write(header.getvalue().encode())
    out.write(camlink._core.csv_rows(res.data))
    out.flush()


def _print_design(model: camlink.Model) -> None:
    """Prints the design findings of the curve contacts to stderr."""
    for f in model.design_check():
        print(f"camlink: {f['text']}", file=sys.stderr)


def _verdict(dof: int, redundant: bool, redundant_driver: bool = False) -> str:
    """The analyses that accept a model with `dof` free motions: dynamics
    and equilibrium accept redundant equations, and so do kinematics and
    inverse dynamics once the model is fully driven (they leave the
    redundant equations out), unless a driver is among them (over-driven)."""
    if redundant_driver:
        return (
            "over-driven: a driver fixes a motion the other equations fix already; "
            "remove it for kinematics and inverse dynamics"
        )
    if dof == 0 and not redundant:
        return "fully driven: ready for kinematics and inverse dynamics"
    if dof == 0:
        return (
            "fully driven, with redundant equations: ready for kinematics and inverse "
            "dynamics (the redundant equations are left out; their joints' reactions "
            "are not unique)"
        )
    plural = "s" if dof != 1 else ""
    return (
        f"{dof} free motion{plural}: ready for dynamics and equilibrium; "
        f"add {dof} driver{plural} for kinematics"
    )


def _cmd_check(args: argparse.Namespace) -> int:
    model = _load(args)
    r = model.check()
    design = model.design_check()
    from camlink.viz import fourbar

    loop = fourbar.summary(model)
    if args.json:
        print(json.dumps({"model": model.name, **r, "design": design, "four_bar": loop}, indent=2))
        return EXIT_OK
    print(f"model        {model.name} ({args.model})")
    print(f"bodies       {r['bodies']} moving (plus ground)")
    print(f"coordinates  {r['coordinates']}")
    print(f"equations    {r['equations']}")
    for c in r["released"]:
        print(f"  {c['text']}")
    joints = r["joints"]
    if joints:
        w_name = max(len(j["name"]) for j in joints)
        w_kind = max(len(j["kind"]) for j in joints)
        print("constraints")
        for j in joints:
            role = "driver" if j["driver"] else "joint"
            print(
                f"  {j['name']:<{w_name}}  {j['kind']:<{w_kind}}  "
                f"{j['equations']} eq  {role}"
            )
    for red in r["redundant"]:
        deps = " + ".join(f"{c:.3g}·{n}" for n, c in red["depends_on"])
        print(f"redundant    {red['equation']}" + (f" = {deps}" if deps else ""))
    dof = r["dof"]
    open_joints = r.get("open_joints", [])
    if open_joints:
        print(f"assembly     failed: largest |Φ| {r['residual']:.3g} after assembly")
        for name, worst in open_joints:
            print(f"  {name} stays open by {worst:.3g} (m or rad)")
        verdict = (
            "the placement cannot close the loops: check the dimensions and the "
            "joints above before adding drivers"
        )
        print(f"degrees of freedom  {dof} at the placement (rank of Φ_q {r['rank']}; {verdict})")
        for f in design:
            print(f"design       {f['text']}")
        return EXIT_OK
    verdict = _verdict(dof, bool(r["redundant"]), bool(r["redundant_drivers"]))
    print(f"degrees of freedom  {dof} (rank of Φ_q {r['rank']}; {verdict})")
    for k, motion in enumerate(r["free_motions"], 1):
        parts = ", ".join(f"{n} {c:+.2f}" for n, c in motion)
        print(f"  free motion {k}: {parts}")
    if loop is not None:
        _print_four_bar(loop)
    for f in design:
        print(f"design       {f['text']}")
    return EXIT_OK


def _print_four_bar(loop: dict[str, object]) -> None:
    """The four-bar lines of `camlink check`: class and transmission angle."""
    lengths = loop["lengths"]
    assert isinstance(lengths, dict)
    print(
        f"four-bar     {loop['crank']} (crank) – {loop['coupler']} (coupler) – {loop['rocker']} (rocker): "
        + ", ".join(f"{k} {v:.6g} m" for k, v in lengths.items())
        + f"; Grashof class: {loop['grashof']}"
    )
    mu = loop["transmission"]
    if isinstance(mu, list):
        lo, hi = (math.degrees(v) for v in mu)
        worst = max(abs(90 - lo), abs(90 - hi))
        print(
            f"transmission angle μ from {lo:.2f}° to {hi:.2f}° over the loop's reach "
            f"(worst {worst:.2f}° from 90°)"
        )


def _cmd_schema(_args: argparse.Namespace) -> int:
    print(json.dumps(camlink.json_schema(), indent=2))
    return EXIT_OK


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    # SIGTERM and SIGHUP stop a run as Ctrl-C does: the steps computed are
    # kept under the output's partial name. The CLI prints camlink's
    # warnings in its own words; a course file's, issued while loading by
    # every command, as `camlink: warning: …`.
    with stop_on_termination(), warnings.catch_warnings():
        warnings.simplefilter("ignore", camlink.CamlinkWarning)
        warnings.simplefilter("always", camlink.CourseFileWarning)
        warnings.showwarning = _show_warning
        return _main(args)


_python_showwarning = warnings.showwarning


def _show_warning(
    message: Warning | str,
    category: type[Warning],
    filename: str,
    lineno: int,
    file: TextIO | None = None,
    line: str | None = None,
) -> None:
    """Prints a `CourseFileWarning` as the CLI's other warnings; any other
    warning as Python does."""
    if issubclass(category, camlink.CourseFileWarning):
        print(f"camlink: warning: {message}", file=sys.stderr)
    else:
        _python_showwarning(message, category, filename, lineno, file, line)


def _main(args: argparse.Namespace) -> int:
    command = {
        "run": _cmd_run,
        "check": _cmd_check,
        "schema": _cmd_schema,
        "convert": cli_convert.run,
        **COMMANDS,
        "cam": cam_cli.run,
        "machine": machine_cli.run,
    }[args.command]
    try:
        return command(args)
    except ModelError as e:
        _error(str(e))
        return EXIT_INPUT
    except BrokenPipeError:
        # Output piped into a command that stopped reading (`| head`).
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return EXIT_OK
    except OSError as e:
        _error(_os_message(e))
        return EXIT_INPUT
    except KeyboardInterrupt as e:
        output = getattr(e, "output", None)
        kept = f"; the steps computed are in {output}" if output is not None else ""
        print(f"camlink: interrupted{kept}", file=sys.stderr)
        return 128 + (e.signum if isinstance(e, Terminated) else signal.SIGINT)
    except Exception as e:
        if os.environ.get("CAMLINK_TRACEBACK"):
            raise
        _error(f"{e}" if str(e).startswith("internal error") else f"internal error: {e!r}")
        return EXIT_INTERNAL


def run() -> NoReturn:
    """The `camlink` command: `main`, then the process ends with its exit
    code at once. Everything the command writes is closed by then; what is
    skipped is the interpreter's teardown, in which Arrow's native thread
    pools (Parquet output) can abort the process with SIGABRT ("terminate
    called without an active exception", apache/arrow#34314) after a run
    that has finished."""
    code = main()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)


if __name__ == "__main__":
    run()
