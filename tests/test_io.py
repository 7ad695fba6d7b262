"""Tests of img2logo._io: atomic writes, output sets, stale temporary files, output path checks."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from helpers import make_abstraction

from img2logo import _io
from img2logo.errors import InvalidParameterError, OutputError
from img2logo.export import writers


def leftovers(directory: Path) -> list[str]:
    return sorted(p.name for p in directory.iterdir())


def _dead_pid() -> int:
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()  # reaped: its process id is free
    return child.pid


def test_parent_directories_created(tmp_path):
    a = make_abstraction()
    for name, write in (("a.json", writers.write_json), ("a.svg", writers.write_svg), ("a.png", writers.write_png)):
        target = tmp_path / "deep" / "er" / name
        assert write(a, str(target)) == target
        assert target.is_file()
    assert leftovers(tmp_path / "deep" / "er") == ["a.json", "a.png", "a.svg"]


def test_written_file_has_usual_permissions(tmp_path):
    umask = os.umask(0o022)
    try:
        p = writers.write_json(make_abstraction(), tmp_path / "a.json")
    finally:
        os.umask(umask)
    assert p.stat().st_mode & 0o777 == 0o644


def test_failed_replace_leaves_nothing(tmp_path, monkeypatch):
    def fail(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(_io.os, "replace", fail)
    with pytest.raises(OSError, match="disk full"):
        writers.write_json(make_abstraction(), tmp_path / "out" / "a.json")
    assert leftovers(tmp_path / "out") == []


def test_failure_midway_keeps_the_old_file(tmp_path, monkeypatch):
    from matplotlib.figure import Figure
    from PIL import Image

    target = tmp_path / "a.png"
    target.write_bytes(b"old")

    def half_then_fail(self, f, **kwargs):
        f.write(b"\x89PNG half")
        raise RuntimeError("renderer crashed")

    monkeypatch.setattr(Figure, "savefig", half_then_fail)  # a transparent PNG's writer
    monkeypatch.setattr(Image.Image, "save", half_then_fail)  # an opaque (RGB) PNG's
    with pytest.raises(RuntimeError, match="renderer crashed"):
        writers.write_png(make_abstraction(), target)
    assert target.read_bytes() == b"old"
    assert leftovers(tmp_path) == ["a.png"]
    with pytest.raises(RuntimeError, match="renderer crashed"):
        writers.write_png(make_abstraction(), tmp_path / "new.png")
    assert leftovers(tmp_path) == ["a.png"]
    with pytest.raises(RuntimeError, match="renderer crashed"):
        writers.write_png(make_abstraction(), target, background="transparent")
    assert target.read_bytes() == b"old" and leftovers(tmp_path) == ["a.png"]


def test_atomic_write_helper(tmp_path):
    def boom(f):
        f.write(b"partial")
        raise ValueError("boom")

    with pytest.raises(ValueError, match="boom"):
        _io.atomic_write(tmp_path / "x.bin", boom)
    assert leftovers(tmp_path) == []
    _io.atomic_write(tmp_path / "x.bin", lambda f: f.write(b"whole"))
    assert (tmp_path / "x.bin").read_bytes() == b"whole"
    assert leftovers(tmp_path) == ["x.bin"]


@pytest.mark.parametrize("bad", [None, 3, "", b"bytes.json"])
def test_bad_path_rejected(bad):
    with pytest.raises(InvalidParameterError, match="path must be a non-empty str or path-like"):
        writers.write_json(make_abstraction(), bad)


def test_writer_errors_name_the_path(tmp_path):
    from img2logo.errors import OutputError

    (tmp_path / "file").write_text("x")
    with pytest.raises(OutputError, match=r"cannot write .*folder: is a directory"):
        (tmp_path / "folder").mkdir()
        writers.write_json(make_abstraction(), tmp_path / "folder")
    with pytest.raises(OutputError, match=r"cannot write .*file/a\.svg: Not a directory"):
        writers.write_svg(make_abstraction(), tmp_path / "file" / "a.svg")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file", "folder"]


def test_output_set_writes_all_or_nothing(tmp_path):
    a = make_abstraction()
    with pytest.raises(KeyboardInterrupt), _io.output_set():
        writers.write_json(a, tmp_path / "new" / "deep" / "a.json")
        writers.write_svg(a, tmp_path / "new" / "a.svg")
        assert not (tmp_path / "new" / "a.svg").exists()  # not before the set ends
        raise KeyboardInterrupt
    assert list(tmp_path.iterdir()) == []  # no file, no temporary file, no folder it created
    with _io.output_set():
        writers.write_json(a, tmp_path / "a.json")
        writers.write_svg(a, tmp_path / "a.svg")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.json", "a.svg"]


# --------------------------------------------------------------------------- hostile targets
@pytest.mark.parametrize(
    ("text", "shown"),
    [
        ("plain name.png", "plain name.png"),
        ("a\nimg2logo: error: x.png", "a\\nimg2logo: error: x.png"),
        ("b\r\t\x1b[31mc", "b\\r\\t\\x1b[31mc"),
        ("line\u2028sep\x85", "line\\u2028sep\\x85"),
        ("bytes\udcff.png", "bytes\\udcff.png"),  # a name that is no UTF-8 (surrogate escape)
        ("é ü 猫.png", "é ü 猫.png"),
    ],
)
def test_printable_escapes_what_could_start_a_line(text, shown):
    from img2logo._io import printable

    assert printable(text) == shown
    assert printable(text).isprintable()


def test_remove_file_in_a_set_waits_for_the_set_and_is_undone_with_it(tmp_path):
    from img2logo._io import atomic_write, output_set, remove_file

    old, new = tmp_path / "old.json", tmp_path / "new.json"
    old.write_text("earlier run")
    with pytest.raises(RuntimeError), output_set():
        atomic_write(new, lambda f: f.write(b"x"))
        remove_file(old)
        assert old.exists()  # not yet
        raise RuntimeError("the run failed")
    assert old.read_text() == "earlier run" and not new.exists()
    with output_set():
        atomic_write(new, lambda f: f.write(b"x"))
        remove_file(old)
        remove_file(tmp_path / "never-there.json")  # no error
        assert old.exists()
    assert not old.exists() and new.read_bytes() == b"x"
    new_copy = tmp_path / "c"
    new_copy.write_text("y")
    remove_file(new_copy)  # outside a set: at once
    assert not new_copy.exists()


def test_stale_temporary_files_of_a_target_are_removed(tmp_path):
    dead, alive = _dead_pid(), os.getpid()
    stale = tmp_path / f".a.json.{dead}-0123abcd.tmp"
    running = tmp_path / f".a.json.{alive}-0123abcd.tmp"  # this process: still writing it
    other = tmp_path / f".b.json.{dead}-0123abcd.tmp"  # another target's
    for p in (stale, running, other):
        p.write_text("partial")
    writers.write_json(make_abstraction(), tmp_path / "a.json")
    assert not stale.exists() and running.exists() and other.exists()


def test_check_output_paths(tmp_path):
    src = tmp_path / "in.png"
    src.write_bytes(b"image")
    (tmp_path / "link.png").symlink_to(src)
    os.link(src, tmp_path / "hard.png")
    (tmp_path / "file").write_text("x")
    (tmp_path / "dir").mkdir()
    os.mkfifo(tmp_path / "pipe.svg")  # no regular file, like a device
    check = _io.check_output_paths
    ok = check({"--svg": tmp_path / "new" / "a.svg", "--json": tmp_path / "a.json"}, [src])
    assert ok == {"--svg": tmp_path / "new" / "a.svg", "--json": tmp_path / "a.json"}
    assert not (tmp_path / "new").exists()  # nothing created by a check
    cases = [
        ({"--png": src}, "is the input"),
        ({"--png": tmp_path / "link.png"}, "link.png is the input .*in.png: refusing to write over an input"),
        ({"--png": tmp_path / "hard.png"}, "hard.png is the input"),
        ({"--svg": tmp_path / "o.out", "--json": tmp_path / "./o.out"}, "--svg and --json name the same file"),
        ({"--svg": tmp_path / "dir"}, "--svg .*dir is a folder"),
        ({"--svg": tmp_path / "pipe.svg"}, r"--svg .*pipe\.svg is not a regular file"),
        ({"--svg": tmp_path / "file" / "sub" / "a.svg"}, r"--svg .*a\.svg: .*file is not a folder"),
    ]
    for targets, message in cases:
        with pytest.raises(InvalidParameterError, match=message):
            check(targets, [src])
    with pytest.raises(InvalidParameterError, match=r"--levels-dir .*file is a file, not a folder"):
        check({}, [src], {"--levels-dir": tmp_path / "file"})


# --- a target that is no regular file: a FIFO, a device -------------------
def _special_targets(tmp_path):
    fifo = tmp_path / "pipe.out"  # a suffix of no format: each writer may be aimed at it
    os.mkfifo(fifo)
    link = tmp_path / "link.out"
    link.symlink_to(fifo)
    return fifo, link


@pytest.mark.parametrize(
    "write",
    [writers.write_json, writers.write_svg, writers.write_png, lambda a, p: _io.atomic_write(p, lambda f: None)],
    ids=["json", "svg", "png", "atomic_write"],
)
def test_a_fifo_at_the_target_is_refused_and_kept(tmp_path, write):
    fifo, link = _special_targets(tmp_path)
    for target in (fifo, link):
        with pytest.raises(OutputError, match=r"cannot write .*: it is a FIFO \(named pipe\), not a regular file"):
            write(make_abstraction(), target)
    import stat

    assert stat.S_ISFIFO(os.stat(fifo).st_mode) and link.is_symlink()  # nothing replaced
    assert leftovers(tmp_path) == ["link.out", "pipe.out"]  # no temporary file left


def test_a_device_at_the_target_is_refused(tmp_path, monkeypatch):
    # A fake character device (no test may touch /dev): os.stat reports one for this path.
    import stat

    device = tmp_path / "full"
    device.write_text("device")
    real_stat = os.stat

    def fake_stat(path, *args, **kwargs):
        st = real_stat(path, *args, **kwargs)
        if os.fspath(path) == os.fspath(device):
            return os.stat_result((stat.S_IFCHR | 0o666, *tuple(st)[1:]))
        return st

    monkeypatch.setattr(_io.os, "stat", fake_stat)
    for write in (writers.write_json, writers.write_svg):
        with pytest.raises(OutputError, match=r"cannot write .*full: it is a device, not a regular file"):
            write(make_abstraction(), device)
    assert device.read_text() == "device" and leftovers(tmp_path) == ["full"]


def test_a_fifo_appearing_inside_an_output_set_moves_nothing(tmp_path):
    a = make_abstraction()
    with pytest.raises(OutputError, match="it is a FIFO"):
        with _io.output_set():
            writers.write_json(a, tmp_path / "a.json")
            writers.write_svg(a, tmp_path / "b.svg")
            os.mkfifo(tmp_path / "b.svg")  # after its write, before the set moves the files
    assert leftovers(tmp_path) == ["b.svg"]  # a.json not moved either: the set is whole or nothing
