"""Batch runs (img2logo.app.batch.run): every image of a folder, on any concurrent.futures executor."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from concurrent.futures import Executor, Future, ProcessPoolExecutor, ThreadPoolExecutor
from pathlib import Path

import pandas as pd
import pytest
from helpers import DATA

from img2logo.app.batch.folder import output_stems
from img2logo.app.batch.run import (
    MANIFEST_NAME,
    SUMMARY_COLUMNS,
    BatchReport,
    find_images,
    process_image,
    run_batch,
)
from img2logo.errors import ImageNotFoundError, InvalidParameterError

GOOD = ("drawing-leaf.png", "drawing-snail.png")  # fast: about 1 s each


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> Path:
    """Two small drawings, one corrupt PNG (text inside) and a file that is no image."""
    root = tmp_path_factory.mktemp("batch-in")
    for name in GOOD:
        shutil.copy(DATA / name, root / name)
    (root / "broken.png").write_text("this is not a PNG\n")
    (root / "notes.txt").write_text("not an image: skipped\n")
    (root / "sub").mkdir()
    shutil.copy(DATA / GOOD[0], root / "sub" / "nested.png")  # not searched
    return root


@pytest.fixture(scope="module")
def runs(folder, tmp_path_factory) -> dict[str, tuple[BatchReport, Path]]:
    """The same batch on a thread pool and on a process pool of two workers."""
    out = {}
    for label, make in (("threads", lambda: ThreadPoolExecutor(2)), ("processes", lambda: ProcessPoolExecutor(2))):
        target = tmp_path_factory.mktemp(f"batch-{label}")
        with make() as executor:
            out[label] = (run_batch(find_images(folder), target, executor=executor, progress=False), target)
    return out


def test_find_images_is_sorted_and_flat(folder):
    assert [p.name for p in find_images(folder)] == ["broken.png", *GOOD]


def test_find_images_errors(tmp_path):
    with pytest.raises(InvalidParameterError, match="input folder not found: "):
        find_images(tmp_path / "missing")
    with pytest.raises(InvalidParameterError, match=r"no images \(png, jpg, jpeg, tif, tiff, bmp, webp\) in "):
        find_images(tmp_path)


@pytest.mark.parametrize("label", ["threads", "processes"])
def test_batch_goes_past_a_bad_file(runs, label):
    report, out = runs[label]
    assert [r.image for r in report.rows] == list(GOOD)
    assert not report.ok and len(report.failures) == 1
    failure = report.failures[0]
    assert failure.image == "broken.png"
    assert "not a readable image" in failure.message and "\n" not in failure.message
    assert failure.line.startswith(str(Path(failure.path))) and failure.line.count("broken.png") == 1
    for row in report.rows:
        assert row.kind == "drawing" and row.arcs > 0 and row.levels >= 1 and 0 < row.similarity <= 5.0
        assert row.seconds > 0
        stem = Path(row.image).stem
        assert row.outputs == tuple(str(out / f"{stem}.{fmt}") for fmt in ("svg", "json", "png"))
    assert sorted(p.name for p in out.iterdir()) == sorted(
        [
            MANIFEST_NAME,
            "index.html",
            "summary.csv",
            *(f"{Path(n).stem}.{fmt}" for n in GOOD for fmt in ("svg", "json", "png")),
        ]
    )


def test_summary_csv(runs):
    report, out = runs["threads"]
    assert report.summary_path == str(out / "summary.csv")
    table = pd.read_csv(out / "summary.csv", keep_default_na=False)
    assert tuple(table.columns) == SUMMARY_COLUMNS
    assert table["image"].tolist() == ["broken.png", *GOOD]  # input order, failures included
    assert "not a readable image" in table.loc[0, "error"] and table.loc[0, "arcs"] == ""
    assert table.loc[1:, "error"].tolist() == ["", ""]
    assert table.loc[1:, "arcs"].astype(int).tolist() == [r.arcs for r in report.rows]
    frame = report.to_frame()
    assert frame["image"].tolist() == table["image"].tolist() and frame["arcs"].dtype == "Int64"


def test_summary_text(runs):
    report, _ = runs["threads"]
    text = report.summary()
    head = text.splitlines()[0].split()
    assert head[:4] == ["image", "kind", "arcs", "E^s"] and head[-1] == "seconds"
    assert "2 of 3 images done" in text and "1 failed:" in text and "not a readable image" in text
    assert "failed" not in report.summary(failures=False)


def test_outputs_do_not_depend_on_the_executor(runs):
    (_, a), (_, b) = runs["threads"], runs["processes"]
    for name in GOOD:
        for fmt in ("svg", "json", "png"):
            file = f"{Path(name).stem}.{fmt}"
            assert (a / file).read_bytes() == (b / file).read_bytes(), file


@pytest.mark.parametrize("processes", [False, True], ids=["threads", "worker-processes"])
def test_a_dask_cluster_gives_the_same_files(folder, runs, tmp_path, processes):
    """The ``[dask]`` extra: a LocalCluster's executor runs the batch, its files byte-identical to a process pool's.

    In threads of this process, and in worker processes of their own, as on a cluster: the options go to
    the workers and the files come back pickled.
    """
    distributed = pytest.importorskip("distributed")
    _, reference = runs["processes"]
    with (
        distributed.LocalCluster(
            n_workers=2 if processes else 1,
            threads_per_worker=1 if processes else 2,
            processes=processes,
            dashboard_address=None,
            local_directory=str(tmp_path / "dask-scratch"),
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        report = run_batch(find_images(folder), tmp_path / "out", executor=client.get_executor(), progress=False)
    assert [r.image for r in report.rows] == list(GOOD) and len(report.failures) == 1
    for name in GOOD:
        for fmt in ("svg", "json", "png"):
            file = f"{Path(name).stem}.{fmt}"
            assert (tmp_path / "out" / file).read_bytes() == (reference / file).read_bytes(), file


def test_outputs_are_those_of_the_single_image_command(runs, tmp_path):
    pytest.importorskip("jsonschema")
    from img2logo.app.cli import main
    from img2logo.export.contract import validate_document

    _, out = runs["processes"]
    single = tmp_path / "single.json"
    assert main([str(DATA / GOOD[0]), "-q", "--json", str(single)]) == 0
    batch = json.loads((out / "drawing-leaf.json").read_text())
    validate_document(batch)
    mine = json.loads(single.read_text())
    assert batch["params"].pop("source") != mine["params"].pop("source")  # the input's path
    assert batch == mine


def test_any_executor_and_its_failures(folder, tmp_path):
    class Broken(Executor):
        """An executor whose every task fails (a worker that died)."""

        def submit(self, fn, /, *args, **kwargs):
            future: Future = Future()
            future.set_exception(RuntimeError("worker lost"))
            return future

    seen = []
    report = run_batch(
        find_images(folder), tmp_path, executor=Broken(), progress=lambda *a: seen.append(a), summary=False
    )
    assert not report.rows and [f.message for f in report.failures] == ["RuntimeError: worker lost"] * 3
    assert sorted(image for _, _, image in seen) == ["broken.png", *GOOD]  # in completion order
    assert [(done, total) for done, total, _ in seen] == [(1, 3), (2, 3), (3, 3)]
    assert report.summary_path is None
    assert not (tmp_path / "summary.csv").exists()


def test_in_process_run_with_options(folder, tmp_path):
    pytest.importorskip("jsonschema")
    from img2logo.export.contract import validate_document
    from img2logo.geometry.golden_ladder import fibonacci

    report = run_batch(
        [folder / GOOD[1]], tmp_path, jobs=1, progress=False, outputs=("json",), ladder="fibonacci", tolerance=7.0
    )
    assert report.ok and report.rows[0].outputs == (str(tmp_path / "drawing-snail.json"),)
    doc = json.loads((tmp_path / "drawing-snail.json").read_text())
    validate_document(doc)
    assert doc["ladder"] == "fibonacci" and doc["tolerance"] == 7.0
    assert all(c["r"] / doc["unit"] == pytest.approx(fibonacci(c["k"]), rel=1e-9) for c in doc["circles"])
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        MANIFEST_NAME,
        "drawing-snail.json",
        "index.html",
        "summary.csv",
    ]


def test_process_image_returns_plain_values(folder):
    out = process_image(str(folder / "broken.png"), {"tolerance": 5.0})
    assert set(out) == {"image", "path", "seconds", "warnings", "error"}
    assert out["image"] == "broken.png" and "not a readable image" in out["error"]


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"tolerance": 0}, "tolerance must be > 0, got 0"),
        ({"colour": "red"}, "unknown option 'colour': expected keyword arguments of img2logo.abstract"),
        ({"image": "x.png"}, "unknown option 'image'"),
        ({"ladder": "fibonacci", "bias": 0.2}, "bias is a parameter of the phi ladder"),
        ({"unit": 2.0}, "unit is a parameter of the Fibonacci ladder"),
        ({"kind": "painting"}, "kind must be one of 'auto', 'photo', 'clipart', 'drawing', got 'painting'"),
        ({"fill": "palette:"}, "the palette is empty"),
        ({"outputs": ("svg", "pdf")}, "outputs entry must be one of 'svg', 'json', 'png', got 'pdf'"),
        ({"jobs": 0}, "jobs must be an integer >= 1, got 0"),
        ({"min_length": -5}, r"min_length must be >= 0, got -5\.0"),
        ({"connectvity": False}, "unknown option 'connectvity' \\(did you mean 'connectivity'\\?\\)"),
    ],
)
def test_bad_options_fail_before_any_work(folder, tmp_path, kwargs, message):
    with pytest.raises(InvalidParameterError, match=message):
        run_batch(find_images(folder), tmp_path / "out", progress=False, **kwargs)
    assert not (tmp_path / "out").exists()


def test_no_paths(tmp_path):
    with pytest.raises(InvalidParameterError, match="paths must name at least one image, got none"):
        run_batch([], tmp_path)


def test_output_stems_never_collide():
    paths = [Path("a.png"), Path("a.jpg"), Path("b.png"), Path("x/a.png")]
    assert output_stems(paths) == ["a-png", "a-jpg", "b", "a-png-2"]


def test_a_missing_foreground_mask_is_refused_before_any_worker_starts(tmp_path):
    counting = _CountingExecutor()
    missing = tmp_path / "missing.png"
    with pytest.raises(ImageNotFoundError, match=f"^--foreground: image file not found: {re.escape(str(missing))}$"):
        run_batch([DATA / GOOD[0]], tmp_path / "out", executor=counting, foreground=str(missing))
    assert counting.submitted == 0 and not (tmp_path / "out").exists()


class _CountingExecutor(Executor):
    """Runs nothing: counts the tasks submitted."""

    def __init__(self) -> None:
        self.submitted = 0

    def submit(self, fn, /, *args, **kwargs):
        self.submitted += 1
        raise AssertionError("no task should be submitted")


def test_options_are_checked_once_before_the_workers_start(folder, tmp_path):
    pool = _CountingExecutor()
    with pytest.raises(InvalidParameterError, match="min_length must be >= 0"):
        run_batch(find_images(folder), tmp_path / "out", executor=pool, min_length=-5)
    assert pool.submitted == 0


def test_outputs_never_overwrite_an_input(tmp_path):
    shutil.copy(DATA / GOOD[0], tmp_path / GOOD[0])
    before = (tmp_path / GOOD[0]).read_bytes()
    with pytest.raises(
        InvalidParameterError, match=r"drawing-leaf\.png is the input .*refusing to write over an input"
    ):
        run_batch(find_images(tmp_path), tmp_path, progress=False)
    assert (tmp_path / GOOD[0]).read_bytes() == before and sorted(p.name for p in tmp_path.iterdir()) == [GOOD[0]]
    (tmp_path / "out").write_text("a file")
    with pytest.raises(InvalidParameterError, match=r"output folder .*out is a file, not a folder"):
        run_batch(find_images(tmp_path), tmp_path / "out", progress=False)


def test_an_image_that_now_fails_keeps_no_old_outputs(tmp_path):
    src, out = tmp_path / "in", tmp_path / "out"
    src.mkdir()
    shutil.copy(DATA / GOOD[0], src / "a.png")
    shutil.copy(DATA / GOOD[1], src / "b.png")
    first = run_batch(find_images(src), out, jobs=1, progress=False)
    assert first.ok and {p.name for p in out.iterdir()} >= {"a.svg", "a.json", "a.png", "b.svg"}
    (src / "a.png").write_text("no longer an image")
    second = run_batch(find_images(src), out, jobs=1, progress=False)
    assert [f.image for f in second.failures] == ["a.png"]
    assert sorted(p.name for p in out.iterdir()) == [
        MANIFEST_NAME,
        "b.json",
        "b.png",
        "b.svg",
        "index.html",
        "summary.csv",
    ]
    assert "not a readable image" in (out / "summary.csv").read_text().splitlines()[1]


def test_workers_start_after_opencv_ran_multithreaded(folder, tmp_path):
    """A forked worker used to hang in cv2.setNumThreads(1) when the parent's OpenCV pool was busy.

    Run in a fresh interpreter, so that the parent's OpenCV has really started its threads. The
    timeout is a hang detector, not a speed limit: the batch takes a few seconds.
    """
    script = (
        "import sys, numpy as np, cv2\n"
        "from img2logo.app.batch.run import find_images, run_batch\n"
        "cv2.setNumThreads(2)\n"
        "a = np.random.default_rng(0).random((1500, 1500)).astype(np.float32)\n"
        "for _ in range(3): cv2.GaussianBlur(a, (31, 31), 5)\n"
        "images = [p for p in find_images(sys.argv[1]) if p.name in sys.argv[3:]]\n"
        "report = run_batch(images, sys.argv[2], jobs=2, progress=False)\n"
        "print(len(report.rows), cv2.getNumThreads())\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script, str(folder), str(tmp_path), *GOOD],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["2", "2"]  # both images, and the parent's OpenCV setting restored


# --------------------------------------------------------------------------- batches never lose data
def _two_images(tmp_path: Path, names=("a.png", "b.png")) -> Path:
    src = tmp_path / "in"
    src.mkdir()
    for name, good in zip(names, GOOD, strict=False):
        shutil.copy(DATA / good, src / name)
    return src


def test_summary_csv_cells_that_a_spreadsheet_would_run_are_quoted(tmp_path):
    src = tmp_path / "in"
    src.mkdir()
    shutil.copy(DATA / GOOD[0], src / "=HYPERLINK(1).png")
    (src / "@bad.png").write_text("not an image")
    report = run_batch(find_images(src), tmp_path / "out", jobs=1, progress=False)
    table = pd.read_csv(tmp_path / "out" / "summary.csv", keep_default_na=False)
    assert table["image"].tolist() == ["'=HYPERLINK(1).png", "'@bad.png"]
    assert table["error"].iloc[1].startswith(str(src))  # a path: not a formula
    assert report.to_frame()["image"].tolist() == ["=HYPERLINK(1).png", "@bad.png"]  # the data itself unchanged


def test_a_failing_image_never_removes_a_file_img2logo_did_not_write(tmp_path):
    src, out = _two_images(tmp_path, ("notes.png", "b.png")), tmp_path / "out"
    out.mkdir()
    (out / "notes.json").write_text('{"my": "notes"}\n')  # the user's, named like an output
    (out / "notes.png").write_bytes((DATA / GOOD[0]).read_bytes())  # a picture of the user's
    (src / "notes.png").write_text("no image")
    report = run_batch(find_images(src), out, jobs=1, progress=False)
    assert [f.image for f in report.failures] == ["notes.png"]
    assert (out / "notes.json").read_text() == '{"my": "notes"}\n' and (out / "notes.png").is_file()
    assert "notes.json" not in (out / MANIFEST_NAME).read_text()


def test_old_outputs_are_recognised_without_a_manifest(tmp_path):
    src, out = _two_images(tmp_path), tmp_path / "out"
    assert run_batch(find_images(src), out, jobs=1, progress=False).ok
    (out / MANIFEST_NAME).unlink()  # outputs of a version that wrote none
    (src / "a.png").write_text("no image")
    run_batch(find_images(src), out, jobs=1, progress=False)
    # the JSON (its format marker) and the SVG (its description) are img2logo's; the PNG cannot be told
    assert sorted(p.name for p in out.iterdir() if p.name.startswith("a.")) == ["a.png"]


class _LostWorkers(Executor):
    """Runs the tasks here, except that the worker of ``lost`` dies (its future fails)."""

    def __init__(self, lost: str) -> None:
        self.lost = lost

    def submit(self, fn, /, *args, **kwargs):
        from concurrent.futures.process import BrokenProcessPool

        future: Future = Future()
        if Path(args[0]).name == self.lost:
            future.set_exception(BrokenProcessPool("A child process terminated abruptly"))
        else:
            future.set_result(fn(*args, **kwargs))
        return future


def test_a_lost_worker_keeps_the_earlier_outputs_of_its_image(tmp_path):
    src, out = _two_images(tmp_path), tmp_path / "out"
    assert run_batch(find_images(src), out, jobs=1, progress=False).ok
    before = {p.name: p.read_bytes() for p in out.iterdir() if p.name.startswith("a.")}
    report = run_batch(find_images(src), out, executor=_LostWorkers("a.png"), progress=False)
    assert [f.image for f in report.failures] == ["a.png"]
    assert "BrokenProcessPool" in report.failures[0].message
    assert {p.name: p.read_bytes() for p in out.iterdir() if p.name.startswith("a.")} == before


def _kill_own_worker_on_b(path, *args, **kwargs):
    """process_image, except that the worker given ``b.png`` is killed (as by the out-of-memory killer)."""
    import os
    import signal

    if Path(path).name == "b.png":
        os.kill(os.getpid(), signal.SIGKILL)
    return _REAL_PROCESS_IMAGE(path, *args, **kwargs)


_REAL_PROCESS_IMAGE = process_image


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="forked workers see the test's patch")
def test_an_image_that_kills_its_worker_fails_alone_and_keeps_its_outputs(tmp_path, monkeypatch):
    import multiprocessing

    if multiprocessing.get_start_method() != "fork":
        pytest.skip("forked workers see the test's patch")
    import img2logo.app.batch.pool

    src, out = _two_images(tmp_path, ("a.png", "b.png")), tmp_path / "out"
    shutil.copy(DATA / GOOD[1], src / "c.png")
    assert run_batch(find_images(src), out, jobs=1, progress=False).ok
    before = {p.name: p.read_bytes() for p in out.iterdir() if p.name[:2] in ("a.", "b.", "c.")}
    monkeypatch.setattr(img2logo.app.batch.pool, "process_image", _kill_own_worker_on_b)
    report = run_batch(find_images(src), out, jobs=2, progress=False)
    assert [r.image for r in report.rows] == ["a.png", "c.png"]  # the others are done
    assert [f.image for f in report.failures] == ["b.png"]
    assert report.failures[0].message == (
        "the worker process running it was lost (killed by a signal, e.g. by the out-of-memory killer); "
        "its earlier outputs are kept"
    )
    assert report.warnings[:2] == (
        "a worker process died (killed by a signal, e.g. by the out-of-memory killer); "
        f"{report.warnings[0].split('; ')[1]}",
        "a worker process died (killed by a signal, e.g. by the out-of-memory killer); "
        f"{report.warnings[1].split('; ')[1]}",
    )
    assert report.warnings[0].endswith("run again in a fresh pool") and report.warnings[1].endswith("each alone")
    assert {p.name: p.read_bytes() for p in out.iterdir() if p.name[:2] in ("a.", "b.", "c.")} == before


def test_a_second_batch_on_a_locked_folder_is_refused_and_a_stale_lock_taken_over(tmp_path):
    from img2logo.app.batch.folder import LOCK_NAME, batch_lock

    src, out = _two_images(tmp_path), tmp_path / "out"
    with batch_lock(out):  # a batch running (a lock is per open file: this one conflicts too)
        with pytest.raises(InvalidParameterError, match=r"output folder .*out is being written by another img2logo"):
            run_batch(find_images(src), out, jobs=1, progress=False)
        assert sorted(p.name for p in out.iterdir()) == [LOCK_NAME]
    assert not out.exists()  # the lock made the folder and, left empty, it is removed
    out.mkdir()
    (out / LOCK_NAME).write_text("999999999\n")  # left by a killed batch: nobody holds it
    assert run_batch(find_images(src), out, jobs=1, progress=False).ok
    assert not (out / LOCK_NAME).exists()


def test_find_images_reports_what_it_skips(tmp_path):
    import os

    shutil.copy(DATA / GOOD[0], tmp_path / "a.png")
    os.mkfifo(tmp_path / "b.png")
    (tmp_path / "c.tif").symlink_to(tmp_path / "gone.tif")
    from img2logo.app.batch.run import SkippedEntryWarning

    with pytest.warns(SkippedEntryWarning) as caught:
        assert [p.name for p in find_images(tmp_path)] == ["a.png"]
    assert str(caught[0].message) == (
        f"{tmp_path}: skipped 2 entries named like images that are no regular files: "
        "'b.png' (a FIFO), 'c.tif' (a dangling link)"
    )


def test_the_summary_text_escapes_control_characters(tmp_path):
    from img2logo.app.batch.run import BatchFailure, BatchRow

    report = BatchReport(
        (BatchRow("a\nb.png", "in/a\nb.png", "drawing", 3, 1, 1.0, 0.1),),
        (BatchFailure("c\rd.png", "in/c\rd.png", "not a readable image"),),
    )
    text = report.summary()
    assert "a\\nb.png" in text and "in/c\\rd.png: not a readable image" in text and "\r" not in text
    assert len(text.splitlines()) == 6
    # A message that names the path already (on one line: the newline a space) does not name it twice.
    failure = BatchFailure("a\nb.png", "in/a\nb.png", "in/a b.png: not a readable image")
    assert failure.line == "in/a\nb.png: not a readable image"


def test_a_foreground_for_a_drawing_is_ignored_with_one_warning(tmp_path):
    report = run_batch([DATA / GOOD[0]], tmp_path, jobs=1, progress=False, outputs=("json",), foreground="none")
    assert report.ok and len(report.warnings) == 1
    assert report.warnings[0].startswith(f"{GOOD[0]}: --foreground none is ignored: the image is drawing (")
    assert report.warnings[0].endswith("and only a photo has a subject to find (give --kind photo to treat it as one)")


def test_a_detail_for_a_drawing_is_ignored_with_one_warning(tmp_path):
    report = run_batch([DATA / GOOD[0]], tmp_path, jobs=1, progress=False, outputs=("json",), detail=3, arcs=30)
    assert report.ok and len(report.warnings) == 1
    assert report.warnings[0].startswith(f"{GOOD[0]}: --detail 3 is ignored: the image is drawing (")


@pytest.mark.parametrize("link", ["symbolic", "hard"])
def test_a_planted_lock_file_never_writes_over_a_users_file(tmp_path, link):
    import os

    from img2logo.app.batch.run import LOCK_NAME

    src, out = _two_images(tmp_path), tmp_path / "out"
    out.mkdir()
    mine = tmp_path / "mine.txt"
    mine.write_text("my text\n")
    if link == "symbolic":
        (out / LOCK_NAME).symlink_to(mine)
    else:
        os.link(mine, out / LOCK_NAME)
    with pytest.raises(InvalidParameterError, match=rf"output folder .*out: \{LOCK_NAME}"):
        run_batch(find_images(src), out, jobs=1, progress=False)
    assert mine.read_text() == "my text\n" and sorted(p.name for p in out.iterdir()) == [LOCK_NAME]


@pytest.mark.parametrize("existing", [False, True])
def test_a_batch_into_a_full_disk_leaves_no_lock_file(tmp_path, monkeypatch, existing):
    # A full disk made the lock's process id unwritable: an empty lock file stayed behind.
    import errno
    import os

    from img2logo.app.batch.folder import batch_lock
    from img2logo.errors import OutputError

    out = tmp_path / "out"
    if existing:
        out.mkdir()

    def full(fd, data, offset):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(os, "pwrite", full)
    with pytest.raises(OutputError, match=r"No space left on device"):
        with batch_lock(out):
            pass
    assert (sorted(out.iterdir()) == []) if existing else not out.exists()


_WORKER_PROBE = """
import gc, sys
import img2logo.app.batch.pool as pool

