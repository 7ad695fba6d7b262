"""``make lint``'s type check: mypy's error count per file may go down, never up.

Runs mypy with the ``[tool.mypy]`` settings of ``pyproject.toml`` (the package ``img2logo``),
counts its errors per file and compares the counts with the committed baseline,
``tools/mypy-baseline.txt`` (a line per file: ``<errors> <path>``):

- a file with more errors than its baseline line (a file not listed has 0) fails the check:
  its errors are printed and the exit status is 1;
- a file with fewer errors passes, and the check says ``lower the baseline to N`` (N the new
  total): ``python tools/mypy_baseline.py --write`` writes the new counts, to commit with the fix;
- a mypy that does not run (a configuration error, a crash: status 2) fails with its output.

The baseline only shrinks: ``--write`` refuses to raise any count of an existing baseline
(``--write --force`` does, e.g. for a new mypy version).
"""

from __future__ import annotations

import argparse
import re
import subprocess
import sys
from collections import Counter
from collections.abc import Iterable, Mapping
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BASELINE = ROOT / "tools" / "mypy-baseline.txt"
HEADER = (
    "# mypy's errors per file (tools/mypy_baseline.py, run by make lint): a count may go down, never up.\n"
    "# Regenerate after lowering: python tools/mypy_baseline.py --write\n"
)
#: ``path:line: error: message  [code]`` (also ``path:line:column:`` with show_column_numbers).
_ERROR = re.compile(r"^(?P<path>[^:\n]+\.pyi?):\d+(?::\d+)?: error: ")


def count_errors(output: str) -> Counter[str]:
    """Errors per file in mypy's output (notes and the summary line are not errors)."""
    return Counter(m["path"].replace("\\", "/") for line in output.splitlines() if (m := _ERROR.match(line)))


def read_baseline(text: str) -> dict[str, int]:
    """The baseline's counts: ``<errors> <path>`` a line, ``#`` comments and blank lines skipped."""
    counts: dict[str, int] = {}
    for number, line in enumerate(text.splitlines(), 1):
        if not line.strip() or line.startswith("#"):
            continue
        count, _, path = line.strip().partition(" ")
        if not count.isdigit() or not path:
            raise ValueError(f"{BASELINE.name} line {number}: expected '<errors> <path>', got {line!r}")
        counts[path.strip()] = int(count)
    return counts


def format_baseline(counts: Mapping[str, int]) -> str:
    """The baseline file's text: files with errors, by path."""
    return HEADER + "".join(f"{n} {path}\n" for path, n in sorted(counts.items()) if n > 0)


def compare(now: Mapping[str, int], baseline: Mapping[str, int]) -> tuple[list[str], list[str]]:
    """The files whose count rose (``path: N errors, baseline M``) and those whose count went down."""
    rose, fell = [], []
    for path in sorted(set(now) | set(baseline)):
        n, b = now.get(path, 0), baseline.get(path, 0)
        if n > b:
            rose.append(f"{path}: {_errors(n)}, baseline {b}")
        elif n < b:
            fell.append(f"{path}: {_errors(n)}, baseline {b}")
    return rose, fell


def _errors(n: int) -> str:
    return f"{n} error" if n == 1 else f"{n} errors"


def _errors_of(output: str, paths: Iterable[str]) -> list[str]:
    wanted = set(paths)
    return [line for line in output.splitlines() if (m := _ERROR.match(line)) and m["path"] in wanted]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", action="store_true", help="write the counts of this run as the baseline")
    parser.add_argument("--force", action="store_true", help="with --write: also when a count rose")
    args = parser.parse_args(argv)
    run = subprocess.run([sys.executable, "-m", "mypy"], cwd=ROOT, capture_output=True, text=True, check=False)
    if run.returncode not in (0, 1):
        sys.stdout.write(run.stdout + run.stderr)
        print(f"mypy: did not run (status {run.returncode})", file=sys.stderr)
        return 1
    now = count_errors(run.stdout)
    baseline = read_baseline(BASELINE.read_text(encoding="utf-8")) if BASELINE.exists() else {}
    rose, fell = compare(now, baseline)
    total, allowed = sum(now.values()), sum(baseline.values())
    if args.write:
        if rose and baseline and not args.force:
            print("mypy: not written, counts rose (--force to accept them):", *rose, sep="\n  ", file=sys.stderr)
            return 1
        BASELINE.write_text(format_baseline(now), encoding="utf-8")
        print(f"mypy: wrote {BASELINE.relative_to(ROOT)}: {total} errors in {len(now)} files")
        return 0
    if rose:
        rising = [line.split(":", 1)[0] for line in rose]
        print(*_errors_of(run.stdout, rising), sep="\n")
        print(
            f"mypy: {total} errors, baseline {allowed}; more than the baseline in:", *rose, sep="\n  ", file=sys.stderr
        )
        return 1
    if fell:
        print(f"mypy: {total} errors, baseline {allowed}: lower the baseline to {total}", *fell, sep="\n  ")
        print("  (python tools/mypy_baseline.py --write, and commit tools/mypy-baseline.txt)")
    else:
        print(f"mypy: {total} errors, as the baseline")
    return 0


if __name__ == "__main__":
    sys.exit(main())
