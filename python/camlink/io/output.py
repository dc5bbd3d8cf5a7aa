"""Result files written safely: never over an input, never half-written
under the final name, readable up to the last complete chunk whatever
stops the process.

A run writes its rows, chunk by chunk, to a temporary file beside the
output, named ``<stem>.partial-<random><suffix>``:

- CSV: the file itself, one ``write`` and flush per chunk; a reader drops
  an unfinished last line (`read_csv`).
- Parquet: the Parquet file itself, row group by row group as the chunks
  arrive (a hidden ``.<stem>.partial-<random><suffix>`` until the end), and
  beside it an Arrow IPC stream (``.arrows``), one record batch per chunk,
  which any Arrow reader reads up to the last complete batch
  (`read_arrow_stream`) should the process be killed before the Parquet
  file has its footer. Neither is read back: the journal is deleted when
  the Parquet file is complete.

Only the chunk being written (and, for Parquet, one row group) is held in
memory, whatever the length of the run.

A CSV file is a plain table: a header line of channel names, then one
line of numbers per step, which ``pandas.read_csv`` and spreadsheet
programs read as is. Its metadata goes to a JSON sidecar beside it,
``<name>.csv.json`` (`sidecar_path`): ``camlink`` (the version), ``model``,
``analysis``, ``units`` (each channel's unit), ``quantities`` (what each
channel measures, as the core names it: ``"velocity"``, ``"force"``…),
``value_units`` (``"mm,deg"`` for results saved in other units than SI),
``columns`` (the header's names), and for a complete run
``rows`` (the number of rows) and ``summary``. The sidecar is written at
the header (for a run that is killed) and again at the end, each time to
a temporary file renamed over it, and follows its CSV to the output or
partial name. CSV files of earlier versions carry the same keys as comment
lines ``# key: <JSON>`` around their rows, which `read_csv_metadata` reads.
Parquet keeps the metadata as JSON under its key-value metadata key
``camlink``, written when the file is closed (the summary is known only
then), which readers see as the schema metadata.

On success the temporary file is renamed over the output in one step (the
last of two runs writing the same output wins, whole); on an analysis
error or an interrupt it is renamed to ``<stem>.partial<suffix>``, so a
good earlier output is never replaced by a failed run. After a SIGKILL or
a power cut the temporary file stays, readable by `camlink.Results.load`
(for Parquet, the journal; the hidden Parquet file without its footer stays
too, and can be deleted).

Each writer's `columns` gives the finished file as a
`camlink.io.results_file.ColumnSource`, which `camlink.Results` reads lazily.
"""

from __future__ import annotations

import contextlib
import csv
import io
import json
import os
import tempfile
from collections.abc import Iterable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from camlink import _core
from camlink._core import ModelError
from camlink.io.results_file import ColumnSource, CsvColumns, ParquetColumns

__all__ = [
    "ROW_GROUP_BYTES",
    "ROW_GROUP_ROWS",
    "SUFFIXES",
    "BackgroundWriter",
    "CsvWriter",
    "ParquetWriter",
    "check_not_input",
    "kind_of",
    "open_writer",
    "partial_path",
    "read_arrow_stream",
    "read_csv_metadata",
    "replacing",
    "sidecar_path",
]

#: File name suffixes results are written as.
SUFFIXES = {".csv": "csv", ".parquet": "parquet", ".pq": "parquet"}

#: Suffixes `camlink.Results.load` also reads: the journal of an
#: unfinished Parquet output.
READ_SUFFIXES = {**SUFFIXES, ".arrows": "arrows"}

#: Most rows per Parquet row group.
ROW_GROUP_ROWS = 1 << 16

#: Most bytes of values per Parquet row group (fewer rows for a wide model).
ROW_GROUP_BYTES = 2 << 20


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


def sidecar_path(path: Path) -> Path:
    """Where the metadata of the results CSV `path` is:
    ``<name>.csv.json`` beside it."""
    return path.with_name(f"{path.name}.json")


def check_not_input(path: Path, inputs: Iterable[str | os.PathLike[str]]) -> None:
    """Raises `ModelError` when the output `path` (or, for a CSV, its
    metadata sidecar) is (or links to) one of the run's `inputs` (the model
    file, its data files)."""
    inputs = list(inputs)
    outputs = [path]
    if path.suffix.lower() == ".csv":
        outputs.append(sidecar_path(path))
    for out in outputs:
        real = os.path.realpath(out)
        for item in inputs:
            same = os.path.realpath(item) == real
            if not same and os.path.exists(out) and os.path.exists(item):
                same = os.path.samefile(out, item)
            if same:
                what = f"output '{path}'"
                if out != path:
                    what = f"the metadata file '{out}' of {what}"
                raise ModelError(
                    f"{what} is an input of the model ('{item}'); "
                    "choose another output file name"
                )


