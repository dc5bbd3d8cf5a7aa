"""`_core.csv_rows` formats an array in any memory layout, and the CSV
writer hands it each column-major chunk as the binding delivered it,
without a copy."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

import camlink.io.output
from camlink import _core
from camlink.io.output import CsvWriter


def values(rows: int, width: int) -> npt.NDArray[np.float64]:
    """Random doubles over many magnitudes, with the special values."""
    rng = np.random.default_rng(7)
    a = rng.standard_normal((rows, width)) * 10.0 ** rng.integers(-12, 12, (rows, width))
    a[0, :4] = [np.nan, np.inf, -np.inf, -0.0]
    a[1, :3] = [0.3, 1.0, -2.0]
    return a


def parsed(text: bytes) -> npt.NDArray[np.float64]:
    return np.loadtxt(io.BytesIO(text), delimiter=",", ndmin=2)


@pytest.mark.parametrize("layout", ["C", "F", "strided"])
def test_csv_rows_reads_every_layout_row_by_row(layout: str) -> None:
    a = values(37, 9)
    if layout == "C":
        arg = np.ascontiguousarray(a)
    elif layout == "F":
        arg = np.asfortranarray(a)
    else:
        # Every other row and column of a larger Fortran-order array.
        big = np.asfortranarray(np.zeros((74, 18)))
        big[::2, ::2] = a
        arg = big[::2, ::2]
    text = _core.csv_rows(arg)
    lines = text.decode().splitlines()
    assert len(lines) == 37
    assert lines[1].split(",")[:3] == ["0.3", "1.0", "-2.0"]
    assert lines[0].split(",")[:4] == ["nan", "inf", "-inf", "0.0"]
    # Shortest round-trip text: every number reads back to the same double.
    back = parsed(text)
    assert back.shape == a.shape
    np.testing.assert_array_equal(back, a)


def test_csv_writer_formats_the_column_major_chunk_without_copying_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    seen: list[npt.NDArray[np.float64]] = []
    format_rows = _core.csv_rows

    def csv_rows(rows: npt.NDArray[np.float64]) -> bytes:
        seen.append(rows)
        return format_rows(rows)

    monkeypatch.setattr(camlink.io.output._core, "csv_rows", csv_rows)
    chunk = np.asfortranarray(values(1024, 5))
    writer = CsvWriter(tmp_path / "out.csv")
    names = ["t", "a.x", "a.y", "a.phi", "b.x"]
    writer.write(names, chunk)
    path = writer.close(names)
    assert len(seen) == 1
    assert seen[0] is chunk
    body = b"".join(line for line in path.read_bytes().splitlines(True) if line[:1] not in b"#t")
    np.testing.assert_array_equal(parsed(body), chunk)
