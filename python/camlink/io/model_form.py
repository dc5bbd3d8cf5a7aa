"""A camlink model file rewritten in frame form or in global form.

In frame form a body's points are given in its frame (``points``), in
global form by their global positions at the initial instant
(``global_points``); docs/model-files.md, "Converting between the forms",
describes the rewrite, which the Rust core does (`camlink._core.convert_model`).
Here the text is written safely: never over the model file, never over
an existing file unless asked, through a temporary file renamed into place.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Literal

from camlink import _core
from camlink._core import ModelError
from camlink.io.output import check_not_input, replacing

__all__ = ["FORMS", "convert_form"]

#: The forms a model file can be written in.
FORMS = ("global", "frame")


def convert_form(
    model: str | os.PathLike[str],
    output: str | os.PathLike[str],
    form: Literal["global", "frame"],
    *,
    force: bool = False,
    allow_outside: bool = False,
) -> list[str]:
    """Writes the model file `model` in `form` to `output` (the same format,
    ``.toml`` or ``.json``); returns the names of the bodies rewritten.

    Raises `ModelError` when the model does not load, when `output` has
    another format, is the model or one of its data files, or exists and
    `force` is not set. Comments and every value not rewritten stay as
    written.
    """
    src, out = Path(model), Path(output)
    if form not in FORMS:
        raise ModelError(f"unknown form '{form}' (expected 'global' or 'frame')")
    if out.suffix.lower() != src.suffix.lower():
        raise ModelError(
            f"{out}: the converted model keeps the format of {src} "
            f"(name it with {src.suffix or 'its suffix'})"
        )
    if out.exists() and not force:
        raise ModelError(f"{out} exists; pass --force to replace it, or name another output")
    data_files = _core.Model.load(src, allow_outside).data_files
    check_not_input(out, [src, *data_files])
    text, bodies = _core.convert_model(src, form, allow_outside)
    with replacing(out) as temp:
        temp.write_text(text, encoding="utf-8")
    return bodies