def probe(path, options, outputs, fill):  # what a worker holds when its first image comes
    loaded = ("matplotlib.backends.backend_agg" in sys.modules, "img2logo.pipeline" in sys.modules)
    state = (*loaded, gc.get_freeze_count() > 0)
    return {"image": path, "path": path, "seconds": 0.0, "warnings": [], "error": repr(state)}

pool.process_image = probe
outputs = tuple(sys.argv[1].split(","))
results = pool.run_tasks([("a.png", None, outputs, "none"), ("b.png", None, outputs, "none")], None, 2, False)
print(sorted({r["error"] for r in results}))
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="workers forked from a warm parent")
@pytest.mark.parametrize(("outputs", "drawn"), [("svg,json,png", True), ("svg,json", False)])
def test_workers_start_warm_with_their_inherited_heap_frozen(outputs, drawn):
    """The default pool's workers are forked with the pipeline (and for PNGs matplotlib's canvas) loaded, the
    inherited objects out of the garbage collector's sight."""
    import os

    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    done = subprocess.run(
        [sys.executable, "-c", _WORKER_PROBE, outputs], capture_output=True, text=True, env=env, timeout=300, check=True
    )
    assert done.stdout.strip() == repr([repr((drawn, True, True))])


def _report(rows: int, failures: int) -> BatchReport:
    """A report of ``rows`` images done and ``failures`` failed, interleaved, with names that need quoting."""
    from img2logo.app.batch.report import BatchFailure, BatchRow

    names = ["=SUM(1).png", 'a "quoted", name.png', "plain.png", "@at.png", "-minus.png", "tab\tname.png", "x.png"]
    done, failed, inputs = [], [], []
    for i in range(rows + failures):
        name = names[i % len(names)] if i < len(names) else f"img{i}.png"
        path = f"in/{name}"
        inputs.append(path)
        if (i % 2 and len(failed) < failures) or len(done) == rows:
            failed.append(BatchFailure(name, path, f'{path}: not a readable image, 3.5 MB, "odd" {i}'))
        else:
            seconds, similarity = 10.0 ** (i - 3) / 3.0, 4.0 / (i + 1)
            done.append(BatchRow(name, path, "clipart", 10 + i, 3 + i, similarity, seconds, (), "" if i % 3 else "+90"))
    return BatchReport(tuple(done), tuple(failed), tuple(inputs))


@pytest.mark.parametrize(("rows", "failures"), [(4, 3), (5, 0), (0, 2)])
def test_summary_csv_text_is_that_of_pandas(rows, failures):
    """``summary.csv`` is written without pandas, as pandas writes the safe table (``csv_safe(to_frame())``)."""
    from img2logo.app.batch.report import csv_safe

    report = _report(rows, failures)
    expected = csv_safe(report.to_frame()).to_csv(index=False, lineterminator="\n", float_format="%.6g")
    assert report.summary_csv() == expected
