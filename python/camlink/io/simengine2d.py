"""simEngine2D course models (``.adm`` with a ``.acf`` analysis file).

Loading goes through :func:`camlink.load`; this module writes a course
model as a camlink model file. The mapping of every field and type is in
docs/simengine2d.md.
"""

from __future__ import annotations

import errno
import os
import warnings
from pathlib import Path

from camlink import _core
from camlink._core import ModelError
from camlink.io.output import check_not_input, replacing
from camlink.warn import CourseFileWarning

__all__ = ["convert"]

#: Model file formats by suffix.
_FORMATS = {".toml": "toml", ".json": "json"}


def convert(
    adm: str | os.PathLike[str],
    output: str | os.PathLike[str],
    acf: str | os.PathLike[str] | None = None,
) -> Path:
    """Writes the mechanism of `adm` (and the analysis of `acf`, default the
    ``.acf`` beside it) as a camlink model file; the format follows
    `output`'s suffix (``.toml`` or ``.json``). Returns the path written.

    The model is loaded first: a model that does not load is not converted
    (`ModelError` names the file, the entry and the field). Parts of the
    course file that are read past are issued as `CourseFileWarning`s.
    `output` is never one of the inputs (the ``.adm``, the ``.acf`` read),
    and it is written to a temporary file beside it and renamed over it in
    one step.
    """
    adm, out = Path(adm), Path(output)
    fmt = _FORMATS.get(out.suffix.lower())
    if fmt is None:
        raise ModelError(f"{out}: the converted model is a .toml or .json file")
    for p in (adm, None if acf is None else Path(acf)):
        if p is not None and not p.is_file():
            raise FileNotFoundError(errno.ENOENT, "no such file", str(p))
    beside = adm.with_suffix(".acf")
    check_not_input(out, [adm, acf if acf is not None else beside])
    text = _core.convert_adm(adm, fmt, acf)
    for w in _core.Model.load_adm(adm, acf).load_warnings:
        warnings.warn(w, CourseFileWarning, stacklevel=2)
    with replacing(out) as temp:
        temp.write_text(text, encoding="utf-8")
    return out
