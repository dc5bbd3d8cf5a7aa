"""`camlink studio`: edit a model in the browser (docs/studio.md)."""

from __future__ import annotations

import argparse
from collections.abc import Callable
from pathlib import Path


def add_parser(
    sub: argparse._SubParsersAction[argparse.ArgumentParser],
) -> Callable[[argparse.Namespace], int]:
    """Registers the ``studio`` subcommand; returns its handler."""
    p = sub.add_parser(
        "studio",
        help="edit a model in the browser, the whole cycle re-solved on each drag",
        description="Serve an editor for MODEL (.toml or .json) on 127.0.0.1 and open it in the "
        "browser: drag joints and body points, move [parameters] sliders, and see the whole "
        "cycle re-solved; edit a motion program's segments, run analyses with progress and a "
        "stop. A cam design file (camlink cam's DESIGN.toml) opens with its segments, SVAJ, "
        "profile and limits analysed again on each edit. Save writes the file with its comments "
        "(the old file kept as MODEL.bak). "
        "The URL carries a random token; requests without it are refused.",
    )
    p.add_argument("model", metavar="MODEL", help="model file (.toml or .json) or cam design file")
    p.add_argument("--port", type=_port, default=0, help="port on 127.0.0.1 (default: any free port)")
    p.add_argument("--no-browser", action="store_true", help="print the URL, do not open a browser")
    return run


def _port(text: str) -> int:
    try:
        port = int(text)
    except ValueError:
        port = -1
    if not 0 <= port <= 65535:
        raise argparse.ArgumentTypeError(f"{text!r} is not a port number (0 to 65535)")
    return port


def run(args: argparse.Namespace) -> int:
    """Serves until interrupted; a bad model raises ModelError (exit 2)."""
    from camlink.studio import run as serve

    serve(Path(args.model), port=args.port, browser=not args.no_browser)
    return 0
