"""What the browser tests share: a free port, a server's start, the studio's server, Debian's chromium and its flags."""

from __future__ import annotations

import os
import shutil
import socket
import subprocess
import time
import urllib.error
import urllib.request
from dataclasses import dataclass
from pathlib import Path

import pytest


def free_port() -> int:
    """A TCP port on 127.0.0.1 that nothing listens on now (for a server the test starts)."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_until_up(url: str, process: subprocess.Popen, timeout: float, *, any_answer: bool = False) -> bool:
    """Poll ``url`` until the server answers: True; False once ``process`` ended or ``timeout`` s passed.

    An answer is a 200, or with ``any_answer`` any HTTP status (a 404 of a probe that must not start a
    kernel); a refused connection means not yet.
    """
    deadline = time.monotonic() + timeout
    while True:
        try:
            urllib.request.urlopen(url, timeout=1.0).close()
            return True
        except urllib.error.HTTPError:
            if any_answer:
                return True
        except OSError:
            pass
        if process.poll() is not None or time.monotonic() > deadline:
            return False
        time.sleep(0.25)


CHROMIUM = os.environ.get("IMG2LOGO_CHROMIUM") or shutil.which("chromium") or "/usr/bin/chromium"
#: Chromium without a GPU, a sandbox (root in CI) or any network of its own.
CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
]


def skip_unless_installed(*modules: str, chromium: bool = False) -> None:
    """Skip the test unless every module of ``modules`` imports (and, with ``chromium``, Debian's chromium is there)."""
    if chromium and not Path(CHROMIUM).is_file():
        pytest.skip(f"no chromium at {CHROMIUM} (Debian: apt-get install chromium; or set IMG2LOGO_CHROMIUM)")
    for module in modules:
        reason = f"{module} is not installed (make test-browser installs the [browser] extra)"
        pytest.importorskip(module, reason=reason)


@dataclass(frozen=True)
class StudioServer:
    """``make studio``'s Voila, started by :func:`start_studio`: its process, port, token, log and page address."""

    process: subprocess.Popen
    port: int
    token: str
    log: Path
    url: str


def start_studio(folder: Path, root: Path, timeout: float, **command_options: int) -> StudioServer:
    """``make studio``'s server (:func:`img2logo.studio.serve.serve_command`) on a free port with a new token.

    Its Jupyter folders and its log (``voila.log``) go into ``folder``; ``command_options`` go to
    ``serve_command`` (``idle_timeout``, ``cull_interval``). Raises RuntimeError, with the log's end,
    when it does not answer within ``timeout`` s (the probe is a static path: ``/`` would start a kernel).
    """
    from img2logo.studio.serve import new_token, serve_command, serve_environment, stop_server, studio_url

    port, token = free_port(), new_token()
    base = dict(
        os.environ,
        JUPYTER_RUNTIME_DIR=str(folder / ".runtime"),
        JUPYTER_CONFIG_DIR=str(folder / ".config"),
        JUPYTER_DATA_DIR=str(folder / ".data"),
        IMG2LOGO_ROOT=str(root),
    )
    log = folder / "voila.log"
    with log.open("w") as out:
        process = subprocess.Popen(
            serve_command(port, root, **command_options),
            env=serve_environment(token, base),
            stdout=out,
            stderr=subprocess.STDOUT,
            cwd=folder,
        )
    if not wait_until_up(f"http://127.0.0.1:{port}/voila/static/none", process, timeout, any_answer=True):
        stop_server(process)
        raise RuntimeError(f"Voila did not start; its log: {log.read_text()[-2000:]}")
    return StudioServer(process, port, token, log, studio_url(port, token))