@contextlib.contextmanager
def replacing(path: str | os.PathLike[str]) -> Iterator[Path]:
    """A temporary file beside `path` (same suffix) for the block to write;
    renamed over `path` in one step when the block ends normally, deleted
    when it raises. A reader never sees a half-written `path`, and of two
    writers of the same `path` the last to finish wins, whole."""
    path = Path(path)
    if path.is_dir():
        raise IsADirectoryError(21, "is a directory", str(path))
    target = _Target(path, path.suffix)
    try:
        yield target.temp
    except BaseException:
        target.temp.unlink(missing_ok=True)
        raise
    target.finish(target.temp, True)


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


#: The comment lines of a results CSV of earlier versions start with this.
COMMENT = "# "


def _channel_meta(names: Sequence[str], quantities: Sequence[str]) -> dict[str, Any]:
    """The ``units`` (SI) and ``quantities`` of the channels `names`, from
    their `quantities` as the core gave them (none: no such keys)."""
    if not quantities:
        return {}
    from camlink.units import channel_units

    return {
        "units": channel_units(names, quantities),
        "quantities": dict(zip(names, quantities, strict=True)),
    }


def _write_json(path: Path, value: Mapping[str, Any]) -> None:
    """`value` as JSON at `path`, written to a temporary file beside it
    and renamed over it in one step."""
    target = _Target(path, ".json")
    try:
        target.temp.write_text(
            json.dumps(value, default=str, ensure_ascii=False, indent=1) + "\n", encoding="utf-8"
        )
    except BaseException:
        target.temp.unlink(missing_ok=True)
        raise
    target.finish(target.temp, True)


class CsvWriter:
    """Writes a header line of channel names, then each chunk of rows with
    one write and a flush: numbers in their shortest exact form, names
    quoted as CSV requires. The metadata (`head`'s ``camlink``, ``model``,
    ``analysis``, each channel's unit and quantity as the first `write`
    gives them) goes to the sidecar (`sidecar_path`) when the header is
    written, and again, with the row count and summary, at `close`."""

    def __init__(self, path: Path, head: Mapping[str, Any] | None = None) -> None:
        self.path = path
        self._head = head or {}
        self._quantities: list[str] = []
        self._target = _Target(path, path.suffix)
        self._file = self._target.temp.open("wb")
        self._header = False
        self._names: list[str] = []
        #: Rows written so far.
        self.rows = 0
        # Byte offsets of the rows: after the header line, after the last row.
        self._start = 0
        self._end = 0

    def _meta(self, metadata: Mapping[str, Any] | None) -> dict[str, Any]:
        """The sidecar's content: `metadata` (or the head with each
        channel's unit) and the header's names."""
        if metadata is not None:
            meta = dict(metadata)
        else:
            meta = {k: self._head[k] for k in ("camlink", "model", "analysis") if k in self._head}
            meta.update(_channel_meta(self._names, self._quantities))
        meta["columns"] = list(self._names)
        return meta

    def write(
        self, names: Sequence[str], rows: npt.NDArray[np.float64], quantities: Sequence[str] = ()
    ) -> None:
        """Writes `rows` of the channels `names`, whose `quantities` (as
        the core names them) the first call records."""
        if not self._header:
            self._names = list(names)
            self._quantities = list(quantities)
            _write_json(sidecar_path(self._target.temp), self._meta(None))
            line = io.StringIO()
            csv.writer(line, lineterminator="\n").writerow(names)
            self._file.write(line.getvalue().encode())
            self._header = True
            self._start = self._end = self._file.tell()
        if len(rows):
            # The column-major chunk as it came: `csv_rows` reads it row by
            # row through its strides, without a copy.
            text = _core.csv_rows(rows)
            self._file.write(text)
            self.rows += len(rows)
            self._end += len(text)
        self._file.flush()

    def close(
        self, names: Sequence[str], complete: bool = True, metadata: Mapping[str, Any] | None = None
    ) -> Path:
        """Finishes the file and its sidecar, which for a complete file
        holds `metadata` (with the ``summary``) and the row count; returns
        where the file is (the output, or its partial name when not
        `complete`)."""
        if not self._header and names:
            self.write(names, np.empty((0, len(names))))
        self._file.close()
        temp_meta = sidecar_path(self._target.temp)
        if complete:
            meta = self._meta(metadata)
            meta["rows"] = self.rows
        else:
            meta = self._meta(None)
        if self._header:
            _write_json(temp_meta, meta)
            final = self.path if complete else partial_path(self.path)
            os.replace(temp_meta, sidecar_path(final))
        self.path = self._target.finish(self._target.temp, complete)
        return self.path

    def columns(self) -> ColumnSource:
        """The written file (after `close`), parsed when first read."""
        return CsvColumns(self.path, self._names, self._start, self._end, self.rows)


