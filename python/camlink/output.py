"""Result files written safely: never over an input, never half-written
under the final name, readable up to the last complete chunk whatever
stops the process.

A run writes its rows, chunk by chunk, to a temporary file beside the
output, named ``<stem>.partial-<random><suffix>``:

- CSV: the file itself, one ``write`` and flush per chunk; a reader drops
  an unfinished last line (`read_csv`).
- Parquet: an Arrow IPC stream (``.arrows``), one record batch per chunk,
  which any Arrow reader reads up to the last complete batch
  (`read_arrow_stream`); the Parquet file is written from it at the end,
  in row groups of `ROW_GROUP_ROWS` rows.

A CSV file starts with comment lines ``# key: value`` (the value as JSON)
before its header line: ``camlink`` (the version), ``model``, ``analysis``
and ``units`` (each channel's unit, ``""`` where the kind does not fix it);
a complete run ends it with ``# summary: {...}``. Parquet keeps the same
under its schema metadata key ``camlink``. `read_csv_metadata` reads them
back.

On success the temporary file is renamed over the output in one step (the
last of two runs writing the same output wins, whole); on an analysis
error or an interrupt it is renamed to ``<stem>.partial<suffix>``, so a
good earlier output is never replaced by a failed run. After a SIGKILL or
a power cut the temporary file stays, readable by `camlink.Results.load`.
"""

from __future__ import annotations

import csv
import io
import json
import os
import tempfile
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from camlink import _core
from camlink._core import ModelError

__all__ = [
    "ROW_GROUP_ROWS",
    "SUFFIXES",
    "CsvWriter",
    "ParquetWriter",
    "check_not_input",
    "kind_of",
    "open_writer",
    "partial_path",
]

#: File name suffixes results are written as.
SUFFIXES = {".csv": "csv", ".parquet": "parquet", ".pq": "parquet"}

#: Suffixes `camlink.Results.load` also reads: the journal of an
#: unfinished Parquet output.
READ_SUFFIXES = {**SUFFIXES, ".arrows": "arrows"}

#: Rows per Parquet row group.
ROW_GROUP_ROWS = 1 << 16


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


_UMASK = _umask()


def kind_of(path: Path, verb: str = "write", known: dict[str, str] = SUFFIXES) -> str:
    """``"csv"``, ``"parquet"`` (or ``"arrows"``) for `path`'s suffix;
    `ModelError` naming `verb` for any other."""
    try:
        return known[path.suffix.lower()]
    except KeyError:
        names = ", ".join(sorted(known))
        raise ModelError(
            f"cannot {verb} results {'to' if verb == 'write' else 'from'} '{path}': "
            f"unknown file type '{path.suffix or '(none)'}' (use one of {names})"
        ) from None


def partial_path(path: Path) -> Path:
    """Where the rows of a run that stopped early are kept:
    ``<stem>.partial<suffix>`` beside `path`."""
    return path.with_name(f"{path.stem}.partial{path.suffix}")


def check_not_input(path: Path, inputs: Iterable[str | os.PathLike[str]]) -> None:
    """Raises `ModelError` when the output `path` is (or links to) one of
    the run's `inputs` (the model file, its data files)."""
    real = os.path.realpath(path)
    for item in inputs:
        same = os.path.realpath(item) == real
        if not same and os.path.exists(path) and os.path.exists(item):
            same = os.path.samefile(path, item)
        if same:
            raise ModelError(
                f"output '{path}' is an input of the model ('{item}'); "
                "choose another output file name"
            )


class _Target:
    """A temporary file beside `path`, renamed over it on success."""

    def __init__(self, path: Path, suffix: str) -> None:
        self.path = path
        folder = path.parent
        fd, name = tempfile.mkstemp(
            prefix=f"{path.stem}.partial-", suffix=suffix, dir=folder if str(folder) else "."
        )
        os.close(fd)
        self.temp = Path(name)
        # mkstemp makes the file private; give it the mode a new file gets.
        os.chmod(self.temp, 0o666 & ~_UMASK)

    def finish(self, source: Path, complete: bool) -> Path:
        """Renames `source` to the output (`complete`) or to its partial
        name; returns where it went."""
        final = self.path if complete else partial_path(self.path)
        os.replace(source, final)
        return final


