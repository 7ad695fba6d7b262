"""The img2logo command line: outputs, messages, exit codes."""

from __future__ import annotations

import os
import re
import subprocess
import sys

import numpy as np
import pytest
from helpers import DATA, modules_loaded

from img2logo.app.cli import EXIT_ERROR, main


def test_segments_png_is_written(tmp_path, capsys):
    out = tmp_path / "sub" / "fish.png"
    assert main([str(DATA / "drawing-fish.png"), "--segments-png", str(out)]) == 0
    import matplotlib.image

    assert matplotlib.image.imread(out).shape[:2] == (512, 512)
    err = capsys.readouterr().err
    assert "kind drawing" in err and "segment graph:" in err and f"wrote {out}" in err


def test_kind_and_rdp_options_change_the_graph(tmp_path, capsys):
    out = ["--json", str(tmp_path / "fish.json")]
    assert main([str(DATA / "drawing-fish.png"), "--rdp", "1", *out]) == 0
    fine = capsys.readouterr().err
    assert main([str(DATA / "drawing-fish.png"), "--rdp", "8", "--kind", "drawing", *out]) == 0
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
    assert main([str(path), "--json", str(tmp_path / "white.json")]) == EXIT_ERROR
    assert "image is blank" in capsys.readouterr().err


def test_bad_option_value_is_a_usage_error(capsys):
    with pytest.raises(SystemExit) as exc:
        main([str(DATA / "drawing-fish.png"), "--kind", "painting"])
    assert exc.value.code == 2
    assert "invalid choice: 'painting'" in capsys.readouterr().err


def test_zero_rdp_tolerance_is_refused(capsys):
    assert main([str(DATA / "drawing-fish.png"), "--rdp", "0"]) == EXIT_ERROR
    assert "img2logo: error: --rdp must be > 0, got 0.0" in capsys.readouterr().err


def test_console_entry_point_runs():
    done = subprocess.run(
        [sys.executable, "-m", "img2logo.app.cli", "--version"], capture_output=True, text=True, check=False
    )
    assert done.returncode == 0 and done.stdout.startswith("img2logo ")


# --------------------------------------------------------------------------- logo outputs
def test_logo_outputs_are_written_and_valid(tmp_path, capsys):
    pytest.importorskip("jsonschema")
    import json
    import xml.etree.ElementTree as ET

    from img2logo.export.contract import validate_document

    out = tmp_path / "o"
    args = [str(DATA / "drawing-fish.png"), "--svg", str(out / "a.svg"), "--json", str(out / "a.json")]
    assert main([*args, "--png", str(out / "a.png")]) == 0
    doc = json.loads((out / "a.json").read_text())
    validate_document(doc)
    root = ET.parse(out / "a.svg").getroot()
    paths = [e for e in root.iter() if e.tag.endswith("path")]
    assert len(paths) == len(doc["arcs"])
    assert "levels:" in capsys.readouterr().err


def test_same_input_same_bytes(tmp_path):
    for name in ("a", "b"):
        assert main([str(DATA / "drawing-leaf.png"), "-q", "--json", str(tmp_path / f"{name}.json")]) == 0
        assert main([str(DATA / "drawing-leaf.png"), "-q", "--svg", str(tmp_path / f"{name}.svg")]) == 0
    assert (tmp_path / "a.json").read_bytes() == (tmp_path / "b.json").read_bytes()
    assert (tmp_path / "a.svg").read_bytes() == (tmp_path / "b.svg").read_bytes()


def test_levels_dir_and_level(tmp_path, capsys):
    import json

    args = ["--levels-dir", str(tmp_path / "lv"), "--json", str(tmp_path / "0.json"), "--level", "0"]
    assert main([str(DATA / "drawing-fish.png"), *args]) == 0
    files = sorted((tmp_path / "lv").glob("level-*.json"))
    assert files[0].name == "level-0000.json" and len(files) >= 2
    assert len(sorted((tmp_path / "lv").glob("level-*.svg"))) == len(files)
    assert json.loads((tmp_path / "0.json").read_text())["level"] == 0
    counts = [len(json.loads(f.read_text())["arcs"]) for f in files]
    assert counts == sorted(counts, reverse=True)


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--level", "999"], "--level must be in 0.."),
        (["--radii", "3,x"], "--radii must be integers separated by commas"),
        (["--tolerance", "0"], "error: --tolerance must be > 0"),
        (["--bias", "1.5"], r"error: --bias must be in [0, 1)"),
        (["--unit", "2"], "error: --unit is a parameter of the Fibonacci ladder (ladder='fibonacci')"),
        (["--ladder", "fibonacci", "--bias", "0.2"], "error: --bias is a parameter of the phi ladder"),
        (["--ladder", "fibonacci", "--unit", "0"], "error: --unit must be > 0, got 0.0"),
        (["--ladder", "fibonacci", "--radii", "1,5"], "error: --radii of the Fibonacci ladder must be >= 2"),
    ],
)
def test_bad_logo_options(tmp_path, capsys, args, message):
    out = tmp_path / "x.json"
    assert main([str(DATA / "drawing-leaf.png"), "--json", str(out), *args]) == EXIT_ERROR
    err = capsys.readouterr().err
    last = err.strip().splitlines()[-1]
    assert last.startswith("img2logo: error: ") and message in last
    assert "Traceback" not in err
    assert not out.exists()


