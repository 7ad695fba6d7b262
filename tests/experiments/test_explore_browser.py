"""The level explorer (notebook 11) in a real front end: JupyterLab driven by chromium.

``make test-browser`` runs it: JupyterLab on 127.0.0.1 with a token, Debian's
chromium (``apt-get install chromium``) driven by playwright through its
``executable_path`` (playwright's own browser downloads are not used), notebook
11 run with ``interactive = True``, the level slider moved and the drawing
checked to have changed. It skips, saying why, where chromium, playwright or
JupyterLab is missing.
"""

from __future__ import annotations

import os
import secrets
import shutil
import subprocess
import sys
import time
import urllib.error
import urllib.request
from dataclasses import dataclass
from pathlib import Path

import pytest
from browser_support import CHROMIUM, CHROMIUM_ARGS, free_port, skip_unless_installed, wait_until_up

pytestmark = pytest.mark.browser


ROOT = Path(__file__).resolve().parents[2]
#: Seconds to wait for JupyterLab to answer, and for a notebook step in the page.
START_TIMEOUT = 60.0
STEP_TIMEOUT_MS = 60_000

try:
    from playwright.sync_api import TimeoutError as PlaywrightTimeoutError
except ImportError:  # the test skips (see skip_unless_installed)
    PlaywrightTimeoutError = TimeoutError


@dataclass(frozen=True)
class Lab:
    url: str
    api: str
    folder: Path
    log: Path


@pytest.fixture(scope="module")
def lab(tmp_path_factory):
    """A JupyterLab server on 127.0.0.1 with a token, serving notebook 11 with interactive = True."""
    skip_unless_installed("playwright", "jupyterlab", chromium=True)
    import papermill

    from img2logo.experiments.runner import SMOKE

    folder = tmp_path_factory.mktemp("lab")
    papermill.execute_notebook(
        str(ROOT / "notebooks" / "11_explore_levels.ipynb"),
        str(folder / "explore.ipynb"),
        parameters={**SMOKE["11_explore_levels"], "interactive": True},
        prepare_only=True,
    )
    # No news pop-up (and no request for it).
    settings = folder / ".settings" / "@jupyterlab" / "apputils-extension"
    settings.mkdir(parents=True)
    (settings / "notification.jupyterlab-settings").write_text('{"fetchNews": "false"}')
    port = free_port()
    token = secrets.token_hex(16)
    env = dict(
        os.environ,
        JUPYTER_RUNTIME_DIR=str(folder / ".runtime"),
        JUPYTER_CONFIG_DIR=str(folder / ".config"),
        IMG2LOGO_ROOT=str(ROOT),
    )
    command = [
        sys.executable,
        "-m",
        "jupyterlab",
        "--no-browser",
        "--allow-root",
        "--ip=127.0.0.1",
        f"--port={port}",
        f"--IdentityProvider.token={token}",
        f"--ServerApp.root_dir={folder}",
        "--LabApp.news_url=",
        "--LabApp.extension_manager=readonly",
        "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate",
        f"--LabApp.workspaces_dir={folder / '.workspaces'}",
        f"--LabApp.user_settings_dir={folder / '.settings'}",
    ]
    log = (folder / "lab.log").open("w")
    server = subprocess.Popen(command, env=env, stdout=log, stderr=subprocess.STDOUT)
    try:
        url = f"http://127.0.0.1:{port}"
        if not wait_until_up(f"{url}/api/status?token={token}", server, START_TIMEOUT):
            pytest.fail(f"JupyterLab did not start; its log: {(folder / 'lab.log').read_text()[-2000:]}")
        yield Lab(f"{url}/lab?token={token}", f"{url}/api/sessions?token={token}", folder, folder / "lab.log")
    finally:
        server.terminate()  # the server shuts its kernels down on SIGTERM
        try:
            server.wait(timeout=20)
        except subprocess.TimeoutExpired:
            server.kill()
            server.wait()
        log.close()


@pytest.fixture(scope="module")
def page(lab):
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        try:
            page = browser.new_page(viewport={"width": 1440, "height": 900})
            page.set_default_timeout(STEP_TIMEOUT_MS)
            # JupyterLab may ask for the kernel when it opens the notebook (a race of its own): take Python 3.
            dialog = page.locator(".jp-Dialog", has_text="Select Kernel")
            page.add_locator_handler(dialog, lambda: _choose_kernel(dialog))
            # Open the notebook from the file browser once the launcher lists the Python kernel: opened
            # before the kernel specs are loaded, JupyterLab cannot match the notebook's kernel and asks.
            page.goto(lab.url)
            page.locator(".jp-LauncherCard", has_text="Python 3").first.wait_for()
            page.locator(".jp-DirListing-item", has_text="explore.ipynb").dblclick()
            page.wait_for_selector(".jp-Notebook")
            page.wait_for_selector(".jp-Notebook-ExecutionIndicator[data-status='idle']")
            try:
                _run_all_cells(page, lab)
                page.wait_for_selector(".widget-image")
                page.wait_for_selector(".jp-Notebook-ExecutionIndicator[data-status='idle']")
            except Exception:
                shot = Path(os.environ.get("IMG2LOGO_BROWSER_FAILURES", lab.folder)) / "failure.png"
                page.screenshot(path=str(shot), full_page=True)
                if shot.parent != lab.folder:
                    shutil.copy(lab.log, shot.parent / "lab.log")
                pytest.fail(f"the explorer did not appear; the page is in {shot}, the server's log in {lab.log}")
            yield page
        finally:
            browser.close()