#: The comment lines of a results CSV start with this.
COMMENT = "# "


def _comment(key: str, value: object) -> bytes:
    """One metadata line: ``# key: <JSON>`` (JSON escapes line breaks)."""
    return f"{COMMENT}{key}: {json.dumps(value, default=str, ensure_ascii=False)}\n".encode()


class CsvWriter:
    """Writes the metadata comments of `head` (``camlink``, ``model``,
    ``analysis``) with each channel's unit, a header line, then each chunk
    of rows with one write and a flush: numbers in their shortest exact
    form, names quoted as CSV requires."""

    def __init__(self, path: Path, head: Mapping[str, Any] | None = None) -> None:
        self.path = path
        self._head = head or {}
        self._target = _Target(path, path.suffix)
        self._file = self._target.temp.open("wb")
        self._header = False

    def write(self, names: Sequence[str], rows: npt.NDArray[np.float64]) -> None:
        if not self._header:
            from camlink.units import unit

            for key in ("camlink", "model", "analysis"):
                if key in self._head:
                    self._file.write(_comment(key, self._head[key]))
            self._file.write(_comment("units", {n: unit(n) for n in names}))
            line = io.StringIO()
            csv.writer(line, lineterminator="\n").writerow(names)
            self._file.write(line.getvalue().encode())
            self._header = True
        if len(rows):
            self._file.write(_core.csv_rows(np.ascontiguousarray(rows, dtype=np.float64)))
        self._file.flush()

    def close(
        self, names: Sequence[str], complete: bool = True, metadata: Mapping[str, Any] | None = None
    ) -> Path:
        """Finishes the file, ending a complete one with the ``summary`` of
        `metadata`; returns where it is (the output, or its partial name
        when not `complete`)."""
        if not self._header and names:
            self.write(names, np.empty((0, len(names))))
        if complete and metadata is not None and "summary" in metadata:
            self._file.write(_comment("summary", metadata["summary"]))
        self._file.close()
        self.path = self._target.finish(self._target.temp, complete)
        return self.path