def test_radii_option_restricts_the_circles(tmp_path):
    import json

    out = tmp_path / "r.json"
    assert main([str(DATA / "drawing-leaf.png"), "-q", "--radii", "9,10,11", "--json", str(out)]) == 0
    assert {c["k"] for c in json.loads(out.read_text())["circles"]} <= {9, 10, 11}


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--rdp", "1e308"], "error: --rdp must be at most 1e+07 px (longer than any image), got 1e+308"),
        (["--rdp", "1e200"], "error: --rdp must be at most 1e+07 px"),
        (["--ladder", "fibonacci", "--unit", "1e308"], "error: --unit must be in 0.001..1e+07 px, got 1e+308"),
        (["--radii", "99999"], "error: --radii must be in -14..33"),
        (["--radii=-1000000"], "error: --radii must be in -14..33"),
        (["--tolerance", "1e308"], "error: --tolerance must be at most 1e+07 px"),
        (["--tolerance", "nan"], "error: --tolerance must be finite, got nan"),
        (["--min-length", "-5"], "error: --min-length must be >= 0, got -5.0"),
        (["--bias", "1.5"], "error: --bias must be in [0, 1), got 1.5"),
        (["--stroke-width", "1e308"], "error: --stroke-width must be at most 1e+07 px"),
        (["--symmetry", "nan"], "error: --symmetry angle must be a number of degrees in -360..360, got 'nan'"),
        (["--symmetry", "1e308"], "error: --symmetry angle must be a number of degrees in -360..360, got '1e308'"),
        (["--png", "o.png", "--png-scale", "1e308"], "error: --png-scale 1e+308 makes the PNG inf px on its longer"),
        (["--png", "o.png", "--png-scale", "inf"], "error: --png-scale must be a finite number > 0, got inf"),
        (["--subject", "1e308,0,5,5"], "error: --subject 1e308,0,5,5 must cover at least 4x4 px of the 512x512 image"),
        (["--ladder", "fibonacci", "--unit", "1e5"], "the smallest, 1e+05 px, is over 20 x the image's longer side"),
        (["--radii", "25"], "choose smaller exponents (--radii)"),
    ],
)
def test_huge_lengths_and_radii_are_one_line_with_nothing_on_stdout(tmp_path, capfd, args, message):
    # a cv2.error, LAPACK lines on stdout, numpy overflow warnings before.
    out = tmp_path / "x.json"
    args = [str(tmp_path / a) if a == "o.png" else a for a in args]
    assert main([str(DATA / "drawing-leaf.png"), "-q", "--json", str(out), *args]) == EXIT_ERROR
    captured = capfd.readouterr()
    assert captured.out == ""
    assert captured.err.startswith("img2logo: error: ") and captured.err.count("\n") == 1
    assert message in captured.err and "Warning" not in captured.err
    assert not out.exists()


def test_no_tangency_is_recorded_in_the_params(tmp_path):
    import json

    on, off = tmp_path / "on.json", tmp_path / "off.json"
    assert main([str(DATA / "drawing-leaf.png"), "-q", "--json", str(on)]) == 0
    assert main([str(DATA / "drawing-leaf.png"), "-q", "--no-tangency", "--json", str(off)]) == 0
    assert json.loads(on.read_text())["params"]["tangency"] is True
    assert json.loads(off.read_text())["params"]["tangency"] is False


def test_lock_mask_of_the_wrong_size(tmp_path, capsys):
    import cv2

    mask = tmp_path / "mask.png"
    cv2.imwrite(str(mask), np.full((40, 40), 255, np.uint8))
    assert main([str(DATA / "drawing-leaf.png"), "--lock-mask", str(mask), "--json", str(tmp_path / "l.json")]) == 2
    assert "mask must have the image's shape (512, 512), got (40, 40)" in capsys.readouterr().err


def test_all_white_lock_mask_is_accepted(tmp_path):
    import cv2

    mask = tmp_path / "mask.png"
    cv2.imwrite(str(mask), np.full((512, 512), 255, np.uint8))
    out = tmp_path / "l.json"
    assert main([str(DATA / "drawing-fish.png"), "-q", "--lock-mask", str(mask), "--json", str(out)]) == 0
    import json

    assert json.loads(out.read_text())["params"]["locked_segments"] > 0


# --------------------------------------------------------------------------- the Fibonacci ladder
@pytest.mark.parametrize("unit", [None, "2.5"])
def test_fibonacci_ladder_gives_a_valid_document_in_fibonacci_proportion(tmp_path, capsys, unit):
    pytest.importorskip("jsonschema")
    import json

    from img2logo.export.contract import validate_document
    from img2logo.geometry.golden_ladder import fibonacci

    out = tmp_path / "f.json"
    args = [str(DATA / "drawing-leaf.png"), "--ladder", "fibonacci", "--json", str(out)]
    assert main([*args, *(["--unit", unit] if unit else [])]) == 0
    assert "Fibonacci unit" in capsys.readouterr().err
    doc = json.loads(out.read_text())
    validate_document(doc)
    assert doc["ladder"] == "fibonacci" and doc["bias"] == 0.0 and doc["params"]["ladder"] == "fibonacci"
    if unit is not None:
        assert doc["unit"] == float(unit)
    else:
        assert 0.5 < doc["unit"] <= 1.0  # the largest unit <= 1 px putting the longest radius on a rung
    fib = {fibonacci(k) for k in range(2, 60)}
    for c in doc["circles"]:
        ratio = c["r"] / doc["unit"]
        assert round(ratio) in fib and ratio == pytest.approx(round(ratio), rel=1e-9)
        assert round(ratio) == fibonacci(c["k"])


# --------------------------------------------------------------------------- img2logo batch
def _batch_folder(tmp_path, names=("drawing-leaf.png", "drawing-snail.png"), bad=True):
    import shutil

    folder = tmp_path / "in"
    folder.mkdir()
    for name in names:
        shutil.copy(DATA / name, folder / name)
    if bad:
        (folder / "corrupt.png").write_text("not an image at all")
    return folder


def test_batch_command_reports_a_bad_file_and_exits_one(tmp_path, capsys):
    from img2logo.app.cli import EXIT_FAILED

    folder, out = _batch_folder(tmp_path), tmp_path / "out"
    assert main(["batch", str(folder), str(out), "--jobs", "2", "--tolerance", "6"]) == EXIT_FAILED == 1
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert lines[-1].startswith("img2logo: error: ") and "corrupt.png: not a readable image" in lines[-1]
    assert err.count("corrupt.png: not a readable image") == 1 and "Traceback" not in err
    # Off a terminal, one line per image done says the batch's progress (in the order they finish).
    assert sorted(line.split(": ", 1)[1] for line in lines if " done: " in line) == sorted(
        ["corrupt.png", "drawing-leaf.png", "drawing-snail.png"]
    )
    assert "drawing-leaf.png" in err and "E^s (px)" in err and "2 of 3 images done" in err
    names = sorted(p.name for p in out.iterdir())
    logos = [f"drawing-{n}.{f}" for n in ("leaf", "snail") for f in ("svg", "json", "png")]
    assert names == sorted([".img2logo-outputs", "index.html", "summary.csv", *logos])
    summary = (out / "summary.csv").read_text().splitlines()
    assert summary[0] == "image,kind,arcs,levels,similarity,symmetry,seconds,error"
    assert [line.split(",")[0] for line in summary[1:]] == ["corrupt.png", "drawing-leaf.png", "drawing-snail.png"]


