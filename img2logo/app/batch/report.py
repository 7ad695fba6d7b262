"""The outcome of a batch run (:func:`img2logo.app.batch.run.run_batch`): its rows, failures and summary table.

A :class:`BatchReport` holds one :class:`BatchRow` per image done and one
:class:`BatchFailure` per image that failed, in input order; :meth:`BatchReport.to_frame`
is the summary table (``SUMMARY_COLUMNS``), :meth:`BatchReport.summary_csv` its
``summary.csv``, :meth:`BatchReport.summary` the text table
the command line prints. :func:`report_of` builds the report from the worker's plain
results (:func:`img2logo.app.batch.pool.process_image`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["SUMMARY_COLUMNS", "BatchFailure", "BatchReport", "BatchRow", "csv_safe", "report_of"]

#: Columns of ``summary.csv`` and of :meth:`BatchReport.to_frame`.
SUMMARY_COLUMNS: tuple[str, ...] = ("image", "kind", "arcs", "levels", "similarity", "symmetry", "seconds", "error")


@dataclass(frozen=True)
class BatchRow:
    """One image abstracted.

    Attributes
    ----------
    image : str
        The input's file name.
    path : str
        The input's path, as given.
    kind : str
        The kind of input used (``"photo"``, ``"clipart"``, ``"drawing"``).
    arcs : int
        |A| of the final level.
    levels : int
        The number of levels A^0 ... A^final.
    similarity : float
        E^s of the final level (paper Eqn. 3), px.
    seconds : float
        Wall time for the image: loading, the abstraction and the files.
    outputs : tuple of str
        The files written.
    symmetry : str
        What ``symmetry=...`` decided: the mirror axis used and its score
        (``"90.0 deg, score 0.99"``), ``"free, score 0.57"`` when ``auto``
        found no axis good enough, or ``""`` when symmetry was not asked for.
    """

    image: str
    path: str
    kind: str
    arcs: int
    levels: int
    similarity: float
    seconds: float
    outputs: tuple[str, ...] = ()
    symmetry: str = ""


@dataclass(frozen=True)
class BatchFailure:
    """One image that failed: its file name, its path as given and the one-line error message."""

    image: str
    path: str
    message: str

    @property
    def line(self) -> str:
        """The message naming the file: ``"<path>: <message>"``, the path not repeated.

        The message is on one line (:func:`~img2logo.app.batch.pool.one_line`): a path with a
        newline is in it with a space there, and is given back as it is (printed escaped).
        """
        for said in (self.path, " ".join(self.path.split())):
            if self.message.startswith(said):
                return self.path + self.message[len(said) :]
        return f"{self.path}: {self.message}"


@dataclass(frozen=True)
class BatchReport:
    """The outcome of :func:`run_batch`.

    Attributes
    ----------
    rows : tuple of BatchRow
        The images done, in input order.
    failures : tuple of BatchFailure
        The images that failed, in input order.
    inputs : tuple of str
        Every input path, in input order (the order of :meth:`to_frame`).
    warnings : tuple of str
        ``"<image>: <message>"`` for every warning a run gave (e.g. an image
        downscaled), in input order. Not collected under a thread pool
        (Python's warning capture is not thread-safe): they are printed there.
    summary_path : str or None
        The ``summary.csv`` written, if any.
    """

    rows: tuple[BatchRow, ...]
    failures: tuple[BatchFailure, ...]
    inputs: tuple[str, ...] = ()
    warnings: tuple[str, ...] = ()
    summary_path: str | None = None

    @property
    def ok(self) -> bool:
        """True when no image failed."""
        return not self.failures

    def to_frame(self) -> pd.DataFrame:
        """The summary table: one row per image (failed ones with their ``error``), ``SUMMARY_COLUMNS``."""
        import pandas as pd

        table = pd.DataFrame.from_records(self._records(), columns=list(SUMMARY_COLUMNS))
        return table.astype({"arcs": "Int64", "levels": "Int64"})

    def summary_csv(self) -> str:
        """``summary.csv``: :meth:`to_frame` as CSV, a text cell a spreadsheet would run as a formula quoted.

        The text of ``csv_safe(report.to_frame()).to_csv(index=False, lineterminator="\\n",
        float_format="%.6g")``, written with the standard library's :mod:`csv` (pandas'
        import is a quarter of a second at the end of every batch): a missing cell empty,
        floats to 6 significant digits, quotes only where needed.
        """
        import csv
        import io

        text = io.StringIO()
        out = csv.writer(text, lineterminator="\n")
        out.writerow(SUMMARY_COLUMNS)
        for record in self._records():
            out.writerow([_csv_cell(column, record.get(column)) for column in SUMMARY_COLUMNS])
        return text.getvalue()

    def _records(self) -> list[dict[str, Any]]:
        """The table's rows in input order: one per image done, then failed ones with only ``image`` and ``error``."""
        keyed: list[tuple[str, dict[str, Any]]] = [
            (
                r.path,
                {
                    "image": r.image,
                    "kind": r.kind,
                    "arcs": r.arcs,
                    "levels": r.levels,
                    "similarity": r.similarity,
                    "symmetry": r.symmetry,
                    "seconds": r.seconds,
                    "error": "",
                },
            )
            for r in self.rows
        ]
        keyed += [(f.path, {"image": f.image, "error": f.message}) for f in self.failures]
        order = {path: i for i, path in enumerate(self.inputs)}
        keyed.sort(key=lambda item: order.get(item[0], len(order)))  # stable: rows before failures otherwise
        return [rec for _, rec in keyed]

    def summary(self, *, failures: bool = True) -> str:
        """The summary as a text table: image, kind, arcs, E^s, (symmetry,) seconds; then the failures.

        The symmetry column is shown when some image was run with ``symmetry``;
        the failures are left out when ``failures`` is False.
        """
        head: tuple[str, ...] = ("image", "kind", "arcs", "E^s (px)", "symmetry", "seconds")
        from ..._io import printable

        body: list[tuple[str, ...]] = [
            (printable(r.image), r.kind, str(r.arcs), f"{r.similarity:.2f}", r.symmetry, f"{r.seconds:.1f}")
            for r in self.rows
        ]
        align: tuple[str, ...] = ("<", "<", ">", ">", "<", ">")
        if not any(r.symmetry for r in self.rows):
            head, align, body = head[:4] + head[5:], align[:4] + align[5:], [row[:4] + row[5:] for row in body]
        widths = [max(len(row[i]) for row in [head, *body]) for i in range(len(head))]

        def line(row: Sequence[str]) -> str:
            return "  ".join(f"{cell:{a}{w}}" for cell, a, w in zip(row, align, widths, strict=True)).rstrip()

        lines = [line(head), line(["-" * w for w in widths]), *(line(row) for row in body)]
        total = len(self.rows) + len(self.failures)
        seconds = sum(r.seconds for r in self.rows)
        lines.append(f"{len(self.rows)} of {total} images done, {seconds:.1f} s of work")
        if self.failures and failures:
            lines.append(f"{len(self.failures)} failed:")
            lines.extend(f"  {printable(f.line)}" for f in self.failures)
        return "\n".join(lines)


