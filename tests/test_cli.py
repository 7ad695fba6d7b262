"""The img2logo command line: outputs, messages, exit codes."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
from conftest import DATA

from img2logo.cli import EXIT_ERROR, main


def test_segments_png_is_written(tmp_path, capsys):
    out = tmp_path / "sub" / "fish.png"
    assert main([str(DATA / "drawing-fish.png"), "--segments-png", str(out)]) == 0
    import matplotlib.image

    assert matplotlib.image.imread(out).shape[:2] == (512, 512)
    err = capsys.readouterr().err
    assert "kind drawing" in err and "segment graph:" in err and f"wrote {out}" in err


def test_kind_and_rdp_options_change_the_graph(tmp_path, capsys):
    assert main([str(DATA / "drawing-fish.png"), "--rdp", "1"]) == 0
    fine = capsys.readouterr().err
    assert main([str(DATA / "drawing-fish.png"), "--rdp", "8", "--kind", "drawing"]) == 0
    coarse = capsys.readouterr().err

    def segments(text: str) -> int:
        return int(text.split("segment graph: ")[1].split(" ")[0])

    assert segments(fine) > segments(coarse)


def test_quiet_prints_nothing(tmp_path, capsys):
    assert main([str(DATA / "drawing-leaf.png"), "-q", "--segments-png", str(tmp_path / "a.png")]) == 0
    assert capsys.readouterr().err == ""


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda d: d / "missing.png", "image file not found"),
        (lambda d: (d / "t.png").write_text("hello") and d / "t.png", "not a readable image"),
    ],
)
def test_bad_input_is_one_line_and_exit_two(tmp_path, capsys, make, message):
    out = tmp_path / "out.png"
    status = main([str(make(tmp_path)), "--segments-png", str(out)])
    err = capsys.readouterr().err
    assert status == EXIT_ERROR
    assert err.startswith("img2logo: error: ") and message in err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert not out.exists()


def test_blank_image_message(tmp_path, capsys):
    import cv2

    path = tmp_path / "white.png"
    cv2.imwrite(str(path), np.full((64, 64, 3), 255, np.uint8))
    assert main([str(path)]) == EXIT_ERROR
    assert "image is blank" in capsys.readouterr().err


def test_bad_option_value_is_a_usage_error(capsys):
    with pytest.raises(SystemExit) as exc:
        main([str(DATA / "drawing-fish.png"), "--kind", "painting"])
    assert exc.value.code == 2
    assert "invalid choice: 'painting'" in capsys.readouterr().err


def test_zero_rdp_tolerance_is_refused(capsys):
    assert main([str(DATA / "drawing-fish.png"), "--rdp", "0"]) == EXIT_ERROR
    assert "rdp_tolerance must be > 0" in capsys.readouterr().err


def test_console_entry_point_runs():
    done = subprocess.run(
        [sys.executable, "-m", "img2logo.cli", "--version"], capture_output=True, text=True, check=False
    )
    assert done.returncode == 0 and done.stdout.startswith("img2logo ")