def test_batch_command_all_good_is_quiet_and_exits_zero(tmp_path, capsys):
    import json

    folder, out = _batch_folder(tmp_path, names=("drawing-leaf.png",), bad=False), tmp_path / "out"
    options = ["--ladder", "fibonacci", "--fill", "palette:#ff0000,#00ff00", "--rdp", "3"]
    assert main(["batch", str(folder), str(out), "-q", *options]) == 0
    assert capsys.readouterr().err == ""
    single = tmp_path / "single.json"
    assert main([str(folder / "drawing-leaf.png"), "-q", "--json", str(single), *options]) == 0
    assert (out / "drawing-leaf.json").read_bytes() == single.read_bytes()  # the options are passed on
    doc = json.loads(single.read_text())
    assert doc["ladder"] == "fibonacci" and doc["fills"] and doc["params"]["rdp_tolerance"] == 3.0


@pytest.mark.parametrize(
    ("make", "args", "message"),
    [
        (lambda d: d / "missing", [], "input folder not found"),
        (lambda d: d, [], "no images (png, jpg, jpeg, tif, tiff, bmp, webp) in"),
        (lambda d: d, ["--jobs", "0"], "--jobs must be >= 1, got 0"),
        (lambda d: d, ["--tolerance", "-1"], "--tolerance must be > 0"),
    ],
)
def test_batch_command_errors_exit_two(tmp_path, capsys, make, args, message):
    assert main(["batch", str(make(tmp_path)), str(tmp_path / "out"), *args]) == EXIT_ERROR
    err = capsys.readouterr().err
    assert err.startswith("img2logo: error: ") and message in err and err.count("\n") == 1
    assert not (tmp_path / "out").exists()


def test_no_output_is_refused_before_any_work(tmp_path, capsys, monkeypatch):
    """Without an output flag nothing would be written: one line, exit 2, before the image is even read."""
    import img2logo.images.loading
    import img2logo.pipeline  # imported first: it binds load_image when it is imported

    def never(*a, **k):
        raise AssertionError("the image was loaded")

    monkeypatch.setattr(img2logo.images.loading, "load_image", never)
    monkeypatch.setattr(img2logo.pipeline, "abstract", never)
    assert main([str(DATA / "drawing-fish.png")]) == EXIT_ERROR
    err = capsys.readouterr().err
    assert err == (
        "img2logo: error: nothing to write: give --svg, --json, --png, --pdf, --segments-png or --levels-dir\n"
    )


def test_clean_png_and_pdf_outputs(tmp_path, capsys):
    import matplotlib.image

    out = tmp_path / "o"
    args = [str(DATA / "drawing-leaf.png"), "--png", str(out / "leaf.png"), "--pdf", str(out / "leaf.pdf")]
    assert main([*args, "--png-background", "transparent", "--png-scale", "0.5"]) == 0
    png = matplotlib.image.imread(out / "leaf.png")
    assert png.shape == (256, 256, 4) and png[0, 0, 3] == 0.0 and png[..., 3].max() > 0.5
    assert (out / "leaf.pdf").read_bytes().startswith(b"%PDF-")
    err = capsys.readouterr().err
    assert f"wrote {out / 'leaf.png'}" in err and f"wrote {out / 'leaf.pdf'}" in err
    assert main([*args, "--png-scale", "0"]) == EXIT_ERROR
    assert capsys.readouterr().err == "img2logo: error: --png-scale must be a finite number > 0, got 0\n"
    assert main([*args, "--png-scale", "100"]) == EXIT_ERROR
    assert capsys.readouterr().err.endswith(
        "\nimg2logo: error: --png-scale 100 makes the PNG 51200 px on its longer side; it must be 1..4096 "
        "over the faded input (--png-background white or transparent: 1..16384)\n"
    )
    assert main([*args, "--png-scale", "100", "--png-background", "white"]) == EXIT_ERROR
    assert "makes the PNG 51200 px on its longer side; it must be 1..16384\n" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        main([*args, "--png-background", "black"])
    assert "invalid choice: 'black'" in capsys.readouterr().err


def test_help_has_examples_for_designers(capsys):
    with pytest.raises(SystemExit):
        main(["--help"])
    text = capsys.readouterr().out
    examples = text.split("examples:\n", 1)[1]
    for line in ("img2logo cat.png --svg cat.svg", "--png-background transparent", "--pdf cat.pdf", "img2logo batch"):
        assert line in examples
    # Each example is a command the parser accepts.
    from img2logo.app.cli import build_parser

    for command in re.findall(r"^  (img2logo (?!batch).*)$", examples, re.M):
        build_parser().parse_args(command.split()[1:])


def test_help_mentions_batch(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["--help"])
    assert exc.value.code == 0
    text = capsys.readouterr().out
    assert "img2logo batch INPUT_DIR OUTPUT_DIR" in text and "--ladder {phi,fibonacci}" in text
    with pytest.raises(SystemExit) as exc:
        main(["batch", "--help"])
    assert exc.value.code == 0
    text = capsys.readouterr().out
    assert text.startswith("usage: img2logo batch") and "--jobs N" in text and "--lock-mask" not in text


def test_lines_option(tmp_path):
    import json

    import cv2

    path = tmp_path / "frame.png"
    im = np.full((240, 240, 3), 255, np.uint8)
    cv2.rectangle(im, (40, 60), (200, 180), (0, 0, 0), 3)
    cv2.imwrite(str(path), im)
    for flag, expected in (([], 0), (["--lines"], 4)):
        out = tmp_path / f"f{len(flag)}.json"
        assert main([str(path), "-q", "--json", str(out), *flag]) == 0
        assert len(json.loads(out.read_text())["extra"].get("lines", [])) == expected


def test_a_photo_without_an_object_says_how_to_choose_one(tmp_path, capsys):
    import cv2
    from helpers import textured_photo

    from img2logo.app.commands import SUBJECT_HINT

    rgb, _ = textured_photo([])  # pure texture: no dominant object, the whole image is drawn
    path = tmp_path / "texture.png"
    cv2.imwrite(str(path), (rgb[:, :, ::-1] * 255).round().astype(np.uint8))
    assert main([str(path), "--kind", "photo", "--json", str(tmp_path / "t.json")]) == 0
    err = capsys.readouterr().err
    assert "subject: kept the whole image: no dominant object" in err
    assert f"subject: {SUBJECT_HINT}" in err
    assert main([str(path), "--kind", "photo", "--foreground", "none", "--json", str(tmp_path / "t.json")]) == 0
    assert SUBJECT_HINT not in capsys.readouterr().err  # asked for: no hint


