"""What the browser tests share: a free port, a server's start, Debian's chromium and its flags."""

from __future__ import annotations

import os
import shutil
import socket
import subprocess
import time
import urllib.error
import urllib.request


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
