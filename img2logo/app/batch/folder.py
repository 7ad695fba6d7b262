"""The batch's output folder: what may be written there, its lock, and the list of the files img2logo wrote.

Before any work, :func:`check_targets` and :func:`check_output_folder` refuse a
folder a run cannot write or that holds an input. While a batch runs it holds
``OUTPUT_DIR/.img2logo-batch.lock`` (:func:`batch_lock`); ``OUTPUT_DIR/.img2logo-outputs``
(the manifest) lists the files img2logo wrote there, so that a later run removes only
its own outputs (:func:`remove_old_outputs`).
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterable, Iterator, Sequence
from pathlib import Path
from typing import NoReturn

from ...errors import InvalidParameterError

__all__ = [
    "LOCK_NAME",
    "MANIFEST_NAME",
    "batch_lock",
    "check_output_folder",
    "check_targets",
    "check_unlocked",
    "output_stems",
    "read_manifest",
    "remove_old_outputs",
    "write_manifest",
    "written_by_img2logo",
]


def check_targets(
    inputs: Sequence[Path], out_dir: Path, stems: Sequence[str], formats: Sequence[str], summary: bool
) -> None:
    """Before any work: the output folder can be written and no file a run writes is one of the inputs."""
    from ...export.writers import check_output_paths

    if out_dir.exists() and not out_dir.is_dir():
        raise InvalidParameterError(f"output folder {out_dir} is a file, not a folder")
    names = [f"{stem}.{fmt}" for stem in stems for fmt in formats] + (["summary.csv", "index.html"] if summary else [])
    targets = {str(out_dir / name): out_dir / name for name in names}
    try:
        check_output_paths(targets, inputs, {"output folder": out_dir})
    except InvalidParameterError as exc:
        raise InvalidParameterError(f"output folder {out_dir}: {exc}") from exc


def check_output_folder(inputs: Sequence[Path], out_dir: Path) -> None:
    """Refuse an output folder that holds an input (``img2logo batch in in``, also through a link).

    Its outputs (``<stem>.png``) would be taken as inputs by the next run of the same folder.
    """
    if not out_dir.is_dir():
        return
    for p in inputs:
        with contextlib.suppress(OSError):
            if os.path.samefile(p.parent if str(p.parent) else ".", out_dir):
                raise InvalidParameterError(
                    f"output folder {out_dir} is the folder of the input {p}: the next run would take its "
                    "outputs as inputs; give another folder"
                )


#: In the output folder: the lock of the batch writing it, and the list of the files img2logo wrote there.
LOCK_NAME = ".img2logo-batch.lock"
MANIFEST_NAME = ".img2logo-outputs"
_MANIFEST_HEADER = "# img2logo batch outputs/1: the files img2logo wrote in this folder, one a line\n"


@contextlib.contextmanager
def batch_lock(out_dir: Path) -> Iterator[None]:
    """Hold ``out_dir``'s batch lock while the block runs: a second batch on the same folder is refused.

    The lock is ``out_dir/.img2logo-batch.lock`` with :func:`fcntl.flock`, which
    the system releases when its process ends, however it ends: a lock file
    left by a killed batch is stale and taken over. The file is removed at the
    end (while still locked, and a batch that took a removed file tries again).
    The folder is created if missing, and removed again if the block leaves it empty.
    Where ``fcntl`` is missing (Windows) no lock is taken.

    Raises
    ------
    InvalidParameterError
        If another batch holds the lock: its process id is named.
    """
    try:
        import fcntl
    except ImportError:  # pragma: no cover - not POSIX
        yield
        return
    from ..._io import make_folders, os_message
    from ...errors import OutputError

    made: list[Path] = []  # the folders created
    lock = out_dir / LOCK_NAME
    fd, held = -1, False
    try:
        make_folders(out_dir, made)
        for _ in range(100):
            fd = _open_lock(lock, os.O_RDWR | os.O_CREAT)
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError:
                _refuse_locked(out_dir, fd)
            try:
                same = os.fstat(fd).st_ino == os.stat(lock).st_ino
            except FileNotFoundError:
                same = False
            if same:
                held = True
                break
            os.close(fd)  # the holder removed that file as we took it: take the new one
            fd = -1
        os.ftruncate(fd, 0)
        os.pwrite(fd, f"{os.getpid()}\n".encode(), 0)
    except OSError as exc:
        # Nothing of this batch stays behind (a full disk left an empty lock file): the lock it holds,
        # and the folders it made.
        if held:
            with contextlib.suppress(OSError):
                os.unlink(lock)
        if fd >= 0:
            os.close(fd)
        for folder in reversed(made):
            with contextlib.suppress(OSError):
                folder.rmdir()
        raise OutputError(os_message(lock, exc)) from exc
    try:
        yield
    finally:
        with contextlib.suppress(OSError):
            os.unlink(lock)
        os.close(fd)
        for folder in reversed(made):
            with contextlib.suppress(OSError):
                folder.rmdir()  # only if empty: nothing was written


def _open_lock(lock: Path, flags: int) -> int:
    """Open the lock file: never through a link, never a FIFO or a device, never a file with other names.

    A lock file planted as a link to (or a hard link of) a file of the user's would
    otherwise be written over; such a folder is refused.
    """
    import stat

    nofollow, nonblock = getattr(os, "O_NOFOLLOW", 0), getattr(os, "O_NONBLOCK", 0)
    try:
        fd = os.open(lock, flags | nofollow | nonblock, 0o666)
    except FileNotFoundError:
        raise
    except OSError as exc:
        if lock.is_symlink():
            raise InvalidParameterError(f"output folder {lock.parent}: {lock.name} is a link; remove it") from exc
        raise
    st = os.fstat(fd)
    if not stat.S_ISREG(st.st_mode) or st.st_nlink > 1:
        os.close(fd)
        raise InvalidParameterError(
            f"output folder {lock.parent}: {lock.name} is not a lock file img2logo made "
            "(not a regular file, or a file with other names); remove it"
        )
    return fd


def _refuse_locked(out_dir: Path, fd: int) -> NoReturn:
    """Close ``fd`` (the lock file another batch holds) and raise the error naming that batch's process."""
    try:
        owner = os.pread(fd, 32, 0).decode("ascii", "replace").strip()
    finally:
        os.close(fd)
    who = f" (process {owner})" if owner.isdigit() else ""
    raise InvalidParameterError(
        f"output folder {out_dir} is being written by another img2logo batch{who}; "
        "wait for it to end or give another folder"
    )