def test_photo_subject_is_reported_and_can_be_chosen(tmp_path, capsys):
    import cv2
    from helpers import textured_photo

    rgb, _ = textured_photo([(90, 120, 60, 60, (0.9, 0.2, 0.3)), (250, 120, 55, 55, (0.2, 0.4, 0.95))], size=(240, 340))
    path = tmp_path / "two.png"
    cv2.imwrite(str(path), (rgb[:, :, ::-1] * 255).round().astype(np.uint8))
    out = ["--json", str(tmp_path / "two.json")]
    assert main([str(path), "--kind", "photo", "--subject", "185,55,130,130", *out]) == 0
    assert "subject: kept the object in 185,55,130,130 (GrabCut)" in capsys.readouterr().err
    assert main([str(path), "--kind", "photo", "--foreground", "none", *out]) == 0
    assert "subject: kept the whole image (foreground none)" in capsys.readouterr().err
    out = tmp_path / "x.json"
    for args, message in [
        (["--foreground", "magic"], "error: --foreground must be one of auto, none, grabcut"),
        (["--foreground", str(tmp_path / "missing.png")], f"--foreground: image file not found: {tmp_path}"),
        (["--lock-mask", str(tmp_path / "missing.png")], f"--lock-mask: image file not found: {tmp_path}"),
        (["--foreground", str(DATA / "photo-cat.png")], "--foreground: "),
        (["--subject", "1,2"], "error: --subject must be a rectangle X,Y,W,H"),
    ]:
        assert main([str(path), "--kind", "photo", "--json", str(out), *args]) == EXIT_ERROR
        err = capsys.readouterr().err
        assert err.strip().splitlines()[-1].startswith("img2logo: error: ") and message in err
        assert not out.exists()
    # A missing mask is a bad option on any image, before the work: a drawing (whose subject options
    # are ignored) does not run with it either.
    assert main([str(DATA / "drawing-fish.png"), "--foreground", str(tmp_path / "m.png"), "--json", str(out)]) == 2
    err = capsys.readouterr().err
    assert err == f"img2logo: error: --foreground: image file not found: {tmp_path / 'm.png'}\n" and not out.exists()


# --------------------------------------------------------------------------- never lose data
def _copy(tmp_path, name="drawing-leaf.png"):
    import shutil

    return shutil.copy(DATA / name, tmp_path / "in.png")


@pytest.mark.parametrize(
    ("outputs", "message"),
    [
        (["--png", "{in}"], r"--png .*in\.png is the input .*in\.png: refusing to write over an input"),
        (["--svg", "{dir}/link.svg"], r"link\.svg is the input"),
        (["--svg", "{dir}/o.out", "--json", "{dir}/o.out"], r"--json and --svg name the same file .*o\.out"),
        (["--svg", "{dir}/file/a.svg"], r"--svg .*a\.svg: .*file is not a folder"),
        (["--svg", "{dir}/folder"], r"--svg .*folder is a folder"),
        (["--svg", "{dir}/pipe.svg"], r"--svg .*pipe\.svg is not a regular file"),
        (["--levels-dir", "{dir}/file"], r"--levels-dir .*file is a file, not a folder"),
        (["--levels-dir", "{dir}", "--svg", "{dir}/level-0000.svg"], r"inside --levels-dir"),
        (["--min-length", "-5"], r"--min-length must be >= 0, got -5\.0"),
        (["--foreground", "{dir}/mask.png", "--png", "{dir}/mask.png"], r"--png .*mask\.png is the input .*mask\.png"),
        (["--foreground", "{dir}/mask.png", "--svg", "{dir}/mlink.svg"], r"mlink\.svg is the input .*mask\.png"),
        (["--lock-mask", "{dir}/mask.png", "--json", "{dir}/mask.png"], r"--json .*mask\.png is the input .*mask\.png"),
        (["--levels-dir", "{dir}/lv"], r"--levels-dir .*lv: .*level-0003\.json is the input .*in\.png"),
        (["--lock-mask", "{dir}/mask.png", "--levels-dir", "{dir}/lv2"], r"level-0001\.svg is the input .*mask\.png"),
        (["--svg", "{dir}/o.pdf"], r"--svg .*o\.pdf: \.pdf names another format \(--svg writes SVG\)"),
        (["--svg", "{dir}/o.svgz"], r"\.svgz names another format"),
        (
            ["--png", "{dir}/o.jpg"],
            r"--png .*o\.jpg: \.jpg names another format \(--png writes PNG\); .*ending in \.png",
        ),
        (["--json", "{dir}/o.svg"], r"--json .*o\.svg: \.svg names another format"),
        (["--segments-png", "{dir}/o.tiff"], r"\.tiff names another format"),
    ],
)
def test_bad_outputs_are_refused_before_any_work(tmp_path, capsys, outputs, message):
    import shutil

    src = _copy(tmp_path)
    before = (tmp_path / "in.png").read_bytes()
    (tmp_path / "link.svg").symlink_to(src)
    (tmp_path / "file").write_text("x")
    (tmp_path / "folder").mkdir()
    os.mkfifo(tmp_path / "pipe.svg")  # no regular file, like a device: never opened
    mask = shutil.copy(DATA / "drawing-leaf.png", tmp_path / "mask.png")  # 512 x 512 like the input
    (tmp_path / "mlink.svg").symlink_to(mask)
    (tmp_path / "lv").mkdir()
    (tmp_path / "lv" / "level-0003.json").symlink_to(src)  # a level file of the folder that is the input
    (tmp_path / "lv2").mkdir()
    os.link(mask, tmp_path / "lv2" / "level-0001.svg")  # a hard link: the same file under a level's name
    masked = mask.read_bytes()
    names = sorted(p.name for p in tmp_path.iterdir())
    args = [a.replace("{in}", str(src)).replace("{dir}", str(tmp_path)) for a in outputs]
    assert main([str(src), *args]) == EXIT_ERROR
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("img2logo: error: ")
    assert re.search(message, err), err
    assert "kind" not in err  # refused before the run
    assert (tmp_path / "in.png").read_bytes() == before and sorted(p.name for p in tmp_path.iterdir()) == names
    assert mask.read_bytes() == masked and sorted(p.name for p in (tmp_path / "lv").iterdir()) == ["level-0003.json"]


def test_batch_into_its_own_input_folder_is_refused(tmp_path, capsys):
    folder = _batch_folder(tmp_path, bad=False)
    before = {p.name: p.read_bytes() for p in folder.iterdir()}
    assert main(["batch", str(folder), str(folder)]) == EXIT_ERROR
    err = capsys.readouterr().err
    assert err.startswith("img2logo: error: output folder ") and err.count("\n") == 1
    assert "drawing-leaf.png is the input" in err
    assert {p.name: p.read_bytes() for p in folder.iterdir()} == before


