"""A results file read back on access: what `camlink.Results` holds instead
of its rows when a run wrote them to a file (``output=``).

- Parquet (`ParquetColumns`): a channel is read through pyarrow's column
  reads of the byte ranges it needs, read from the open file (not mapped
  into memory: a mapped file cut short while it is read kills the
  process with SIGBUS).
- CSV (`CsvColumns`): pyarrow's CSV reader parses, block by block, the
  byte range of the rows that the writer recorded (after the header line),
  keeping only the channels asked for.

A source holds its file open from when it is made (one file descriptor,
closed when the source is garbage-collected) and reads through it: results
keep reading the file their run wrote even after another run replaced the
output, or the file was deleted. A file changed in
place (its size or modification time differ, before or after a read)
raises `ModelError` instead of returning other numbers.
"""

from __future__ import annotations

import io
import os
import weakref
from collections.abc import Callable
from pathlib import Path
from typing import Any, Protocol, TypeVar

import numpy as np
import numpy.typing as npt

from camlink._core import ModelError

__all__ = ["ColumnSource", "CsvColumns", "ParquetColumns"]

T = TypeVar("T")

#: Bytes of CSV text parsed at a time (more for rows longer than an
#: eighth of it): pyarrow's reader holds several times a block per column.
CSV_BLOCK = 256 << 10


class ColumnSource(Protocol):
    """Where the rows of lazily read `camlink.Results` are."""

    #: The file.
    path: Path
    #: Number of rows (time steps).
    rows: int

    def column(self, name: str) -> npt.NDArray[np.float64]:
        """One channel's values, a new array."""
        ...

    def table(self, names: list[str]) -> npt.NDArray[np.float64]:
        """All rows, columns in the order of `names`, a new array."""
        ...

    def head(self, names: list[str], n: int) -> npt.NDArray[np.float64]:
        """The first `n` rows (fewer when the file has fewer), columns in
        the order of `names`, reading no more of the file than they need."""
        ...


def _fill(out: npt.NDArray[np.float64], column: Any) -> None:
    """Copies an Arrow double column (an array or a chunked array) into
    `out`. pyarrow's own ``to_numpy`` would import pandas, seconds the
    first time."""
    start = 0
    for chunk in getattr(column, "chunks", [column]):
        n = len(chunk)
        if chunk.null_count:
            values = np.asarray(chunk.to_numpy(zero_copy_only=False), dtype=np.float64)
        else:
            values = np.frombuffer(
                chunk.buffers()[1], dtype=np.float64, count=n, offset=chunk.offset * 8
            )
        out[start : start + n] = values
        start += n


class _File:
    """A file held open, read after checking that it did not change."""

    def __init__(self, path: Path) -> None:
        self.path = path
        try:
            fd = os.open(path, os.O_RDONLY)
        except OSError as e:
            raise ModelError(f"cannot read results from '{path}': {e.strerror}") from None
        weakref.finalize(self, os.close, fd)
        self._fd = fd
        self._stamp = self._now()

    def _now(self) -> tuple[int, int]:
        st = os.fstat(self._fd)
        return (st.st_size, st.st_mtime_ns)

    def check(self) -> None:
        """`ModelError` when the file changed since the source was made."""
        if self._now() != self._stamp:
            raise ModelError(
                f"cannot read results from '{self.path}': the file changed after the "
                "run wrote it; load it again with camlink.Results.load"
            )

    def guarded(self, read: Callable[[], T]) -> T:
        """`read()`, with the file checked before and after: `ModelError`
        when it changed, so that a read the change cut short or mixed up
        is not returned (nor its own error raised)."""
        self.check()
        try:
            out = read()
        except (ValueError, OSError, EOFError):
            self.check()
            raise
        self.check()
        return out


