"""`camlink synth`: solve a linkage synthesis problem (docs/synthesis.md) and
write each solution as a model file."""

from __future__ import annotations

import argparse
import json
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any


def add_parser(
    sub: argparse._SubParsersAction[argparse.ArgumentParser],
) -> Callable[[argparse.Namespace], int]:
    """Registers the ``synth`` subcommand; returns its handler."""
    p = sub.add_parser(
        "synth",
        help="synthesise a four-bar or slider-crank from poses, a function or a path and write it "
        "as a model file",
        description="Solve the [synthesis] problem of PROBLEM (motion generation through two or "
        "three poses, four or five by Burmester theory, slider-cranks, function generation by "
        "Freudenstein's equation, path generation, dead-centre synthesis or cognates), check every "
        "solution (Grashof class, "
        "transmission angle, branch, order) and write each as DIR/<name>.toml, a model that "
        "`camlink run` runs. The report goes to standard output.",
    )
    p.add_argument("problem", metavar="PROBLEM", help="synthesis problem file (.toml)")
    p.add_argument(
        "-o", "--output", metavar="DIR", required=True, help="folder for the models (made if missing)"
    )
    p.add_argument("--json", action="store_true", help="print the report as JSON")
    p.add_argument("--force", action="store_true", help="replace models that exist in DIR")
    p.add_argument("-q", "--quiet", action="store_true", help="print nothing on success")
    p.add_argument(
        "--atlas",
        metavar="PNG",
        help="draw the candidates' coupler curves against the targets (path and cognates problems)",
    )
    p.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="Dask scheduler (tcp://host:8786) to spread a path search's starts over; "
        "the result is the same as on local cores (default: local cores)",
    )
    p.add_argument(
        "--studio",
        action="store_true",
        help="then open the best solution (the first written) in `camlink studio`",
    )
    p.add_argument(
        "--no-browser",
        action="store_true",
        help="with --studio: print the studio's URL, do not open a browser",
    )
    return run


def run(args: argparse.Namespace) -> int:
    """Solves and writes; bad input raises ModelError or OSError (exit 2)."""
    from camlink import synth
    from camlink._core import ModelError
    from camlink.io.output import check_not_input, replacing

    if args.no_browser and not args.studio:
        raise ModelError("--no-browser goes with --studio")
    if args.atlas:
        # A PNG, never the problem file (nor its targets' CSV), checked before solving.
        atlas_path = Path(args.atlas)
        if atlas_path.suffix.lower() != ".png":
            raise ModelError(f"--atlas {args.atlas}: the atlas is a picture; name a .png file")
        check_not_input(atlas_path, [args.problem])
    if args.scheduler:
        from camlink.study.runner import connect

        client = connect(args.scheduler)
        try:
            result = synth.solve(args.problem, client=client)
        finally:
            client.close()
    else:
        result = synth.solve(args.problem)
    paths = synth.write(result, args.output, inputs=[args.problem], force=args.force)
    if args.atlas:
        from camlink.synth import atlas as synth_atlas

        figure = synth_atlas.atlas(result)
        with replacing(atlas_path) as temp:
            synth_atlas.save(figure, temp)
    if args.json:
        print(json.dumps({
            "kind": result.kind,
            "solutions": [
                {**_plain(s.report), "model": str(p)}
                for s, p in zip(result.solutions, paths, strict=True)
            ],
        }, indent=2))
    elif not args.quiet:
        print(synth.report_text(result))
        for p in paths:
            print(f"→ {p}")
    if args.studio:
        from camlink.studio import run as serve

        serve(paths[0], browser=not args.no_browser)
    return 0


def _plain(value: Any) -> Any:
    """The report as plain dicts and lists, for JSON."""
    if isinstance(value, Mapping):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, tuple):
        return [_plain(v) for v in value]
    return value