def test_a_write_error_is_one_line_exit_one_and_leaves_no_partial_set(tmp_path, capsys, monkeypatch):
    from img2logo.app.cli import EXIT_FAILED
    from img2logo.errors import OutputError
    from img2logo.export import writers

    real = writers.atomic_write

    def full_disk(path, write):  # the PNG, written after the JSON and the SVG
        if str(path).endswith(".png"):
            raise OutputError(f"cannot write {path}: No space left on device")
        return real(path, write)

    monkeypatch.setattr(writers, "atomic_write", full_disk)
    out = tmp_path / "new" / "deeper"
    args = ["--json", str(out / "a.json"), "--svg", str(out / "a.svg"), "--png", str(out / "a.png")]
    assert main([str(DATA / "drawing-leaf.png"), *args]) == EXIT_FAILED
    err = capsys.readouterr().err
    assert err.splitlines()[-1] == f"img2logo: error: cannot write {out / 'a.png'}: No space left on device"
    assert list(tmp_path.iterdir()) == []  # no JSON, no SVG, no temporary file, no folder


def test_out_of_memory_is_one_line_exit_one(tmp_path, capsys, monkeypatch):
    import img2logo.pipeline
    from img2logo.app.cli import EXIT_FAILED

    def no_memory(*args, **kwargs):
        raise MemoryError

    monkeypatch.setattr(img2logo.pipeline, "abstract", no_memory)
    assert main([str(DATA / "drawing-leaf.png"), "-q", "--svg", str(tmp_path / "a.svg")]) == EXIT_FAILED
    assert capsys.readouterr().err == "img2logo: error: out of memory; try a smaller image or fewer --jobs\n"
    assert list(tmp_path.iterdir()) == []