class ParquetColumns(_File):
    """A Parquet results file, read one channel at a time."""

    def __init__(self, path: Path) -> None:
        super().__init__(path)
        #: Number of rows, from the file's footer.
        self.rows = self.guarded(lambda: self._file().metadata.num_rows)

    def _file(self) -> Any:
        import pyarrow.parquet as pq

        return pq.ParquetFile(_Range(self._fd, 0, self._stamp[0]))

    def column(self, name: str) -> npt.NDArray[np.float64]:
        return self.table([name])[:, 0]

    def table(self, names: list[str]) -> npt.NDArray[np.float64]:
        def read() -> npt.NDArray[np.float64]:
            table = self._file().read(columns=names)
            out = np.empty((table.num_rows, len(names)))
            for k in range(len(names)):
                _fill(out[:, k], table.column(k))
            return out

        return self.guarded(read)

    def head(self, names: list[str], n: int) -> npt.NDArray[np.float64]:
        def read() -> npt.NDArray[np.float64]:
            out = np.empty((min(n, self.rows), len(names)))
            if not len(out):
                return out
            done = 0
            for batch in self._file().iter_batches(batch_size=len(out), columns=names):
                m = min(batch.num_rows, len(out) - done)
                for k in range(len(names)):
                    _fill(out[done : done + m, k], batch.column(k).slice(0, m))
                done += m
                if done == len(out):
                    break
            return out

        return self.guarded(read)


class CsvColumns(_File):
    """A results CSV whose rows lie between byte `start` (after the header
    line) and byte `end` (after the last row)."""

    def __init__(self, path: Path, names: list[str], start: int, end: int, rows: int) -> None:
        super().__init__(path)
        self._names = list(names)
        self._start = start
        self._end = end
        self.rows = rows

    def column(self, name: str) -> npt.NDArray[np.float64]:
        return self.table([name])[:, 0]

    def table(self, names: list[str]) -> npt.NDArray[np.float64]:
        return self.guarded(lambda: self._read(names, self.rows))

    def head(self, names: list[str], n: int) -> npt.NDArray[np.float64]:
        return self.guarded(lambda: self._read(names, min(n, self.rows)))

    def _read(self, names: list[str], wanted: int) -> npt.NDArray[np.float64]:
        """The first `wanted` rows of the channels `names`."""
        import pyarrow as pa
        import pyarrow.csv as pacsv

        out = np.empty((wanted, len(names)))
        if wanted == 0:
            return out
        # Parsed block by block from the file (not mapped: touching every
        # page of a large CSV would count it all as resident memory).
        block = max(CSV_BLOCK, 8 * (self._end - self._start) // self.rows)
        rows = io.BufferedReader(_Range(self._fd, self._start, self._end), block)
        reader = pacsv.open_csv(
            rows,
            read_options=pacsv.ReadOptions(column_names=self._names, block_size=block),
            convert_options=pacsv.ConvertOptions(
                column_types={n: pa.float64() for n in self._names},
                include_columns=names,
                null_values=[],
                strings_can_be_null=False,
            ),
        )
        done = 0
        for batch in reader:
            n = batch.num_rows
            if done + n > self.rows:
                break
            m = min(n, wanted - done)
            for k in range(len(names)):
                _fill(out[done : done + m, k], batch.column(k).slice(0, m))
            done += m
            if done == wanted < self.rows:
                return out
        if done != self.rows:
            raise ModelError(
                f"cannot read results from '{self.path}': {done if done < self.rows else 'more'} "
                f"rows where the run wrote {self.rows}"
            )
        return out


class _Range(io.RawIOBase):
    """Bytes `start` to `end` of the open file `fd`, read (and seekable)
    without moving the file's offset."""

    def __init__(self, fd: int, start: int, end: int) -> None:
        super().__init__()
        self._fd = fd
        self._start = start
        self._at = start
        self._end = end

    def readable(self) -> bool:
        return True

    def seekable(self) -> bool:
        return True

    def tell(self) -> int:
        return self._at - self._start

    def seek(self, offset: int, whence: int = io.SEEK_SET) -> int:
        base = {io.SEEK_SET: self._start, io.SEEK_CUR: self._at, io.SEEK_END: self._end}[whence]
        self._at = max(base + offset, self._start)
        return self._at - self._start

    def readinto(self, buffer: Any) -> int:
        n = min(len(buffer), self._end - self._at)
        if n <= 0:
            return 0
        data = os.pread(self._fd, n, self._at)
        buffer[: len(data)] = data
        self._at += len(data)
        return len(data)
