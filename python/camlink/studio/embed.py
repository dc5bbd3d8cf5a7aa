"""The studio served from a thread of this process (`ServedStudio`), and
in a Jupyter notebook without a widget library: `notebook(path)` (also
`camlink.studio.notebook`) serves the studio for a model or cam design
file from a thread of the kernel's process and returns a
`NotebookStudio`, which the notebook shows as an iframe of the studio's
page (its tokened URL on 127.0.0.1, so the browser must run on the
kernel's machine). The page is the one `camlink studio` serves, allowed
in a frame of a page of this machine only; edits, runs and saving work as
there. `stop()` stops the server (a saved notebook keeps the iframe,
which then shows nothing).
"""

from __future__ import annotations

import asyncio
import html
import threading
from pathlib import Path
from types import TracebackType
from typing import Any, Self

from camlink.studio import StudioServer

__all__ = ["NotebookStudio", "ServedStudio", "notebook"]

#: Height of the iframe (CSS px) unless asked for.
HEIGHT = 760


class ServedStudio:
    """A studio (`StudioServer`) on an event loop of its own in a thread of
    this process, until `stop()`; `doc` is the document it edits, `url`
    its page (with the token). With `embed`, its page may be framed by a
    page of this machine (a notebook's)."""

    def __init__(self, path: str | Path, port: int = 0, embed: bool = False) -> None:
        self.server = StudioServer(path, port, embed=embed)
        self._loop = asyncio.new_event_loop()
        self._thread = threading.Thread(target=self._loop.run_forever, name="camlink-studio",
                                        daemon=True)
        self._thread.start()
        self.stopped = False
        try:
            start = asyncio.run_coroutine_threadsafe(self.server.start(), self._loop)
            self.url = start.result(60)
        except BaseException:
            self._end_loop()
            raise

    @property
    def doc(self) -> Any:
        """The document edited (`camlink.studio.document.Document`, or a
        cam design's `camlink.studio.cam.CamDocument`)."""
        return self.server.doc

    def __repr__(self) -> str:
        state = "stopped" if self.stopped else self.url
        return f"<camlink studio for {self.doc.path.name}: {state}>"

    def stop(self) -> None:
        """Stops the server (open pages are told so); again, nothing."""
        if self.stopped:
            return
        self.stopped = True
        try:
            asyncio.run_coroutine_threadsafe(self.server.stop(), self._loop).result(60)
        finally:
            self._end_loop()

    def _end_loop(self) -> None:
        self._loop.call_soon_threadsafe(self._loop.stop)
        self._thread.join(10)
        self._loop.close()

    def __enter__(self) -> Self:
        return self

    def __exit__(self, kind: type[BaseException] | None, value: BaseException | None,
                 tb: TracebackType | None) -> None:
        self.stop()


class NotebookStudio(ServedStudio):
    """A studio served from a thread of this process, shown in a notebook
    as an iframe of its page, `height` CSS px high."""

    def __init__(self, path: str | Path, port: int = 0, height: int = HEIGHT) -> None:
        self.height = int(height)
        super().__init__(path, port, embed=True)

    def _repr_html_(self) -> str:
        if self.stopped:
            return f"<p>camlink studio for {html.escape(self.doc.path.name)}: stopped</p>"
        return (f'<iframe src="{html.escape(self.url, quote=True)}" title="camlink studio" '
                f'width="100%" height="{self.height}" style="border: 1px solid #ccc"></iframe>')


def notebook(path: str | Path, *, port: int = 0, height: int = HEIGHT) -> NotebookStudio:
    """The studio for the model or cam design file `path`, served on
    127.0.0.1 (`port`, default any free one) from a thread of this
    process; shown in a notebook as an iframe `height` px high. Call
    ``.stop()`` when done."""
    return NotebookStudio(path, port, height)