def report_of(
    inputs: Sequence[Path], results: list[dict[str, Any]], written: Mapping[int, tuple[str, ...]], notes: list[str]
) -> BatchReport:
    """The :class:`BatchReport` of the results of :func:`~img2logo.app.batch.pool.process_image`, in input order."""
    rows, failures, warns = [], [], list(notes)
    for i, res in enumerate(results):
        warns.extend(f"{res['image']}: {w}" for w in res.get("warnings", ()))
        if "error" in res:
            failures.append(BatchFailure(res["image"], res["path"], res["error"]))
        else:
            rows.append(
                BatchRow(
                    res["image"],
                    res["path"],
                    res["kind"],
                    int(res["arcs"]),
                    int(res["levels"]),
                    float(res["similarity"]),
                    float(res["seconds"]),
                    written.get(i, ()),
                    res.get("symmetry", ""),
                )
            )
    return BatchReport(tuple(rows), tuple(failures), tuple(str(p) for p in inputs), tuple(warns))


#: First characters that make a spreadsheet read a CSV cell as a formula (CSV injection, OWASP).
_FORMULA_STARTS: tuple[str, ...] = ("=", "+", "-", "@", "\t", "\r")


def _csv_cell(column: str, value: Any) -> str:
    """One cell of ``summary.csv`` (:meth:`BatchReport.summary_csv`): as pandas writes it, formulas quoted."""
    if value is None:
        return ""
    if column in ("similarity", "seconds"):
        return "" if value != value else "%.6g" % value  # noqa: UP031 - pandas' float_format
    return str(_not_a_formula(value))


def _not_a_formula(value: Any) -> Any:
    """``value``, quoted by a leading ``'`` if it is text that a spreadsheet would run as a formula."""
    return f"'{value}" if isinstance(value, str) and value.startswith(_FORMULA_STARTS) else value


def csv_safe(table: pd.DataFrame) -> pd.DataFrame:
    """``table`` with every text cell that a spreadsheet would run as a formula quoted by a leading ``'``.

    An image named ``=HYPERLINK(...).png`` (or an error message naming it) is then
    shown as text when ``summary.csv`` is opened in a spreadsheet. Numbers are untouched.
    """
    safe = table.copy()
    for column in ("image", "kind", "symmetry", "error"):
        safe[column] = [_not_a_formula(v) for v in safe[column]]
    return safe