def test_a_run_removes_stale_temporary_files_of_its_targets(tmp_path):
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    stale = tmp_path / f".a.svg.{dead.pid}-0123abcd.tmp"
    stale.write_text("left by a killed run")
    assert main([str(DATA / "drawing-leaf.png"), "-q", "--svg", str(tmp_path / "a.svg")]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.svg"]


def test_messages_name_the_input_and_carry_no_third_party_lines(tmp_path):
    truncated = tmp_path / "cut.png"
    truncated.write_bytes((DATA / "clipart-fish.png").read_bytes()[:3000])
    done = subprocess.run(
        [sys.executable, "-m", "img2logo.app.cli", str(truncated), "--json", str(tmp_path / "cut.json")],
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == EXIT_ERROR
    assert (
        done.stderr == f"img2logo: error: {truncated}: not a readable image: the PNG ends before its IEND chunk "
        "(the file cut short?)\n"
    )


def test_downscale_is_reported_before_the_run(tmp_path, capsys):
    import cv2

    big = tmp_path / "big.png"
    cv2.imwrite(str(big), cv2.resize(cv2.imread(str(DATA / "drawing-leaf.png")), (2600, 2600)))
    assert main([str(big), "--json", str(tmp_path / "big.json")]) == 0
    err = capsys.readouterr().err.splitlines()
    assert err[0] == f"img2logo: warning: {big}: image is 2600x2600 px, larger than 2048 px; downscaled to 2048x2048 px"
    assert err[1].startswith(f"{big}: 2048x2048 px")


def test_png_of_an_input_over_the_working_size_is_drawn_at_the_working_size(tmp_path, capsys):
    """A 12000 px input's PNG at its full size took 12 GB and minutes: by default it is 2048 px."""
    import json

    import cv2

    big = tmp_path / "big.png"
    cv2.imwrite(str(big), cv2.resize(cv2.imread(str(DATA / "drawing-leaf.png")), (2600, 2080)))
    png, json_path = tmp_path / "big-logo.png", tmp_path / "big.json"
    assert main([str(big), "--png", str(png), "--json", str(json_path)]) == 0
    err = capsys.readouterr().err
    line = "png: drawn at 2048x1638 px (the input is 2600x2080 px; --png-scale S draws S times that)"
    assert line in err.splitlines()
    assert cv2.imread(str(png)).shape[:2] == (1638, 2048)
    assert json.loads(json_path.read_text())["width"] == 2600  # the document stays in the input's pixels
    # An explicit scale is the input's times it, checked before the work (one line, nothing written).
    assert main([str(big), "--png", str(tmp_path / "x2.png"), "--png-scale", "2"]) == EXIT_ERROR
    err = capsys.readouterr().err
    assert "--png-scale 2 makes the PNG 5200 px on its longer side; it must be 1..4096" in err
    assert not (tmp_path / "x2.png").exists() and "levels:" not in err
    assert main([str(big), "-q", "--png", str(tmp_path / "s.png"), "--png-scale", "0.1"]) == 0
    assert cv2.imread(str(tmp_path / "s.png")).shape[:2] == (208, 260)


def _default_signals() -> None:
    """In the child: SIGINT as a terminal gives it, also when the suite runs with it ignored (``(make test &)``)."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _run_until(args, line_start: str, cwd):
    """Start the command; return the process once it printed a line starting with ``line_start``."""
    proc = subprocess.Popen(
        [sys.executable, "-m", "img2logo.app.cli", *args],
        stderr=subprocess.PIPE,
        text=True,
        cwd=cwd,
        preexec_fn=_default_signals,  # no thread starts between the fork and the exec
    )
    for line in proc.stderr:
        if line.startswith(line_start):
            return proc
    proc.wait()
    raise AssertionError(f"the command ended before printing {line_start!r}")


@pytest.mark.parametrize(("sig", "status", "word"), [("SIGINT", 130, "interrupted"), ("SIGTERM", 143, "terminated")])
def test_interrupt_is_one_line_and_leaves_nothing(tmp_path, sig, status, word):
    import signal

    src = DATA / "photo-cat.png"
    proc = _run_until([str(src), "--svg", "o/a.svg", "--json", "o/a.json"], f"{src}:", tmp_path)
    try:
        proc.send_signal(getattr(signal, sig))
        rest = proc.stderr.read()
        assert proc.wait(timeout=60) == status
    finally:
        proc.kill()
        proc.wait()
    assert rest.endswith(f"img2logo: {word}; nothing more written\n") and "Traceback" not in rest
    assert list(tmp_path.iterdir()) == []


def _children(pid: int) -> list[int]:
    """Live (not zombie) processes whose parent is ``pid``, from /proc."""
    from pathlib import Path

    kids = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == pid and fields[0] != "Z":
            kids.append(int(stat.parent.name))
    return kids


def _alive(pid: int) -> bool:
    from pathlib import Path

    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
@pytest.mark.parametrize("sig", ["SIGKILL", "SIGTERM"])
def test_batch_workers_end_with_their_parent(tmp_path, sig):
    import shutil
    import signal
    import time

    folder = tmp_path / "in"
    folder.mkdir()
    for i in range(4):
        shutil.copy(DATA / "photo-cat.png", folder / f"cat{i}.png")
    proc = _run_until(["batch", str(folder), str(tmp_path / "out"), "--jobs", "2"], f"{folder}: 4 images", tmp_path)
    workers: list[int] = []
    try:
        deadline = time.monotonic() + 60
        while len(workers) < 2 and time.monotonic() < deadline:
            workers = _children(proc.pid)
            time.sleep(0.05)
        assert len(workers) == 2
        proc.send_signal(getattr(signal, sig))
        proc.wait(timeout=60)
        deadline = time.monotonic() + 20
        while any(_alive(w) for w in workers) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert not any(_alive(w) for w in workers)
    finally:
        proc.kill()
        proc.wait()
        for w in workers:  # never leave a worker behind, even when the test fails
            if _alive(w):
                os.kill(w, signal.SIGKILL)


# --------------------------------------------------------------------------- the command line
@pytest.mark.parametrize(
    ("args", "message"),
    [
        ([], "the following arguments are required: input"),
        (["in.png", "--kind", "painting"], "argument --kind: invalid choice: 'painting'"),
        (["in.png", "--tolerance"], "argument --tolerance/-T: expected one argument"),
        (["batch"], "the following arguments are required: INPUT_DIR, OUTPUT_DIR"),
        (["batch", "a", "b", "--jobs", "x"], "argument --jobs/-j: invalid int value: 'x'"),
        (
            ["-x.png"],
            "unknown option -x.png (for a file whose name starts with '-', write: img2logo [OPTIONS] -- -x.png)",
        ),
        (
            ["--", "-x.png", "-q"],
            "unrecognized arguments: -q (everything after -- is a file name: put the options before --)",
        ),
        (["in.png", "--svg", "o.svg", "-x.png"], "unknown option -x.png (for a file whose name starts with '-'"),
        (
            ["batch", "-in", "out"],
            "unknown option -in (for a file whose name starts with '-', write: img2logo batch [OPTIONS] -- -in)",
        ),
    ],
)
def test_argument_errors_are_one_line(capsys, args, message):
    with pytest.raises(SystemExit) as exc:
        main(args)
    assert exc.value.code == EXIT_ERROR
    err = capsys.readouterr().err
    assert err.startswith("img2logo: error: ") and err.count("\n") == 1 and "usage:" not in err
    assert message in err, err


def test_negative_numbers_are_option_values_not_unknown_options(capsys):
    assert main([str(DATA / "drawing-leaf.png"), "--min-length", "-5"]) == EXIT_ERROR
    assert capsys.readouterr().err == "img2logo: error: --min-length must be >= 0, got -5.0\n"


def test_a_file_whose_name_starts_with_a_dash_after_two_dashes(tmp_path, monkeypatch, capsys):
    import shutil

    shutil.copy(DATA / "drawing-leaf.png", tmp_path / "-x.png")
    monkeypatch.chdir(tmp_path)
    assert main(["-q", "--svg", "o.svg", "--", "-x.png"]) == 0
    assert (tmp_path / "o.svg").is_file()


def test_python_dash_m_img2logo_runs():
    done = subprocess.run([sys.executable, "-m", "img2logo", "--version"], capture_output=True, text=True, check=False)
    assert done.returncode == 0 and done.stdout.startswith("img2logo ")


def test_a_control_character_in_a_name_cannot_forge_a_line(tmp_path, capsys):
    import shutil

    forged = tmp_path / "a\nimg2logo: error: forged.png"
    assert main([str(forged), "--json", str(tmp_path / "f.json")]) == EXIT_ERROR
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "a\\nimg2logo: error: forged.png" in err
    named = tmp_path / "b\r\x1b[2Kc.png"
    shutil.copy(DATA / "drawing-leaf.png", named)
    assert main([str(named), "--svg", str(tmp_path / "o.svg")]) == 0
    err = capsys.readouterr().err
    assert "\r" not in err and "\x1b" not in err and "b\\r\\x1b[2Kc.png: 512x512 px" in err


def test_subject_options_on_a_drawing_are_ignored_with_one_warning(tmp_path, capsys):
    out = ["--json", str(tmp_path / "leaf.json")]
    assert main([str(DATA / "drawing-leaf.png"), "--subject", "10,10,100,100", "--foreground", "none", *out]) == 0
    warned = [line for line in capsys.readouterr().err.splitlines() if line.startswith("img2logo: warning: ")]
    assert warned == [
        "img2logo: warning: --subject 10,10,100,100 and --foreground none are ignored: the image is drawing "
        f"({warned[0].split('drawing (', 1)[1].split('), and')[0]}), and only a photo has a subject to find "
        "(give --kind photo to treat it as one)"
    ]
    assert main([str(DATA / "drawing-leaf.png"), *out]) == 0
    assert "warning" not in capsys.readouterr().err  # not given: nothing to say


def test_a_logo_brought_to_its_arc_budget_past_t_says_so(tmp_path, capsys):
    import json

    out = tmp_path / "cat.json"
    assert main([str(DATA / "clipart-cat.png"), "--json", str(out)]) == 0  # 49 arcs within T
    err = capsys.readouterr().err
    assert "(T = 5; past it, up to 1.62 T, for the arc budget)" in err and "stopped: past T, " in err
    params = json.loads(out.read_text())["params"]
    assert params["arcs"] == 40 and params["stretch"] == pytest.approx(1.618, abs=1e-3)
    assert main([str(DATA / "clipart-cat.png"), "--json", str(out), "--stretch", "1"]) == 0  # the paper's rule
    assert "past" not in capsys.readouterr().err and json.loads(out.read_text())["similarity"] <= 5.0


def test_clipart_options_on_a_drawing_are_ignored_with_one_warning(tmp_path, capsys):
    out = ["--json", str(tmp_path / "leaf.json")]
    assert main([str(DATA / "drawing-leaf.png"), "--detail", "3", "--arcs", "20", *out]) == 0
    warned = [line for line in capsys.readouterr().err.splitlines() if line.startswith("img2logo: warning: ")]
    assert len(warned) == 1  # --arcs acts on every kind
    assert warned[0].startswith("img2logo: warning: --detail 3 is ignored: the image is drawing (")
    assert warned[0].endswith("and only a clip art has colour regions to keep (give --kind clipart to treat it as one)")
    assert main([str(DATA / "drawing-leaf.png"), "--detail", "24", *out]) == 0
    assert "warning" not in capsys.readouterr().err  # the default detail: nothing was asked


def test_levels_dir_removes_the_level_files_of_an_earlier_run_only(tmp_path, capsys, monkeypatch):
    import json

    from img2logo.app.cli import EXIT_FAILED
    from img2logo.errors import OutputError
    from img2logo.export import writers

    lv = tmp_path / "lv"
    src = str(DATA / "drawing-fish.png")
    assert main([src, "-q", "--levels-dir", str(lv), "-T", "9"]) == 0
    many = sorted(p.name for p in lv.iterdir())
    assert len(many) >= 6  # three levels or more
    (lv / "level-0099.json").write_text('{"mine": true}\n')  # named like a level, not img2logo's
    (lv / "level-0098.svg").write_text("<svg/>\n")
    (tmp_path / "keep.svg").write_text("x")
    (lv / "level-0097.svg").symlink_to(tmp_path / "keep.svg")
    (lv / "notes.txt").write_text("mine\n")
    foreign = ["level-0097.svg", "level-0098.svg", "level-0099.json", "notes.txt"]

    real = writers.atomic_write

    def full_disk(path, write):
        if str(path).endswith(".png"):
            raise OutputError(f"cannot write {path}: No space left on device")
        return real(path, write)

    with monkeypatch.context() as m:  # a run that fails removes nothing: the set is all or nothing
        m.setattr(writers, "atomic_write", full_disk)
        assert main([src, "-q", "--levels-dir", str(lv), "-T", "3", "--png", str(tmp_path / "o.png")]) == EXIT_FAILED
    assert sorted(p.name for p in lv.iterdir()) == sorted([*many, *foreign])
    capsys.readouterr()
    assert main([src, "--levels-dir", str(lv), "-T", "3"]) == 0
    err = capsys.readouterr().err
    assert f"wrote 1 level to {lv}/ (removed {len(many) - 2} files of an earlier run's other levels)" in err
    assert sorted(p.name for p in lv.iterdir()) == sorted(["level-0000.json", "level-0000.svg", *foreign])
    assert json.loads((lv / "level-0000.json").read_text())["tolerance"] == 3.0
    assert (tmp_path / "keep.svg").read_text() == "x"


def test_batch_into_its_own_folder_of_jpegs_is_refused_also_through_a_link(tmp_path, capsys):
    import cv2

    folder = tmp_path / "in"
    folder.mkdir()
    cv2.imwrite(str(folder / "leaf.jpg"), cv2.imread(str(DATA / "drawing-leaf.png")))
    (tmp_path / "link").symlink_to(folder)
    for out in (folder, tmp_path / "link", folder / "."):
        assert main(["batch", str(folder), str(out)]) == EXIT_ERROR
        err = capsys.readouterr().err
        assert (
            err.startswith(f"img2logo: error: output folder {out} is the folder of the input ") and err.count("\n") == 1
        )
    assert sorted(p.name for p in folder.iterdir()) == ["leaf.jpg"]


def test_batch_checks_the_foreground_mask_before_the_workers_start(tmp_path, capsys):
    folder, out = _batch_folder(tmp_path, bad=False), tmp_path / "out"
    assert main(["batch", str(folder), str(out), "--foreground", str(tmp_path / "missing.png")]) == EXIT_ERROR
    err = capsys.readouterr().err
    assert err == f"img2logo: error: --foreground: image file not found: {tmp_path / 'missing.png'}\n"
    (tmp_path / "text.png").write_text("no image")
    assert main(["batch", str(folder), str(out), "--foreground", str(tmp_path / "text.png")]) == EXIT_ERROR
    err = capsys.readouterr().err
    assert err.startswith("img2logo: error: --foreground: ") and "not a readable image" in err and err.count("\n") == 1
    assert not out.exists()


def test_batch_refuses_an_output_that_is_its_foreground_mask(tmp_path, capsys):
    import shutil

    folder, out = _batch_folder(tmp_path, names=("drawing-leaf.png",), bad=False), tmp_path / "out"
    out.mkdir()
    mask = shutil.copy(DATA / "drawing-leaf.png", out / "drawing-leaf.png")  # the name of an output
    assert main(["batch", str(folder), str(out), "--foreground", str(mask)]) == EXIT_ERROR
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "drawing-leaf.png is the input" in err
    assert sorted(p.name for p in out.iterdir()) == ["drawing-leaf.png"]
    assert mask.read_bytes() == (DATA / "drawing-leaf.png").read_bytes()


def test_batch_counts_and_names_the_entries_it_skips(tmp_path, capsys):
    folder, out = _batch_folder(tmp_path, names=("drawing-leaf.png",), bad=False), tmp_path / "out"
    os.mkfifo(folder / "pipe.png")  # never opened: it would block
    (folder / "dead.jpg").symlink_to(tmp_path / "nowhere.jpg")
    (folder / "dir.png").mkdir()
    assert main(["batch", str(folder), str(out)]) == 0
    err = capsys.readouterr().err.splitlines()
    assert err[0] == (
        f"img2logo: warning: {folder}: skipped 3 entries named like images that are no regular files: "
        "'dead.jpg' (a dangling link), 'dir.png' (a folder), 'pipe.png' (a FIFO)"
    )
    assert err[1] == f"{folder}: 1 images"


def _wait_for_workers(proc, count: int) -> list[int]:
    import time

    workers: list[int] = []
    deadline = time.monotonic() + 120
    while len(workers) < count and time.monotonic() < deadline:
        workers = _children(proc.pid)
        time.sleep(0.05)
    assert len(workers) == count
    return workers


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_a_killed_batch_worker_loses_no_output(tmp_path):
    """kill -9 of one worker (the out-of-memory killer): the unfinished images run again, nothing is lost."""
    import shutil
    import signal

    folder, out = tmp_path / "in", tmp_path / "out"
    folder.mkdir()
    for name in ("drawing-fish.png", "drawing-bird.png", "drawing-leaf.png", "drawing-snail.png"):
        shutil.copy(DATA / name, folder / name)
    assert main(["batch", str(folder), str(out), "-q", "--jobs", "1"]) == 0  # the earlier run's outputs
    earlier = {p.name: p.read_bytes() for p in out.iterdir() if not p.name.startswith(".")}
    proc = _run_until(["batch", str(folder), str(out), "--jobs", "2"], f"{folder}: 4 images", tmp_path)
    workers: list[int] = []
    try:
        workers = _wait_for_workers(proc, 2)
        os.kill(workers[0], signal.SIGKILL)
        rest = proc.stderr.read()
        assert proc.wait(timeout=600) == 0, rest
    finally:
        proc.kill()
        proc.wait()
        for w in _children(proc.pid) + workers:
            if _alive(w):
                os.kill(w, signal.SIGKILL)
    assert (
        "img2logo: warning: a worker process died (killed by a signal" in rest and "run again in a fresh pool" in rest
    )
    assert "4 of 4 images done" in rest and "Traceback" not in rest
    now = {p.name: p.read_bytes() for p in out.iterdir() if not p.name.startswith(".")}
    assert set(now) == set(earlier)  # every output is there
    assert all(now[n] == earlier[n] for n in now if n not in ("summary.csv", "index.html"))  # seconds aside: the same


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_a_second_batch_on_the_same_output_folder_is_refused(tmp_path, capsys):
    import shutil
    import signal
    import time

    folder, out = tmp_path / "in", tmp_path / "out"
    folder.mkdir()
    for i in range(2):
        shutil.copy(DATA / "photo-cat.png", folder / f"cat{i}.png")
    proc = _run_until(["batch", str(folder), str(out), "--jobs", "1"], f"{folder}: 2 images", tmp_path)
    try:
        deadline = time.monotonic() + 60
        lock = out / ".img2logo-batch.lock"
        while time.monotonic() < deadline and not (lock.exists() and lock.read_text().strip() == str(proc.pid)):
            time.sleep(0.02)
        assert main(["batch", str(folder), str(out)]) == EXIT_ERROR
        err = capsys.readouterr().err
        assert err == (
            f"img2logo: error: output folder {out} is being written by another img2logo batch (process {proc.pid}); "
            "wait for it to end or give another folder\n"
        )
        proc.send_signal(signal.SIGKILL)  # a killed batch leaves its lock file: stale, taken over
        proc.wait(timeout=60)
    finally:
        proc.kill()
        proc.wait()
    assert (out / ".img2logo-batch.lock").exists()
    (tmp_path / "small").mkdir()
    small = _batch_folder(tmp_path / "small", names=("drawing-leaf.png",), bad=False)
    assert main(["batch", str(small), str(out), "-q"]) == 0
    assert not (out / ".img2logo-batch.lock").exists() and (out / "drawing-leaf.svg").is_file()


def test_version_and_help_load_no_numeric_library():
    # Start-up: `img2logo --version` and `--help` only parse flags; numpy, scipy, OpenCV, numba
    # and pillow are loaded by the run that needs them.
    code = (
        "import sys, contextlib, io\n"
        "from img2logo.app.cli import main\n"
        "for argv in (['--version'], ['--help'], ['batch', '--help']):\n"
        "    with contextlib.redirect_stdout(io.StringIO()), contextlib.suppress(SystemExit):\n"
        "        main(argv)\n"
    )
    assert modules_loaded(code, "numpy", "scipy", "cv2", "numba", "PIL") == []


def test_same_files_whatever_the_thread_counts(tmp_path):
    # Byte-identical outputs on a busy or an idle machine, with one core or many: the BLAS libraries
    # (numpy's and scipy's OpenBLAS) and OpenCV run on 1 thread in one run and on 4 in the other.
    outputs = []
    for threads in ("1", "4"):
        env = dict(os.environ)
        for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "OPENCV_FOR_THREADS_NUM"):
            env[var] = threads
        out = tmp_path / threads
        out.mkdir()
        cmd = [sys.executable, "-m", "img2logo.app.cli", str(DATA / "clipart-fish.png"), "-q", "--fill", "auto"]
        cmd += ["--json", str(out / "fish.json"), "--png", str(out / "fish.png")]
        subprocess.run(cmd, env=env, check=True)
        outputs.append([(out / name).read_bytes() for name in ("fish.json", "fish.png")])
    assert outputs[0] == outputs[1]


def test_the_command_freezes_its_heap_and_main_with_argv_does_not(tmp_path, monkeypatch):
    """The process that is the command moves its long-lived objects out of the collector's sight (gc.freeze).

    main([...]) called from Python (tests, notebooks) leaves the collector alone.
    """
    import gc

    gc.unfreeze()
    try:
        out = tmp_path / "leaf.svg"
        assert main([str(DATA / "drawing-leaf.png"), "-q", "--svg", str(out)]) == 0
        assert gc.get_freeze_count() == 0
        monkeypatch.setattr(sys, "argv", ["img2logo", str(DATA / "drawing-leaf.png"), "-q", "--svg", str(out)])
        assert main() == 0
        assert gc.get_freeze_count() > 0 and out.read_text().startswith("<?xml")
    finally:
        gc.unfreeze()


@pytest.mark.skipif(sys.platform == "win32" or sys.getfilesystemencoding() != "utf-8", reason="POSIX byte names")
def test_a_file_name_that_is_not_utf8_works_in_the_command_and_the_batch(tmp_path, capsys):
    # caf\xe9.png (Latin-1 bytes) gave a UnicodeEncodeError with --json, and a batch crashed writing summary.csv.
    from img2logo.export.writers import read_json

    name = os.fsdecode(b"caf\xe9.png")  # a surrogate escape (PEP 383)
    folder = tmp_path / "in"
    folder.mkdir()
    (folder / name).write_bytes((DATA / "drawing-leaf.png").read_bytes())
    out = tmp_path / "o.json"
    assert main([str(folder / name), "-q", "--json", str(out), "--svg", str(tmp_path / "o.svg")]) == 0
    assert read_json(out).params["source"] == str(folder / name)  # the same name back
    out.read_bytes().decode("utf-8")  # the JSON stays UTF-8 (the name as JSON's \udce9 escape)
    batch = tmp_path / "out"
    assert main(["batch", str(folder), str(batch), "-q"]) == 0
    assert os.fsencode(batch / "caf\udce9.svg") in [os.fsencode(p) for p in batch.iterdir()]
    assert b"caf\xe9.png,drawing," in (batch / "summary.csv").read_bytes()  # the name's own bytes
    gallery = (batch / "index.html").read_bytes().decode("utf-8")
    assert 'src="caf%E9.svg"' in gallery and "caf\ufffd.png" in gallery
    assert capsys.readouterr().err == ""


def test_min_length_that_removes_every_line_names_the_option(tmp_path, capsys):
    assert main([str(DATA / "drawing-leaf.png"), "--min-length", "1e7", "--json", str(tmp_path / "o.json")]) == 2
    err = capsys.readouterr().err
    assert "img2logo: error: " in err and "min_length (--min-length) = 1e+07 px removes every feature line" in err
