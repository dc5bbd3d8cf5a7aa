"""A results file read back on access: what `camlink.Results` holds instead
of its rows when a run wrote them to a file (``output=``).

- Parquet (`ParquetColumns`): each channel is read when first asked for,
  through pyarrow's column reads of the memory-mapped file.
- CSV (`CsvColumns`): the rows are parsed, all at once, when first asked
  for, by pyarrow's CSV reader over the byte range of the rows that the
  writer recorded (between the header line and the ``# summary`` line).

The file's identity (device, inode, size, modification time) is taken when
the source is made; a read after the file was replaced or changed (another
run to the same output) raises `ModelError` instead of returning another
run's numbers.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Protocol

import numpy as np
import numpy.typing as npt

from camlink._core import ModelError

__all__ = ["ColumnSource", "CsvColumns", "ParquetColumns"]


class ColumnSource(Protocol):
    """Where the rows of lazily read `camlink.Results` are."""

    #: The file.
    path: Path
    #: Number of rows (time steps).
    rows: int
    #: True when single channels can be read without the others.
    by_column: bool

    def column(self, name: str) -> npt.NDArray[np.float64]:
        """One channel's values, a new array."""
        ...

    def table(self, names: list[str]) -> npt.NDArray[np.float64]:
        """All rows, columns in the order of `names`, a new array."""
        ...


def _fill(out: npt.NDArray[np.float64], column: Any) -> None:
    """Copies an Arrow double column (a chunked array) into `out`.
    pyarrow's own ``to_numpy`` would import pandas, seconds the first time."""
    start = 0
    for chunk in column.chunks:
        n = len(chunk)
        if chunk.null_count:
            values = np.asarray(chunk.to_numpy(zero_copy_only=False), dtype=np.float64)
        else:
            values = np.frombuffer(
                chunk.buffers()[1], dtype=np.float64, count=n, offset=chunk.offset * 8
            )
        out[start : start + n] = values
        start += n


def _stamp(path: Path) -> tuple[int, int, int, int]:
    st = os.stat(path)
    return (st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns)


class _File:
    """A file whose identity is checked before each read."""

    def __init__(self, path: Path) -> None:
        self.path = path
        try:
            self._stamp = _stamp(path)
        except OSError as e:
            raise ModelError(f"cannot read results from '{path}': {e.strerror}") from None

    def check(self) -> None:
        """Raises `ModelError` when the file is gone or is no longer the
        one the run wrote."""
        try:
            same = _stamp(self.path) == self._stamp
        except OSError as e:
            raise ModelError(
                f"cannot read results from '{self.path}': {e.strerror}; the run's "
                "results are read from its output file, which must stay in place"
            ) from None
        if not same:
            raise ModelError(
                f"cannot read results from '{self.path}': the file changed after the "
                "run wrote it (another run to the same output?); load it again with "
                "camlink.Results.load"
            )


class ParquetColumns(_File):
    """A Parquet results file, read one channel at a time."""

    by_column = True

    def __init__(self, path: Path) -> None:
        import pyarrow.parquet as pq

        super().__init__(path)
        #: Number of rows, from the file's footer.
        self.rows = pq.read_metadata(path).num_rows

    def column(self, name: str) -> npt.NDArray[np.float64]:
        import pyarrow.parquet as pq

        self.check()
        table = pq.ParquetFile(self.path, memory_map=True).read(columns=[name])
        out = np.empty(table.num_rows)
        _fill(out, table.column(0))
        return out

    def table(self, names: list[str]) -> npt.NDArray[np.float64]:
        import pyarrow.parquet as pq

        self.check()
        table = pq.ParquetFile(self.path, memory_map=True).read(columns=names)
        out = np.empty((table.num_rows, len(names)))
        for k in range(len(names)):
            _fill(out[:, k], table.column(k))
        return out


class CsvColumns(_File):
    """A results CSV whose rows lie between byte `start` (after the header
    line) and byte `end` (before the ``# summary`` line, if any)."""

    by_column = False

    def __init__(self, path: Path, names: list[str], start: int, end: int, rows: int) -> None:
        super().__init__(path)
        self._names = list(names)
        self._start = start
        self._end = end
        self.rows = rows

    def column(self, name: str) -> npt.NDArray[np.float64]:
        return self.table([name])[:, 0]

    def table(self, names: list[str]) -> npt.NDArray[np.float64]:
        import pyarrow as pa
        import pyarrow.csv as pacsv

        self.check()
        if self.rows == 0:
            return np.empty((0, len(names)))
        with pa.memory_map(str(self.path)) as source:
            source.seek(self._start)
            text = source.read_buffer(self._end - self._start)
            table = pacsv.read_csv(
                pa.BufferReader(text),
                read_options=pacsv.ReadOptions(column_names=self._names),
                convert_options=pacsv.ConvertOptions(
                    column_types={n: pa.float64() for n in self._names},
                    include_columns=names,
                    null_values=[],
                    strings_can_be_null=False,
                ),
            )
        if table.num_rows != self.rows:
            raise ModelError(
                f"cannot read results from '{self.path}': {table.num_rows} rows where "
                f"the run wrote {self.rows}"
            )
        out = np.empty((table.num_rows, len(names)))
        for k in range(len(names)):
            _fill(out[:, k], table.column(k))
        return out