class ParquetWriter:
    """Writes each chunk as it arrives, twice: into the Parquet file through
    `pyarrow.parquet.ParquetWriter` (chunks gathered into row groups of
    `ROW_GROUP_ROWS` rows or `ROW_GROUP_BYTES` bytes, whichever is fewer)
    and into the Arrow IPC journal, which stays readable if the process is
    killed. Neither is read back: `close` writes the last row group and the
    metadata, and deletes the journal. Memory stays that of one row group
    whatever the length of the run.

    The Parquet file is written to a hidden ``.<journal stem>.parquet``
    beside the journal until `close` renames it; files are LZ4-compressed
    (the fastest of pyarrow's codecs on simulated doubles, and as small as
    snappy) without dictionary encoding, and keep no Arrow schema (every
    column is a double), so that the ``camlink`` key-value metadata, known
    only at the end of the run, is what readers see as the schema
    metadata."""

    def __init__(self, path: Path, head: Mapping[str, Any] | None = None) -> None:
        self.path = path
        self._head = dict(head or {})
        self._target = _Target(path, ".arrows")
        journal = self._target.temp
        self._parquet = journal.with_name(f".{journal.stem}{path.suffix}")
        self._parquet.touch(mode=0o666 & ~_UMASK)
        self._schema: Any = None
        self._journal: Any = None
        self._journal_sink: Any = None
        self._writer: Any = None
        self._pending: list[Any] = []
        self._pending_rows = 0
        self._group_rows = ROW_GROUP_ROWS
        #: Rows written so far.
        self.rows = 0

    def _open(self, names: Sequence[str], quantities: Sequence[str] = ()) -> None:
        import pyarrow as pa
        import pyarrow.parquet as pq

        self._schema = pa.schema([(n, pa.float64()) for n in names])
        width = max(len(names), 1)
        self._group_rows = max(1, min(ROW_GROUP_ROWS, ROW_GROUP_BYTES // (8 * width)))
        self._head.update(_channel_meta(names, quantities))
        head = self._head
        # Buffered, flushed once per chunk: one system call instead of one
        # per column.
        self._journal_sink = pa.BufferedOutputStream(
            pa.OSFile(str(self._target.temp), "wb"), buffer_size=1 << 20
        )
        self._journal = pa.ipc.new_stream(
            self._journal_sink,
            self._schema.with_metadata({"camlink": json.dumps(head, default=str)}),
        )
        # Simulated doubles seldom repeat: dictionary encoding costs time
        # and saves nothing.
        self._writer = pq.ParquetWriter(
            str(self._parquet),
            self._schema,
            compression="lz4",
            use_dictionary=False,
            store_schema=False,
        )

    def write(
        self, names: Sequence[str], rows: npt.NDArray[np.float64], quantities: Sequence[str] = ()
    ) -> None:
        """Writes `rows` of the channels `names`, whose `quantities` (as
        the core names them) the first call records."""
        import pyarrow as pa

        if self._writer is None:
            self._open(names, quantities)
        if not len(rows):
            return
        batch = pa.record_batch(
            [_float_array(rows[:, k]) for k in range(len(names))], schema=self._schema
        )
        self._journal.write_batch(batch)
        self._journal_sink.flush()
        self._pending.append(batch)
        self._pending_rows += len(rows)
        self.rows += len(rows)
        if self._pending_rows >= self._group_rows:
            self._write_groups(whole_only=True)

    def _write_groups(self, whole_only: bool) -> None:
        """Writes the pending rows as row groups of `_group_rows` rows;
        with `whole_only`, a last shorter group stays pending."""
        import pyarrow as pa

        table = pa.Table.from_batches(self._pending, schema=self._schema)
        whole = table.num_rows - table.num_rows % self._group_rows
        cut = whole if whole_only else table.num_rows
        if cut:
            self._writer.write_table(table.slice(0, cut), row_group_size=self._group_rows)
        rest = table.slice(cut)
        self._pending = rest.to_batches() if rest.num_rows else []
        self._pending_rows = rest.num_rows

    def close(
        self, names: Sequence[str], complete: bool = True, metadata: Mapping[str, Any] | None = None
    ) -> Path:
        """Writes the last row group and, as the Parquet key-value metadata
        ``camlink``, `metadata` as JSON (for a run that stopped early, the
        head given at open with each channel's unit and quantity); returns where the
        file is (the output, or its partial name when not `complete`)."""
        if self._writer is None:
            self._open(names)
        if self._pending_rows:
            self._write_groups(whole_only=False)
        meta = dict(metadata) if metadata is not None else dict(self._head)
        self._writer.add_key_value_metadata({"camlink": json.dumps(meta, default=str)})
        self._writer.close()
        self._journal.close()
        self._journal_sink.close()
        self.path = self._target.finish(self._parquet, complete)
        self._target.temp.unlink()
        return self.path

    def columns(self) -> ColumnSource:
        """The written file (after `close`), read column by column."""
        return ParquetColumns(self.path)


def _stacked(chunks: list[npt.NDArray[np.float64]]) -> npt.NDArray[np.float64]:
    """Chunks of rows one after the other, in Fortran order (each channel
    contiguous); a single chunk as it is."""
    if len(chunks) == 1:
        return chunks[0]
    out = np.empty((sum(len(c) for c in chunks), chunks[0].shape[1]), order="F")
    start = 0
    for c in chunks:
        out[start : start + len(c)] = c
        start += len(c)
    return out


def _float_array(values: npt.NDArray[np.float64]) -> Any:
    """An Arrow double array over `values` (copied only when not
    contiguous). `pyarrow.array` would import pandas, seconds at the first
    chunk, to ask whether `values` is a pandas object."""
    import pyarrow as pa

    values = np.ascontiguousarray(values, dtype=np.float64)
    return pa.Array.from_buffers(pa.float64(), len(values), [None, pa.py_buffer(values)])


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
    error in the thread surfaces at the next `write` or at `close`.

    At most `QUEUED_CHUNKS` chunks wait; when the thread falls behind, the
    chunks waiting are written together, up to `BATCH_ROWS` rows, which
    spares the writer's cost per chunk."""

    #: Chunks that may wait for the thread.
    QUEUED_CHUNKS = 8

    #: Most rows written in one call when chunks are waiting.
    BATCH_ROWS = 8192

    def __init__(self, writer: CsvWriter | ParquetWriter) -> None:
        import queue
        import threading

        self._writer = writer
        self.path = writer.path
        self._queue: queue.Queue[
            tuple[Sequence[str], npt.NDArray[np.float64], Sequence[str]] | None
        ] = queue.Queue(maxsize=self.QUEUED_CHUNKS)
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
            names, rows, quantities = item
            waiting = [rows]
            end = False
            while sum(len(r) for r in waiting) < self.BATCH_ROWS:
                try:
                    more = self._queue.get_nowait()
                except queue.Empty:
                    break
                if more is None:
                    end = True
                    break
                waiting.append(more[1])
            if self._error is None:
                try:
                    self._writer.write(names, _stacked(waiting), quantities)
                except BaseException as e:
                    self._error = e
            if end:
                return

    def _raise(self) -> None:
        if self._error is not None:
            error, self._error = self._error, None
            raise error

    def write(
        self, names: Sequence[str], rows: npt.NDArray[np.float64], quantities: Sequence[str] = ()
    ) -> None:
        self._raise()
        self._queue.put((list(names), rows, list(quantities)))

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

    def columns(self) -> ColumnSource:
        """The written file (after `close`), read lazily."""
        return self._writer.columns()


def open_writer(
    path: str | os.PathLike[str], head: Mapping[str, Any] | None = None
) -> CsvWriter | ParquetWriter:
    """A writer for `path` (CSV or Parquet by suffix), its temporary file
    created now so that an unwritable folder fails before any work. The
    metadata of `head` goes to a CSV's sidecar with the header (Parquet
    gets its metadata at `close`, the `head` for a run that stopped early);
    the first `write` gives each channel's quantity, hence its unit."""
    path = Path(path)
    kind = kind_of(path)
    if path.is_dir():
        raise IsADirectoryError(21, "is a directory", str(path))
    return CsvWriter(path, head) if kind == "csv" else ParquetWriter(path, head)


def read_csv_metadata(lines: Iterable[str]) -> dict[str, Any]:
    """The ``# key: <JSON>`` comment lines of a results CSV of earlier
    versions as a dict (lines that are not metadata are skipped)."""
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