def check_unlocked(out_dir: Path) -> None:
    """Raise, without taking it, if another batch holds ``out_dir``'s lock (see :func:`batch_lock`)."""
    try:
        import fcntl

        fd = _open_lock(out_dir / LOCK_NAME, os.O_RDONLY)
    except (ImportError, FileNotFoundError):  # no lock file: no batch holds it
        return
    try:
        fcntl.flock(fd, fcntl.LOCK_SH | fcntl.LOCK_NB)
    except OSError:
        _refuse_locked(out_dir, fd)
    os.close(fd)  # closing releases the shared lock


def read_manifest(out_dir: Path) -> set[str]:
    """The names of the files earlier img2logo batches wrote in ``out_dir`` (:data:`MANIFEST_NAME`)."""
    try:
        text = (out_dir / MANIFEST_NAME).read_text(encoding="utf-8", errors="surrogateescape")
    except (OSError, ValueError):
        return set()
    if not text.startswith(_MANIFEST_HEADER):
        return set()
    return {line for line in text[len(_MANIFEST_HEADER) :].split("\n") if line and "/" not in line}


def write_manifest(out_dir: Path, names: Iterable[str]) -> None:
    """Record the files img2logo wrote in ``out_dir`` (those still there), whole or not at all."""
    from ..._io import atomic_write

    if not out_dir.is_dir():
        return
    kept = sorted(n for n in names if (out_dir / n).is_file() and "\n" not in n)
    if not kept and not (out_dir / MANIFEST_NAME).exists():
        return
    text = _MANIFEST_HEADER + "".join(f"{n}\n" for n in kept)
    atomic_write(out_dir / MANIFEST_NAME, lambda f: f.write(text.encode("utf-8", "surrogateescape")))


def written_by_img2logo(path: Path, manifest: set[str]) -> bool:
    """Whether ``path`` is a regular file an img2logo run wrote.

    It is when the folder's manifest lists it; a JSON file also when it is an
    ``img2logo.abstraction/1`` document, an SVG when its description says img2logo
    wrote it (outputs of runs before the manifest). A file of the user's
    (``notes.json``), a link or anything else is not.
    """
    if path.is_symlink() or not path.is_file():
        return False
    if path.name in manifest:
        return True
    try:
        if path.suffix == ".json" and path.stat().st_size <= 256 * 2**20:
            import json

            from ...constants import FORMAT_NAME

            doc = json.loads(path.read_bytes())
            return isinstance(doc, dict) and doc.get("format") == FORMAT_NAME
        if path.suffix == ".svg":
            with path.open("rb") as f:
                return b"golden ratio logo by img2logo" in f.read(4096)
    except (OSError, ValueError):
        return False
    return False


def remove_old_outputs(out_dir: Path, stem: str, formats: Sequence[str], manifest: set[str]) -> list[str]:
    """Remove ``out_dir/<stem>.<fmt>`` that an earlier img2logo run wrote (never an input, checked before).

    Returns the names removed. A file img2logo did not write (see
    :func:`written_by_img2logo`) is left alone.
    """
    removed = []
    for fmt in formats:
        old = out_dir / f"{stem}.{fmt}"
        if written_by_img2logo(old, manifest):
            from ..._io import remove_file

            remove_file(old)
            removed.append(old.name)
    return removed


def output_stems(paths: Sequence[Path]) -> list[str]:
    """File stems of the outputs: the input's stem, ``<stem>-<suffix>`` where stems collide, numbered if still."""
    counts: dict[str, int] = {}
    for p in paths:
        counts[p.stem] = counts.get(p.stem, 0) + 1
    stems = [p.stem if counts[p.stem] == 1 else f"{p.stem}-{p.suffix.lstrip('.').lower()}" for p in paths]
    seen: dict[str, int] = {}
    out = []
    for s in stems:
        seen[s] = seen.get(s, 0) + 1
        out.append(s if seen[s] == 1 else f"{s}-{seen[s]}")
    return out
