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
#: Rows shown in the head of a results table.
HEAD_ROWS = 5
#: Most rows a results plot draws: a longer run is drawn as the least and
#: greatest value of each channel over each of a quarter as many spans.
PLOT_ROWS = 2000


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
    from camlink.viz.drawing import draw

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
    """The head of the results table beside a plot of two channels.

    Results read lazily from a file read the head's rows only, and the
    whole of the channels plotted (and ``t``); the plot of a long run
    draws each channel's envelope (`PLOT_ROWS`)."""
    import pandas as pd

    from camlink.viz.plots import plot
    from camlink.viz.viewer import default_plots

    channels = results.channels[:HEAD_COLUMNS]
    timed = "t" in results
    # Adding 0.0 turns −0.0 into 0.0: the table shows no "-0".
    rows = results._head((["t"] if timed else []) + channels, HEAD_ROWS) + 0.0
    index = (pd.Index(rows[:, 0], name="t") if timed
             else pd.RangeIndex(len(rows), name="step"))
    shown = pd.DataFrame(rows[:, int(timed):], index=index, columns=channels)
    more = len(results.channels) - shown.shape[1]
    caption = html.escape(repr(results)) + (f" ({more} more channels)" if more > 0 else "")
    table = f"<p><code>{caption}</code></p>" + shown.to_html(float_format=lambda v: f"{v + 0.0:.6g}")
    if len(results) < 2:
        return table
    plotted = default_plots(results)[:2]
    picture = png(plot(_envelope(results, plotted), plotted, width=4.5, height=2.6), dpi=72)
    return _side_by_side(table, picture)


def _envelope(results: Results, channels: list[str]) -> Results:
    """`results` itself when it has at most `PLOT_ROWS` rows; otherwise
    results in memory holding, of ``t`` and `channels`, the first and last
    rows and the rows where each channel is least and greatest over each
    of ``PLOT_ROWS // 4`` spans, in time order: drawn at a plot's width,
    the same lines as every row."""
    import numpy as np

    n = len(results)
    if n <= PLOT_ROWS or "t" not in results:
        return results
    spans = PLOT_ROWS // 4
    width = n // spans
    whole = spans * width
    starts = np.arange(spans) * width
    picks = [np.array([0, n - 1]), np.arange(whole, n)]
    columns = [results[c] for c in channels]
    for y in columns:
        block = y[:whole].reshape(spans, width)
        picks += [starts + np.argmin(block, axis=1), starts + np.argmax(block, axis=1)]
    rows = np.unique(np.concatenate(picks))
    data = np.column_stack([results.t[rows], *(y[rows] for y in columns)])
    return results._like(["t", *channels], data)
