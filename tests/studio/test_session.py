"""img2logo.studio.session: the designer's studio (notebook 14), its state and callbacks without a browser."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest
from helpers import DATA

from img2logo import InvalidParameterError
from img2logo.app import cli
from img2logo.export.contract import from_document
from img2logo.studio import serve as studio_serve, session as studio
from img2logo.studio.session import Studio


@pytest.fixture(scope="module")
def ran():
    """A studio on drawing-fish.png after one Run (shared: the tests copy what they change)."""
    s = Studio("drawing-fish.png")
    assert s.run(), s.message
    return s


def fresh(ran: Studio) -> Studio:
    """A studio in the state of ``ran`` (the run is shared: it is immutable)."""
    s = Studio()
    s.image, s.name, s.settings = ran.image, ran.name, ran.settings
    s.mask = np.zeros_like(ran.mask)
    s.result, s.levels, s.level = ran.result, ran.levels, ran.level
    return s


def longest(s: Studio) -> int:
    return max(range(len(s.shown.arcs)), key=lambda i: s.shown.arcs[i].length)


# --------------------------------------------------------------------------- input and messages
def test_an_example_is_loaded_and_named_for_the_downloads():
    s = Studio("drawing-fish.png")
    assert s.ok and s.message == "drawing-fish.png: 512x512 px; press Run"
    assert s.stem == "drawing-fish" and s.shown is None
    assert s.download_names(("svg", "png")) == {"svg": "drawing-fish.svg", "png": "drawing-fish.png"}
    assert s.mask.shape == (512, 512) and not s.mask.any()


def test_the_downloads_are_named_by_level_and_edit(ran):
    s = fresh(ran)
    t = s.level
    assert s.download_names() == {
        "svg": f"drawing-fish-level{t}.svg",
        "json": f"drawing-fish-level{t}.json",
        "pdf": f"drawing-fish-level{t}.pdf",
        "png": f"drawing-fish-level{t}.png",
        "png-transparent": f"drawing-fish-level{t}-transparent.png",
        "png-input": f"drawing-fish-level{t}-over-input.png",
    }
    s.selected = [longest(s)]
    assert s.delete_selected(), s.message
    assert s.download_names(("svg",)) == {"svg": f"drawing-fish-level{t}-edited.svg"}
    s.set_level(t - 1)
    assert s.download_names(("svg",)) == {"svg": f"drawing-fish-level{t - 1}.svg"}
    with pytest.raises(InvalidParameterError, match="format must be one of svg, json, pdf"):
        s.download_names(("gif",))


@pytest.mark.parametrize(
    ("given", "shown"),
    [
        ("..", "upload"),
        (".", "upload"),
        ("", "upload"),
        ("lo\x00go.png", "logo.png"),
        ("x" * 300 + ".png", "x" * (studio.MAX_NAME_CHARS - 4) + ".png"),
        ("\u00e9" * 200, "\u00e9" * studio.MAX_NAME_CHARS),
        ("../../etc/passwd", "passwd"),
        ("C:\\Users\\me\\cat.png", "cat.png"),
    ],
)
def test_any_name_of_an_upload_is_read_and_shown_cleaned(given, shown):
    s = Studio()
    assert s.load_upload(given, (DATA / "clipart-cat.png").read_bytes()), s.message
    assert s.name == shown and s.message == f"{shown}: 512x512 px; press Run"


def test_an_unreadable_upload_with_a_hostile_name_is_one_line():
    s = Studio()
    assert not s.load_upload("..", b"not an image")
    assert s.message == "error: upload: not a readable image (expected PNG, JPEG, TIFF, BMP, WebP, ...)"


def test_an_input_over_the_working_size_is_shown_and_edited_in_its_own_pixels(tmp_path):
    import cv2

    big = tmp_path / "big-fish.png"
    rgb = cv2.imread(str(DATA / "clipart-fish.png"))
    cv2.imwrite(str(big), cv2.resize(rgb, (2600, 2600), interpolation=cv2.INTER_NEAREST))
    s = Studio(str(big))
    assert s.message.startswith("big-fish.png: 2600x2600 px") and s.mask.shape == (2600, 2600)
    s.paint([(1300.0, 1300.0)], 40.0)
    assert s.run(), s.message
    a = s.shown
    assert (a.width, a.height) == (2600, 2600) and s.work_scale < 1.0
    # T and the error in one unit: the working copy's pixels, as abstract() takes T.
    assert f"error {a.similarity * s.work_scale:.2f} px (tolerance 5 px of the " in s.title
    assert a.similarity * s.work_scale <= 5.0 and s.run_tolerance == pytest.approx(5.0)
    assert s.set_tolerance(4.0) and s.settings.tolerance == 4.0 and s.result is not None
    assert max(lv.similarity for lv in s.levels[1:]) * s.work_scale <= 4.0
    i = longest(s)
    middle = s.shown.arcs[i].sample(step=4.0)[len(s.shown.arcs[i].sample(step=4.0)) // 2]
    assert s.select_at(*middle, 20.0) == i


def test_undo_and_redo(ran):
    s = fresh(ran)
    n = len(s.shown.arcs)
    s.selected = [longest(s)]
    assert s.delete_selected()
    assert s.undo() and len(s.shown.arcs) == n
    assert s.redo() and len(s.shown.arcs) == n - 1 and s.message.startswith("edit redone")
    assert not s.redo() and s.message == "error: nothing to redo on this level"
    assert s.undo()
    s.selected = [0]
    assert s.delete_selected()  # a new edit forgets what was undone
    assert not s.redo()


def test_shift_click_selects_several_and_delete_removes_them_in_one_edit(ran):
    s = fresh(ran)
    a = s.shown
    picks = [a.arcs[i].sample(step=1.0) for i in (0, 1, 2)]
    for p in picks:
        s.select_at(*p[len(p) // 2], 3.0, add=True)
    assert s.selected == [0, 1, 2] and s.message == "3 arcs selected: 0, 1, 2"
    s.select_at(*picks[1][len(picks[1]) // 2], 3.0, add=True)
    assert s.selected == [0, 2]
    assert s.delete_selected(), s.message
    assert len(s.shown.arcs) == len(a.arcs) - 2 and s.n_edits == 1
    assert list(s.shown.params["edits"][-2:]) == ["delete_arc(2)", "delete_arc(0)"]


def test_an_unreadable_upload_is_one_line_and_keeps_the_image(ran):
    s = fresh(ran)
    shown = s.shown
    assert not s.load_upload("logo.png", b"this is not a png")
    assert s.message == "error: logo.png: not a readable image (expected PNG, JPEG, TIFF, BMP, WebP, ...)"
    assert "\n" not in s.message and "/tmp" not in s.message
    assert s.shown is shown and s.name == "drawing-fish.png"


def test_a_blank_upload_says_so(ran, tmp_path):
    from PIL import Image

    Image.new("RGB", (64, 64), "white").save(tmp_path / "white.png")
    s = fresh(ran)
    assert not s.load_upload("white.png", (tmp_path / "white.png").read_bytes())
    assert s.message == "error: white.png: image is blank (one colour, #ffffff, in every pixel); nothing to trace"
    assert s.shown is not None


def test_an_upload_is_read_as_the_file_it_was(ran):
    s = Studio()
    assert s.load_upload("My Fish.png", (DATA / "drawing-fish.png").read_bytes())
    assert s.name == "My Fish.png" and s.stem == "My Fish" and s.image.source == "My Fish.png"
    np.testing.assert_array_equal(s.image.rgb, ran.image.rgb)


def test_run_needs_an_image_and_a_bad_fill_is_said_before_it():
    s = Studio()
    assert not s.run() and s.message.startswith("error: load an image first")
    s.load_example("drawing-fish.png")
    assert not s.run(fill="palette:")
    assert "the palette is empty" in s.message and s.result is None


# --------------------------------------------------------------------------- levels and T
def test_the_final_level_is_shown_and_a_smaller_t_needs_no_run(ran):
    s = fresh(ran)
    n = len(s.levels)
    assert s.level == n - 1 and s.title.startswith(f"drawing-fish: level {n - 1} of {n - 1}")
    result = s.result
    assert s.set_tolerance(2.0)
    assert s.result is result  # read off the run
    from img2logo.experiments.explore import levels_within

    assert s.levels == levels_within(result, 2.0) and len(s.levels) < n and "(tolerance 2 px)" in s.title
    assert s.set_level(0) and s.shown is s.levels[0]
    assert not s.set_level(99) and s.message.startswith("error: level must be in [0,")


# --------------------------------------------------------------------------- lock mask and subject
def test_painting_fills_the_discs_and_the_gap_of_a_stroke():
    s = Studio("drawing-fish.png")
    s.paint([[100.0, 100.0], [140.0, 100.0]], 5.0)
    m = s.mask
    assert m[99, 99] and m[99, 139] and m[99, 120]  # both ends and the stroke between them
    assert m[104, 120] and not m[106, 120] and not m[99, 146]
    count = int(m.sum())
    assert abs(count - (40 * 10 + np.pi * 25)) < 20  # a capsule of 40 x 10 px with round ends
    s.paint([[120.0, 100.0]], 3.0, erase=True)
    assert not m[99, 120] and m[99, 100]
    assert "lock mask:" in s.message and "press Run" in s.message
    s.paint([[-50.0, -50.0]], 3.0)  # outside: nothing, no error
    s.clear_mask()
    assert not s.mask.any()


def test_a_painted_stroke_locks_its_segments_on_the_next_run(ran):
    s = fresh(ran)
    a = s.shown
    arc = a.arcs[longest(s)]
    s.paint(arc.sample(step=2.0), 6.0)
    assert s.run(), s.message
    assert s.result.final.params["locked_segments"] > 0
    assert "segments locked" in s.message
    # The run without the mask merges more (or as much): the lock forbids merges.
    assert len(s.shown.arcs) >= len(a.arcs)


def test_a_mask_over_everything_is_refused_and_the_result_kept(ran):
    s = fresh(ran)
    shown = s.shown
    s.mask[:] = True
    assert not s.run()
    assert s.message.startswith("error: the lock mask covers all ") and "nothing could be merged" in s.message
    assert s.shown is shown and s.result is ran.result


def test_the_subject_rectangle_is_clipped_pixels_and_seeds_a_photo():
    s = Studio("photo-cat.png", kind="photo")
    h, w = s.mask.shape
    assert s.set_subject(w + 10, 5.4, 20.6, 30.2) == (20, 5, w - 20, 26)
    assert s.set_subject(10, 10, 11, 40) is None and s.subject is None  # too thin: cleared
    box = (w // 4, h // 4, w // 2, h // 2)
    s.set_subject(box[0], box[1], box[0] + box[2], box[1] + box[3])
    assert s.subject == box
    assert s.run(), s.message
    assert s.result.lines.subject.method == "rectangle"
    assert f"{box[0]},{box[1]},{box[2]},{box[3]}" in s.result.lines.subject.description
    assert "subject: kept the object in" in s.message
    s.clear_subject()
    assert s.subject is None


def test_a_lock_mask_with_symmetry_is_the_librarys_line(ran):
    s = fresh(ran)
    s.paint([[100.0, 100.0]], 10.0)
    assert not s.run(symmetry="vertical")
    assert s.message == "error: a lock mask cannot be combined with symmetry (use symmetry='none')"


# --------------------------------------------------------------------------- selection, edits, undo
def test_a_click_selects_the_nearest_arc_within_the_distance(ran):
    s = fresh(ran)
    i = longest(s)
    p = s.shown.arcs[i].sample(step=1.0)
    middle = p[len(p) // 2]
    assert s.select_at(middle[0] + 2.0, middle[1], 5.0) == i and s.selected == [i]
    assert s.message.startswith(f"arc {i} selected: circle ")
    assert s.select_at(-100.0, -100.0, 5.0) is None and s.selected == []


def test_delete_and_undo(ran):
    s = fresh(ran)
    before = s.shown
    i = longest(s)
    s.selected = [i]
    assert s.delete_selected(), s.message
    assert len(s.shown.arcs) == len(before.arcs) - 1
    assert s.shown.params["edits"][-1] == f"delete_arc({i})"
    assert s.n_edits == 1 and "1 edit" in s.title
    assert s.undo() and s.shown is before and s.n_edits == 0
    assert not s.undo() and s.message == "error: nothing to undo on this level"


def test_edits_belong_to_their_level(ran):
    s = fresh(ran)
    top = s.level
    s.selected = [0]
    s.delete_selected()
    edited = s.shown
    s.set_level(0)
    assert s.shown is s.levels[0]
    s.set_level(top)
    assert s.shown is edited


def test_move_and_rung_keep_the_ladder(ran):
    from img2logo.constants import PHI

    s = fresh(ran)
    i = longest(s)
    s.selected = [i]
    old = s.shown.arcs[i].circle
    assert s.move_selected(2.0, 0.0), s.message
    assert s.shown.arcs[i].circle.cx == pytest.approx(old.cx + 2.0)
    assert s.rung_selected(+1), s.message
    new = s.shown.arcs[i].circle
    assert new.k == old.k + 1
    assert new.r == pytest.approx(PHI ** (new.k + s.shown.bias))
    assert s.n_edits == 2
    s.undo()
    s.undo()
    assert s.shown is s.levels[s.level]


def test_delete_then_connect_the_two_loose_ends(ran):
    # Fig. 17's workflow: delete an arc of a chain, then join its two neighbours again with a new arc.
    s = fresh(ran)
    a = s.shown
    ends = a.arc_junctions

    def neighbour(i, j):
        others = set(a.junction_arcs[j]) - {i}
        return others.pop() if len(others) == 1 else None

    chain = [
        (i, neighbour(i, ends[i].start), neighbour(i, ends[i].end))
        for i in range(len(a.arcs))
        if ends[i].start is not None and ends[i].end is not None and ends[i].start != ends[i].end
    ]
    i, p, q = next((i, p, q) for i, p, q in chain if p is not None and q is not None and p != q)
    s.selected = [i]
    assert s.delete_selected(), s.message
    shift = [x - (x > i) for x in (p, q)]
    assert all(studio.free_ends(s.shown, x) for x in shift)
    s.selected = shift
    assert s.connect_selected(), s.message
    assert len(s.shown.arcs) == len(a.arcs) and s.selected == [len(a.arcs) - 1]
    assert s.shown.params["edits"][-1].startswith("connect(")
    assert s.n_edits == 2


def test_an_edit_that_cannot_be_done_is_one_line_and_changes_nothing(ran):
    s = fresh(ran)
    shown = s.shown
    assert not s.delete_selected() and s.message == "error: select an arc first (click it)"
    s.selected = [0]
    assert not s.connect_selected() and s.message.startswith("error: connect needs two arcs")
    s.selected = [0]
    ok = s.rung_selected(-40)  # far below the ladder's smallest rung: refused by the edits API
    assert not ok and s.message.startswith("error: ") and "\n" not in s.message
    assert s.shown is shown and s.n_edits == 0


def test_a_fibonacci_logo_refuses_edits_with_the_librarys_line():
    s = Studio("drawing-fish.png")
    assert s.run(ladder="fibonacci"), s.message
    s.selected = [0]
    assert not s.rung_selected(1)
    assert "supports only the golden ratio ladder" in s.message


# --------------------------------------------------------------------------- downloads
def _cli_files(tmp_path, level: int, fill: str) -> dict[str, bytes]:
    """The SVG, JSON, PDF and PNG (on white) the command line writes for ``level``."""
    folder = tmp_path / "cli"
    folder.mkdir()
    shutil.copy(DATA / "drawing-fish.png", folder / "drawing-fish.png")
    import os

    here = os.getcwd()
    os.chdir(folder)  # the document records the input as given: run it as `img2logo drawing-fish.png`
    try:
        args = ["drawing-fish.png", "--level", str(level), "--fill", fill, "-q"]
        outputs = ["--svg", "out.svg", "--json", "out.json", "--pdf", "out.pdf", "--png", "out.png"]
        assert cli.main([*args, *outputs, "--png-background", "white"]) == 0
    finally:
        os.chdir(here)
    return {fmt: (folder / f"out.{fmt}").read_bytes() for fmt in ("svg", "json", "pdf", "png")}


@pytest.mark.parametrize("fill", ["none", "auto"])
def test_downloads_are_the_command_lines_bytes(ran, tmp_path, fill):
    s = fresh(ran)
    assert s.set_fill(fill), s.message
    s.set_level(len(s.levels) - 2)
    assert s.downloads(("svg", "json", "pdf", "png")) == _cli_files(tmp_path, s.level, fill)


def test_downloads_of_an_edited_logo_are_valid_documents(ran):
    s = fresh(ran)
    s.selected = [longest(s)]
    s.delete_selected()
    files = s.downloads()
    doc = json.loads(files["json"])
    a = from_document(doc)
    assert len(a.arcs) == len(s.shown.arcs) and doc["params"]["edits"] == list(s.shown.params["edits"])
    assert files["svg"].startswith(b"<?xml") and files["png"].startswith(b"\x89PNG")
    assert files["pdf"].startswith(b"%PDF")
    from io import BytesIO

    from PIL import Image

    white, clear = (Image.open(BytesIO(files[f])) for f in ("png", "png-transparent"))
    assert white.getpixel((0, 0))[:3] == (255, 255, 255) and clear.mode == "RGBA" and clear.getpixel((0, 0))[3] == 0
    from img2logo.export import writers

    assert files["svg"] == writers.to_svg(s.shown).encode("utf-8")


def test_nothing_to_download_before_a_run():
    with pytest.raises(InvalidParameterError, match="nothing to download: press Run first"):
        Studio("drawing-fish.png").downloads()


# --------------------------------------------------------------------------- notebook, server
def test_the_scripted_session_writes_the_downloads(tmp_path):
    session = studio_serve.scripted_session("drawing-fish.png", tmp_path)
    stem = f"drawing-fish-level{session.steps[2][1].level}-edited"
    assert [p.name for p in session.files] == [
        f"{stem}{end}" for end in (".svg", ".json", ".pdf", ".png", "-transparent.png", "-over-input.png")
    ]
    assert len(session.steps) == 3 and session.steps[1][2].any()
    assert len(session.steps[2][1].arcs) == len(session.steps[1][1].arcs) - 1
    from_document(json.loads((tmp_path / f"{stem}.json").read_text()))
    fig = studio_serve.plot_session(session)
    assert len(fig.axes) >= 3


def test_the_server_command_is_voila_on_localhost_with_the_studios_settings():
    command = studio_serve.serve_command(8899)
    assert command[1:3] == ["-m", "voila"] and command[3].endswith("notebooks/14_studio.ipynb")
    assert "--port=8899" in command and "--Voila.ip=127.0.0.1" in command and "--no-browser" in command
    assert command[command.index("--Voila.config_file_paths") + 1] == str(studio_serve.VOILA_CONFIG.parent)
    assert "--MappingKernelManager.cull_idle_timeout=300" in command
    assert "--MappingKernelManager.cull_interval=60" in command
    config = json.loads(studio_serve.VOILA_CONFIG.read_text())
    assert config["Voila"]["auto_token"] is True
    assert config["Voila"]["identity_provider_class"] == "img2logo.studio.identity.StudioIdentityProvider"
    assert config["Voila"]["port_retries"] == 0
    assert config["Voila"]["tornado_settings"] == {
        "allow_remote_access": False,
        "local_hostnames": ["localhost"],
        "allow_origin": "",
        "websocket_max_message_size": studio.WEBSOCKET_MAX_MESSAGE_BYTES,
    }
    assert config["VoilaConfiguration"]["file_allowlist"] == []
    assert config["MappingKernelManager"]["cull_connected"] is False


@pytest.mark.parametrize("seconds", [0, -5, 2.5, True, "60"])
def test_the_server_command_refuses_a_culling_time_that_is_not_whole_seconds(seconds):
    with pytest.raises(InvalidParameterError, match="idle_timeout must be a whole number of seconds >= 1"):
        studio_serve.serve_command(8899, idle_timeout=seconds)


def test_the_studio_url_and_environment_carry_the_token():
    assert studio_serve.studio_url(8866, "a/b+c") == "http://127.0.0.1:8866/?token=a%2Fb%2Bc"
    assert studio_serve.serve_environment("t0k", {"HOME": "/h"}) == {"HOME": "/h", "JUPYTER_TOKEN": "t0k"}
    with pytest.raises(InvalidParameterError, match="token must not be empty"):
        studio_serve.serve_environment("")
    tokens = {studio_serve.new_token() for _ in range(3)}
    assert len(tokens) == 3 and all(len(t) >= 43 for t in tokens)


def test_the_url_make_studio_prints_carries_the_token_and_main_hides_it_from_ps(monkeypatch, capsys):
    import re
    import subprocess
    import sys
    import types
    import urllib.parse

    started = {}

    class Server:
        def __init__(self, command, env):
            started.update(command=command, env=env)

        def wait(self):
            return 0

    monkeypatch.setitem(sys.modules, "voila", types.ModuleType("voila"))
    monkeypatch.setattr(subprocess, "Popen", Server)
    assert studio_serve.main(["--port", "8871"]) == 0
    line = capsys.readouterr().out
    url = re.search(r"open (\S+) \(Ctrl-C", line).group(1)
    token = urllib.parse.parse_qs(urllib.parse.urlsplit(url).query)["token"][0]
    assert url.startswith("http://127.0.0.1:8871/?token=") and len(token) >= 32
    assert started["env"][studio_serve.TOKEN_VARIABLE] == token
    assert not any(token in part for part in started["command"])  # the command line is visible to all users
    assert studio_serve.main(["--port", "8871"]) == 0  # a new token for every run
    assert started["env"][studio_serve.TOKEN_VARIABLE] != token


def test_papermill_is_no_live_front_end(monkeypatch):
    monkeypatch.delenv("SERVER_SOFTWARE", raising=False)
    monkeypatch.delenv("JPY_SESSION_NAME", raising=False)
    assert not studio.front_end_live()
    monkeypatch.setenv("SERVER_SOFTWARE", "voila/0.5.13")
    assert studio.front_end_live()


# --------------------------------------------------------------------------- the paper's tool: Fig. 15, 16, 17
def test_add_the_other_side_of_the_selected_arcs_circle(ran):
    s = fresh(ran)
    a = s.shown
    i = next(
        j
        for j, arc in enumerate(a.arcs)
        if not arc.is_line and None not in (a.arc_junctions[j].start, a.arc_junctions[j].end)
    )
    s.selected = [i]
    assert s.add_other_side(), s.message
    new = s.shown
    assert len(new.arcs) == len(a.arcs) + 1 and new.arcs[-1].circle == a.arcs[i].circle
    assert abs(abs(new.arcs[-1].sweep) + abs(a.arcs[i].sweep) - 2 * np.pi) < 1e-6
    assert s.selected == [len(a.arcs)] and s.download_stem.endswith("-edited")


def test_a_lock_stroke_shows_the_segments_the_next_run_locks(ran):
    s = fresh(ran)
    assert s.lock_preview() == []
    arc = s.shown.arcs[longest(s)]
    s.paint(arc.sample(step=4.0), 6.0)
    preview = s.lock_preview()
    assert preview and all(p.ndim == 2 and p.shape[1] == 2 for p in preview)
    assert s.run(), s.message
    assert int(s.result.final.params["locked_segments"]) == len(preview)


def test_the_circle_sizes_of_fig_15(ran):
    s = fresh(ran)
    assert not s.set_exponents("5, seven") and s.message.startswith("error: circle sizes must be whole numbers")
    assert s.settings.exponents is None
    chosen = s.rungs_used[-3:]
    assert s.set_exponents(" ".join(map(str, chosen))) and s.settings.exponents == chosen
    assert s.run(), s.message
    assert {c.k for c in s.shown.golden_circles} <= set(chosen)
    assert s.set_exponents("") and s.settings.exponents is None


def test_the_server_takes_an_upload_too_large_for_the_studio_to_say_so():
    """Tornado's 10 MiB websocket cap dropped a 10 MB upload without a word: the server's config raises it."""
    config = json.loads(studio_serve.VOILA_CONFIG.read_text())
    assert config["Voila"]["tornado_settings"]["websocket_max_message_size"] == studio.WEBSOCKET_MAX_MESSAGE_BYTES
    assert studio.WEBSOCKET_MAX_MESSAGE_BYTES > 10 * studio.MAX_UPLOAD_BYTES
    s = Studio()
    assert not s.load_upload("huge.jpg", b"\xff" * (11 * 2**20))
    assert s.message.startswith(f"error: huge.jpg: the file has {11 * 2**20} bytes, more than the studio takes")


def test_a_region_gets_its_own_colour_in_the_drawing_and_the_files(ran):
    s = fresh(ran)
    assert not s.colour_region_at(10.0, 10.0, "#ff0000") and s.message.startswith("error: choose fills first")
    assert s.set_fill("palette:#264653,#2a9d8f"), s.message
    fills = s.fills()
    point = fills[0].rings()[0].mean(axis=0)
    i = s.region_at(*point)
    assert i is not None
    assert s.colour_region_at(*point, "#FF0000"), s.message
    assert s.message == f"region {i}: #ff0000" and s.fills()[i].color == "#ff0000"
    doc = json.loads(s.downloads(("json",))["json"])
    assert doc["fills"][i]["color"] == "#ff0000"
    assert not s.colour_region_at(*point, "red-ish") and s.fills()[i].color == "#ff0000"
    assert not s.colour_region_at(-50.0, -50.0, "#00ff00") and s.message.startswith("error: no region at")
    s.set_level(s.level - 1)
    assert all(f.color != "#ff0000" for f in s.fills() or ())  # another logo: its own regions


def test_the_detail_of_a_clip_art_is_a_setting_of_the_run():
    s = Studio("clipart-cat.png")
    assert s.run(), s.message
    many = len(s.shown.arcs)
    assert s.run(detail=2), s.message
    assert s.settings.detail == 2 and len(s.shown.arcs) < many


def test_an_arc_budget_of_a_clip_art_is_a_setting_of_the_run():
    s = Studio("clipart-cat.png")
    assert s.run(), s.message
    many = len(s.shown.arcs)
    assert s.run(arcs=many // 2), s.message
    assert s.settings.arcs == many // 2 and len(s.shown.arcs) < many
    assert not s.run(arcs=0) and "arcs" in s.message  # a budget is at least 1 arc (the page's 0 is the default)


def test_a_level_made_past_t_for_the_arc_budget_says_so():
    s = Studio("clipart-cat.png")  # 49 arcs within T: the default budget of 40 takes it past T
    assert s.run(), s.message
    a = s.shown
    assert len(a.arcs) <= 40 and a.similarity > a.tolerance
    assert s.title.endswith("(tolerance 5 px, past it for the arc budget)")
    assert s.set_level(0)  # the initial fit is within T
    assert "past it" not in s.title


def test_any_two_free_ends_clicked_are_joined_on_the_circle_chosen(ran):
    # Fig. 17 "add" between two ends the designer picks: the open ends of the drawing's strokes.
    from img2logo.constants import JUNCTION_TOLERANCE

    s = fresh(ran)
    a = s.shown
    ends = s.free_end_junctions()
    assert len(ends) >= 2 and all(len(set(a.junction_arcs[j])) == 1 for j in ends)
    j0, j1 = ends[0], ends[-1]
    assert s.select_end_at(*a.junctions[j0] + 2.0, 4.0) == j0 and s.ends == [j0]
    assert s.end_arc() is None and not s.add_arc_at_ends() and "click two free ends" in s.message
    assert s.select_end_at(*a.junctions[j1], 4.0) == j1 and s.ends == [j0, j1]
    assert f"free ends {j0} and {j1} chosen" in s.message and "option 1 of" in s.message
    seen = []
    for _ in range(3):  # each option is another circle through both ends
        arc = s.end_arc()
        assert arc is not None and np.abs(arc.circle.distance(a.junctions[[j0, j1]])).max() <= JUNCTION_TOLERANCE
        seen.append((arc.circle.cx, arc.circle.cy, arc.circle.r))
        assert s.other_end_circle()
    assert len(set(seen)) == 3
    chosen = s.end_arc()
    assert s.add_arc_at_ends(), s.message
    b = s.shown
    assert len(b.arcs) == len(a.arcs) + 1 and b.arcs[-1] == chosen and s.selected == [len(a.arcs)]
    assert b.arc_junctions[-1].start == j0 and b.arc_junctions[-1].end == j1 and s.ends == []
    assert j0 not in s.free_end_junctions() and j1 not in s.free_end_junctions()
    assert s.undo() and s.shown is a


def test_a_click_away_from_every_free_end_chooses_none(ran):
    s = fresh(ran)
    a = s.shown
    far = a.junctions[s.free_end_junctions()].min(axis=0) - 50.0
    assert s.select_end_at(*far, 4.0) is None and s.ends == []
    j = s.free_end_junctions()[0]
    assert s.select_end_at(*a.junctions[j], 4.0) == j
    assert s.select_end_at(*a.junctions[j], 4.0) == j and s.ends == [] and s.message == "no free end chosen"
    assert not s.other_end_circle() and s.message.startswith("error: click two free ends")
