"""Small I/O helpers of the writers: atomic writes, a set of files written together, output checks.

Every file img2logo writes goes through :func:`atomic_write`: the bytes go to a
temporary file in the target's directory that is then renamed over the target
(:func:`os.replace`), so a file is written whole or not at all; missing parent
directories are created. Inside :func:`output_set` the files of a run appear
together at its end, or none of them. A path that cannot be written raises
:class:`~img2logo.errors.OutputError` naming it; :func:`check_output_paths` finds
most such paths, and outputs that are inputs, before any work. Temporary files
left by a killed run are removed by the next run that writes the same target.
"""

from __future__ import annotations

import contextlib
import contextvars
import errno
import glob
import os
import re
import stat
from collections.abc import Callable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import IO

from .errors import InvalidParameterError, OutputError

__all__ = [
    "as_path",
    "atomic_write",
    "check_output_paths",
    "make_folders",
    "os_message",
    "output_set",
    "printable",
    "remove_file",
]


def printable(text: object) -> str:
    """``text`` safe to print as part of one line: every character that is not printable is escaped.

    A newline, a carriage return, a terminal escape or any other control
    character (and a byte of a file name that is no UTF-8, Python's surrogate
    escape) becomes its Python escape (``\\n``, ``\\x1b``, ``\\udcff``), as
    :func:`repr` writes it; so a file named ``"a\\nimg2logo: error: x.png"``
    cannot forge a line of its own. Printable text, spaces included, is kept as it is.
    """
    s = str(text)
    if s.isprintable():
        return s
    return "".join(ch if ch.isprintable() or ch == " " else repr(ch)[1:-1] for ch in s)


def check_output_paths(
    targets: Mapping[str, str | os.PathLike[str]],
    inputs: Sequence[str | os.PathLike[str]] = (),
    folders: Mapping[str, str | os.PathLike[str]] | None = None,
) -> dict[str, Path]:
    """Check, before any work, that every output can be written and that none is an input.

    Links are resolved (symbolic links by :func:`os.path.realpath`, hard links
    by the file's identity), so a target that is an input under another name is
    found. Temporary files of the targets left by killed runs are removed.

    Parameters
    ----------
    targets : mapping of str to path
        What each output is called in a message (``"--svg"``) -> its file.
    inputs : sequence of path
        The files the run reads: no target may be one of them.
    folders : mapping of str to path, optional
        Output folders (``"--levels-dir"``) -> folder: each must be a folder or
        creatable, and writable.

    Returns
    -------
    dict of str to pathlib.Path

    Raises
    ------
    InvalidParameterError
        Naming the output and the path: a target that is an input, a folder or
        not a regular file (a device such as /dev/null); two outputs on one
        file; a parent that is a regular file, or a folder that cannot be
        written (no permission, a read-only file system).
    """
    checked: dict[str, Path] = {}
    seen: dict[str, str] = {}
    real_inputs = {os.path.realpath(os.fspath(p)): Path(p) for p in inputs}
    # Each input's file identity, stat'ed once (not once per target): the targets x inputs
    # comparisons of a large batch then cost no file system calls.
    input_ids = {real: _file_id(given) for real, given in real_inputs.items()}
    for name, path in targets.items():
        target = as_path(path)
        label = name if name == str(target) else f"{name} {target}"
        if target.is_dir():
            raise InvalidParameterError(f"{label} is a folder; give a file name")
        if target.exists() and not target.is_file():
            raise InvalidParameterError(f"{label} is not a regular file (a device, a pipe, ...)")
        real = os.path.realpath(target)
        target_id = _file_id(target)
        for real_input, given in real_inputs.items():
            if real == real_input or (target_id is not None and target_id == input_ids[real_input]):
                raise InvalidParameterError(f"{label} is the input {given}: refusing to write over an input")
        if real in seen:
            raise InvalidParameterError(f"{seen[real]} and {name} name the same file {target}; give two files")
        seen[real] = name
        _check_writable_parent(label, target.parent)
        _remove_stale_temporaries(target)
        checked[name] = target
    for name, path in (folders or {}).items():
        folder = as_path(path)
        if folder.exists() and not folder.is_dir():
            raise InvalidParameterError(f"{name} {folder} is a file, not a folder")
        _check_writable_parent(f"{name} {folder}", folder)
    return checked


def _file_id(path: Path) -> tuple[int, int] | None:
    """The (device, inode) of an existing file, what :func:`os.path.samefile` compares; None if it cannot be stat'ed."""
    try:
        st = os.stat(path)
    except OSError:
        return None
    return st.st_dev, st.st_ino