class ParquetWriter:
    """Journals each chunk as an Arrow record batch, then writes the
    Parquet file from the journal when the run ends."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self._target = _Target(path, ".arrows")
        self._sink: Any = None
        self._writer: Any = None

    def write(self, names: Sequence[str], rows: npt.NDArray[np.float64]) -> None:
        import pyarrow as pa

        batch = pa.record_batch([pa.array(rows[:, k]) for k in range(len(names))], names=list(names))
        if self._writer is None:
            self._sink = pa.OSFile(str(self._target.temp), "wb")
            self._writer = pa.ipc.new_stream(self._sink, batch.schema)
        self._writer.write_batch(batch)
        self._sink.flush()

    def close(
        self, names: Sequence[str], complete: bool = True, metadata: Mapping[str, Any] | None = None
    ) -> Path:
        """Writes the Parquet file from the journal, with `metadata` as JSON
        under the schema metadata key ``camlink``; returns where it is (the
        output, or its partial name when not `complete`)."""
        import pyarrow.parquet as pq

        if self._writer is None:
            self.write(names, np.empty((0, len(names))))
        self._writer.close()
        self._sink.close()
        table = read_arrow_stream(self._target.temp)
        if metadata is not None:
            text = json.dumps(metadata, default=str)
            table = table.replace_schema_metadata({"camlink": text})
        parquet = self._target.temp.with_suffix(self.path.suffix)
        # Simulated doubles seldom repeat: dictionary encoding costs time
        # and saves nothing.
        pq.write_table(table, parquet, row_group_size=ROW_GROUP_ROWS, use_dictionary=False)
        os.chmod(parquet, 0o666 & ~_UMASK)
        self.path = self._target.finish(parquet, complete)
        self._target.temp.unlink()
        return self.path


def read_arrow_stream(path: Path) -> Any:
    """The record batches of an Arrow IPC stream as one table, up to the
    last complete batch (a journal cut short by a crash)."""
    import pyarrow as pa

    batches = []
    schema = None
    with pa.memory_map(str(path)) as source:
        try:
            reader = pa.ipc.open_stream(source)
        except pa.ArrowInvalid as e:
            raise ModelError(f"cannot read results from '{path}': {e}") from None
        schema = reader.schema
        while True:
            try:
                batches.append(reader.read_next_batch())
            except StopIteration:
                break
            except (pa.ArrowInvalid, OSError):
                break
    return pa.Table.from_batches(batches, schema=schema)


class BackgroundWriter:
    """Hands each chunk to `writer` on a second thread, so that formatting
    and writing overlap the computation (which runs without the GIL). An
    error in the thread surfaces at the next `write` or at `close`."""

    def __init__(self, writer: CsvWriter | ParquetWriter) -> None:
        import queue
        import threading

        self._writer = writer
        self.path = writer.path
        self._queue: queue.Queue[tuple[Sequence[str], npt.NDArray[np.float64]] | None] = (
            queue.Queue(maxsize=4)
        )
        self._error: BaseException | None = None
        self._thread = threading.Thread(target=self._work, name="camlink-writer", daemon=True)
        self._thread.start()

    def _work(self) -> None:
        import queue

        while True:
            # A signal handler that raises (Ctrl-C, SIGTERM) while the main
            # thread is inside `Queue.put` can lose the wake-up of a
            # waiting `get`: wait in short slices so that a lost wake-up
            # costs 0.1 s, never a hang.
            try:
                item = self._queue.get(timeout=0.1)
            except queue.Empty:
                continue
            if item is None:
                return
            if self._error is None:
                try:
                    self._writer.write(*item)
                except BaseException as e:
                    self._error = e

    def _raise(self) -> None:
        if self._error is not None:
            error, self._error = self._error, None
            raise error

    def write(self, names: Sequence[str], rows: npt.NDArray[np.float64]) -> None:
        self._raise()
        self._queue.put((list(names), rows))

    def close(
        self, names: Sequence[str], complete: bool = True, metadata: Mapping[str, Any] | None = None
    ) -> Path:
        """Waits for the queued chunks, then closes the file as
        `CsvWriter.close` / `ParquetWriter.close` do."""
        self._queue.put(None)
        self._thread.join()
        failed = self._error is not None
        self.path = self._writer.close(
            names, complete=complete and not failed, metadata=metadata
        )
        self._raise()
        return self.path


def open_writer(
    path: str | os.PathLike[str], head: Mapping[str, Any] | None = None
) -> CsvWriter | ParquetWriter:
    """A writer for `path` (CSV or Parquet by suffix), its temporary file
    created now so that an unwritable folder fails before any work; a CSV
    starts with the metadata of `head` (Parquet gets its metadata at
    `close`)."""
    path = Path(path)
    kind = kind_of(path)
    if path.is_dir():
        raise IsADirectoryError(21, "is a directory", str(path))
    return CsvWriter(path, head) if kind == "csv" else ParquetWriter(path)


def read_csv_metadata(lines: Iterable[str]) -> dict[str, Any]:
    """The ``# key: <JSON>`` comment lines of a results CSV as a dict
    (lines that are not metadata are skipped)."""
    meta: dict[str, Any] = {}
    for line in lines:
        if not line.startswith(COMMENT):
            continue
        key, sep, value = line[len(COMMENT) :].partition(": ")
        if not sep:
            continue
        try:
            meta[key] = json.loads(value)
        except ValueError:
            continue
    return meta
