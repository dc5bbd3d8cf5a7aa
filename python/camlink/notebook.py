"""How models and results show themselves in Jupyter (`_repr_html_`).

A model shows a summary table beside its drawing; results show the head of
their table beside a small plot. Pictures are inline PNG (base64), so a
saved notebook keeps them.
"""

from __future__ import annotations

import base64
import html
import io
from typing import TYPE_CHECKING

from camlink._core import ModelError

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from camlink.model import Model
    from camlink.results import Results

__all__ = ["model_html", "png", "results_html"]

#: Channels shown in the head of a results table.
HEAD_COLUMNS = 8


def png(fig: Figure, dpi: int = 72) -> str:
    """The figure as an inline ``<img>`` (PNG, base64)."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    data = base64.b64encode(buf.getvalue()).decode("ascii")
    return f'<img src="data:image/png;base64,{data}"/>'


def _side_by_side(left: str, right: str) -> str:
    return (
        '<div style="display:flex;gap:16px;align-items:flex-start">'
        f"<div>{left}</div><div>{right}</div></div>"
    )


def model_html(model: Model) -> str:
    """A table of the model (bodies, joints with kinds, degrees of freedom)
    beside its drawing."""
    from camlink.drawing import draw

    check = model.check()
    rows = [
        ("model", model.name),
        ("bodies", f"{check['bodies']} moving + ground"),
        ("degrees of freedom", str(check["dof"])),
        ("analysis", model.analysis_type),
    ]
    rows += [(f"{'driver' if j['driver'] else 'joint'} {j['name']}",
              f"{j['kind']} ({' – '.join(j['bodies'])})") for j in model.joints]
    table = "<table>" + "".join(
        f"<tr><th style='text-align:left'>{html.escape(k)}</th><td style='text-align:left'>"
        f"{html.escape(v)}</td></tr>" for k, v in rows
    ) + "</table>"
    try:
        picture = png(draw(model, width=4.5), dpi=72)
    except (ModelError, KeyError, ValueError) as e:
        picture = f"<p>(no drawing: {html.escape(str(e))})</p>"
    return _side_by_side(table, picture)


def results_html(results: Results) -> str:
    """The head of the results table beside a plot of two channels."""
    from camlink.plots import plot
    from camlink.viewer import default_plots

    frame = results.to_pandas()
    shown = frame.iloc[:, :HEAD_COLUMNS].head()
    more = len(results.channels) - shown.shape[1]
    caption = html.escape(repr(results)) + (f" ({more} more channels)" if more > 0 else "")
    table = f"<p><code>{caption}</code></p>" + shown.to_html(float_format=lambda v: f"{v:.6g}")
    if len(results) < 2:
        return table
    channels = default_plots(results)
    picture = png(plot(results, channels[:2], width=4.5, height=2.6), dpi=72)
    return _side_by_side(table, picture)