def _check_writable_parent(label: str, folder: Path) -> None:
    """Raise unless ``folder`` (or its first existing ancestor, where it would be created) is a writable folder."""
    p = folder if str(folder) else Path(".")
    while not p.exists() and not p.is_symlink() and p != p.parent:
        p = p.parent
    if not p.is_dir():
        raise InvalidParameterError(f"{label}: {p} is not a folder")
    if not os.access(p, os.W_OK | os.X_OK):
        raise InvalidParameterError(f"{label}: cannot write in {p} (no permission, or a read-only file system)")


class _Stage:
    """The files of one :func:`output_set`: (temporary, target) pairs and the folders it created."""

    def __init__(self) -> None:
        self.files: list[tuple[Path, Path]] = []
        self.folders: list[Path] = []
        self.removals: list[Path] = []

    def discard(self) -> None:
        """Remove the temporary files and the folders created (if left empty)."""
        for tmp, _ in self.files:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
        for folder in reversed(self.folders):
            with contextlib.suppress(OSError):
                folder.rmdir()
        self.files.clear()
        self.folders.clear()
        self.removals.clear()

    def commit(self) -> None:
        """Move every temporary file over its target, with SIGINT and SIGTERM held off meanwhile."""
        import signal
        import threading

        held = threading.current_thread() is threading.main_thread() and hasattr(signal, "pthread_sigmask")
        if held:
            old = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT, signal.SIGTERM})
        try:
            try:
                for _, target in self.files:  # one may have appeared since the write: before any move
                    refuse_special_file(target)
            except OutputError:
                self.discard()
                raise
            while self.files:
                tmp, target = self.files[0]
                try:
                    os.replace(tmp, target)
                except OSError as exc:
                    self.discard()
                    raise OutputError(os_message(target, exc)) from exc
                self.files.pop(0)
            for gone in self.removals:
                _unlink(gone)
            self.removals.clear()
        finally:
            if held:
                signal.pthread_sigmask(signal.SIG_SETMASK, old)


_STAGE: contextvars.ContextVar[_Stage | None] = contextvars.ContextVar("img2logo_output_stage", default=None)


@contextlib.contextmanager
def output_set() -> Iterator[None]:
    """Write every file of a run together: all of them appear at the end, or none.

    Inside the ``with`` block every writer (:func:`atomic_write`) writes its bytes to
    a temporary file next to its target; when the block ends normally the
    temporary files are renamed over their targets one after the other (signals
    held off meanwhile); when it ends with an exception (an error, Ctrl-C, a
    SIGTERM turned into an exception) they are removed, with the folders the
    block created, and no target is touched.

    Examples
    --------
    >>> with output_set():  # doctest: +SKIP
    ...     writers.write_json(level, "out/logo.json")
    ...     writers.write_svg(level, "out/logo.svg")
    """
    stage = _Stage()
    token = _STAGE.set(stage)
    try:
        yield
    except BaseException:
        stage.discard()
        raise
    finally:
        _STAGE.reset(token)
    stage.commit()


def remove_file(path: str | os.PathLike[str]) -> None:
    """Remove a file img2logo wrote; inside :func:`output_set`, at the end of the set, after its files are in place.

    So a run that replaces a set of files by a smaller one (``--levels-dir``)
    removes the files of the earlier set with the same all-or-nothing rule: if
    the run fails, nothing is removed. A file already gone is no error.

    Raises
    ------
    OutputError
        If the file cannot be removed (outside a set: at once).
    """
    target = as_path(path)
    stage = _STAGE.get()
    if stage is not None:
        stage.removals.append(target)
    else:
        _unlink(target)


def _unlink(target: Path) -> None:
    """Remove ``target`` (gone already: nothing to do); an operating-system error is an :class:`OutputError`."""
    try:
        os.unlink(target)
    except FileNotFoundError:
        return
    except OSError as exc:
        raise OutputError(f"cannot remove {target}: {exc.strerror or exc}") from exc