def _choose_kernel(dialog) -> None:
    """Accept JupyterLab's kernel dialog (its choice is the notebook's Python 3), unless it closed meanwhile.

    JupyterLab asks when a cell is run while the notebook's kernel is still being attached.
    """
    try:
        dialog.locator("button.jp-mod-accept").click(force=True, timeout=10_000)
        dialog.wait_for(state="hidden", timeout=5_000)
    except PlaywrightTimeoutError:
        if dialog.is_visible():
            dialog.press("Enter")


def _kernel_ready(lab: Lab, timeout: float = 60.0) -> None:
    """Wait until the notebook's kernel is idle with the page connected to it (the server's view)."""
    import json

    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        with urllib.request.urlopen(lab.api, timeout=5.0) as answer:
            kernels = [s["kernel"] for s in json.load(answer) if s.get("kernel")]
        if kernels and all(k["execution_state"] == "idle" and k["connections"] >= 1 for k in kernels):
            return
        time.sleep(0.25)
    raise PlaywrightTimeoutError(f"the notebook's kernel was not ready within {timeout:g} s")


def _run_all_cells(page, lab: Lab, attempts: int = 4) -> None:
    """Run > Run All Cells once the kernel is ready; again if no cell started (JupyterLab can drop it)."""
    started = "() => [...document.querySelectorAll('.jp-InputPrompt')].some(p => /\\[(\\*|\\d+)\\]/.test(p.innerText))"
    for _ in range(attempts):
        page.wait_for_selector(".jp-Notebook-ExecutionIndicator[data-status='idle']")
        _kernel_ready(lab)
        page.wait_for_timeout(500)
        page.get_by_role("menuitem", name="Run", exact=True).click()
        page.get_by_text("Run All Cells", exact=True).click()
        try:
            page.wait_for_function(started, timeout=20_000)
            return
        except PlaywrightTimeoutError:
            continue
    raise PlaywrightTimeoutError(f"no cell started after {attempts} x Run All Cells")


def _title(page) -> str:
    return page.locator(".jp-OutputArea-output .widget-html").first.inner_text()


def test_the_explorer_fits_a_laptop_screen_at_a_fixed_size(page):
    from img2logo.experiments.explore import EXPLORER_SIZE

    drawing = page.locator(".widget-image").first
    drawing.scroll_into_view_if_needed()
    box = drawing.bounding_box()
    assert max(box["width"], box["height"]) == EXPLORER_SIZE  # not stretched to the output's width
    natural = drawing.evaluate("img => [img.naturalWidth, img.naturalHeight]")
    assert natural == [2 * round(box["width"]), 2 * round(box["height"])]  # two image pixels per CSS px
    slider = page.locator(".widget-slider", has_text="level t").first.bounding_box()
    assert slider["x"] > box["x"] + box["width"]  # the controls beside the drawing
    assert box["y"] + box["height"] <= 900


def test_moving_the_level_slider_changes_the_drawing(page):
    drawing = page.locator(".widget-image").first
    drawing.scroll_into_view_if_needed()
    before_title, before = _title(page), drawing.screenshot()
    assert "level t = 4 of 4" in before_title
    handle = page.locator(".widget-slider", has_text="level t").locator(".noUi-handle").first
    handle.focus()
    handle.press("ArrowLeft")
    handle.press("ArrowLeft")
    page.wait_for_function(
        "() => document.querySelector('.jp-OutputArea-output .widget-html').innerText.includes('level t = 2 of 4')"
    )
    page.wait_for_timeout(300)  # the new PNG reaches the <img>
    assert drawing.screenshot() != before


def test_a_smaller_tolerance_is_shown_without_a_run(page):
    status = page.locator(".widget-label", has_text="done:").first.inner_text()
    handle = page.locator(".widget-slider", has_text="T (px)").locator(".noUi-handle").first
    handle.focus()
    for _ in range(4):  # 5 -> 3 px, steps of 0.5
        handle.press("ArrowLeft")
    page.wait_for_function(
        "() => document.querySelector('.jp-OutputArea-output .widget-html').innerText.includes('(T = 3)')"
    )
    assert page.locator(".widget-label", has_text="done:").first.inner_text() == status  # no new run