def atomic_write(path: str | os.PathLike[str], write: Callable[[IO[bytes]], object]) -> Path:
    """Write a file whole or not at all: into a temporary sibling, then :func:`os.replace`.

    ``write`` gets the open binary temporary file. Parent directories are created.
    On any error the temporary file is removed and an existing target is untouched;
    an operating-system error (a read-only file system, a full disk, a parent
    that is a file, a target that is a folder) is raised as :class:`OutputError`
    naming the path. Temporary files of the same target left by a process that
    no longer runs (killed while writing) are removed first. Inside
    :func:`output_set` the rename waits for the end of the set. The file gets
    the usual permissions (0o666 less the umask). A target that exists and is
    not a regular file (a device such as ``/dev/full``, a FIFO, a socket, also
    through a symbolic link) is refused with :class:`OutputError` before
    anything is written: renaming over it would replace the device itself.
    """
    target = as_path(path)
    stage = _STAGE.get()
    refuse_special_file(target)
    try:
        if target.is_dir():
            raise IsADirectoryError(errno.EISDIR, "is a directory", str(target))
        make_folders(target.parent, None if stage is None else stage.folders)
        _remove_stale_temporaries(target)
        fd, tmp = _open_temporary(target)
    except OSError as exc:
        raise OutputError(os_message(target, exc)) from exc
    try:
        with os.fdopen(fd, "wb") as f:
            write(f)
            f.flush()
            os.fsync(f.fileno())
        if stage is not None:
            stage.files.append((tmp, target))
        else:
            refuse_special_file(target)  # one may have appeared while writing
            os.replace(tmp, target)
    except BaseException as exc:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        if isinstance(exc, OSError) and not isinstance(exc, OutputError):
            raise OutputError(os_message(target, exc)) from exc
        raise
    return target


def special_file_kind(path: Path) -> str | None:
    """What ``path`` is when it exists and is not a regular file (``"a device"``, ``"a FIFO"``, ...), else None.

    Symbolic links are followed: a link to ``/dev/full`` is a device. A folder
    is not reported here (its own message says so).
    """
    try:
        mode = os.stat(path).st_mode
    except (OSError, ValueError):  # missing, a dangling link, an unreadable parent: the write says
        return None
    if stat.S_ISREG(mode) or stat.S_ISDIR(mode):
        return None
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISFIFO(mode):
        return "a FIFO (named pipe)"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "not a regular file"  # pragma: no cover - no other kind on POSIX


def refuse_special_file(target: Path) -> None:
    """Raise :class:`OutputError` if ``target`` exists and is not a regular file (nor a folder)."""
    kind = special_file_kind(target)
    if kind is not None:
        raise OutputError(f"cannot write {target}: it is {kind}, not a regular file; refusing to replace it")


#: Temporary files: ``.<target name>.<pid>-<8 hex>.tmp`` next to the target.
_TEMPORARY = re.compile(r"\.(?P<name>.+)\.(?P<pid>\d+)-[0-9a-f]{8}\.tmp")


def _open_temporary(target: Path) -> tuple[int, Path]:
    """Create and open a new temporary file next to ``target``: (file descriptor, path)."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0)
    for _ in range(100):
        tmp = target.parent / f".{target.name}.{os.getpid()}-{os.urandom(4).hex()}.tmp"
        try:
            return os.open(tmp, flags, 0o666), tmp
        except FileExistsError:
            continue
    raise FileExistsError(errno.EEXIST, "could not create a temporary file next to it", str(target))  # pragma: no cover


def _remove_stale_temporaries(target: Path) -> list[Path]:
    """Remove ``target``'s temporary files whose writing process is gone; return them."""
    removed = []
    with contextlib.suppress(OSError):
        for p in target.parent.glob(f".{glob.escape(target.name)}.*.tmp"):
            m = _TEMPORARY.fullmatch(p.name)
            if m is None or m["name"] != target.name or _process_alive(int(m["pid"])):
                continue
            with contextlib.suppress(FileNotFoundError):
                p.unlink()
                removed.append(p)
    return removed


def _process_alive(pid: int) -> bool:
    """Whether a process ``pid`` exists (this one included)."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError, OSError):
        return True
    return True


def make_folders(folder: Path, made: list[Path] | None = None) -> None:
    """Create ``folder`` and its missing parents, appending each one created to ``made`` as it is made.

    ``made`` is filled as the folders appear, so that a caller can remove them
    again (deepest first) when a later step fails, even if this call failed part way.
    """
    missing = []
    p = folder
    while not p.exists() and p != p.parent:
        missing.append(p)
        p = p.parent
    for p in reversed(missing):
        try:
            p.mkdir()
        except FileExistsError:
            if not p.is_dir():
                raise
            continue
        if made is not None:
            made.append(p)


def os_message(target: Path, exc: OSError) -> str:
    """``cannot write <target>: <reason>``, naming the path that failed when it is not the target."""
    reason = exc.strerror or str(exc) or type(exc).__name__
    where = None if exc.filename is None else Path(os.fsdecode(exc.filename))
    if where is not None and where != target and not where.name.startswith(f".{target.name}."):
        reason = f"{reason} ({where})"
    return f"cannot write {target}: {reason}"


def as_path(path: object) -> Path:
    """``path`` as a :class:`pathlib.Path`, for a str or path-like that is not empty."""
    if isinstance(path, str | os.PathLike):
        p = os.fspath(path)
        if isinstance(p, str) and p:
            return Path(p)
    raise InvalidParameterError(f"path must be a non-empty str or path-like, got {path!r}")
