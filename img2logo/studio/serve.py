"""The studio without a page, and its server: notebook 14's scripted session and ``make studio``.

:func:`scripted_session` does the page's steps with a :class:`~.studio.Studio` (what papermill
runs of notebook 14: no front end, a checkable record and the downloads); :func:`serve_command`
is the Voila command of ``make studio`` (and of the browser tests), :func:`main` its entry
point: ``python -m img2logo.studio.serve [--port N]``.
"""

from __future__ import annotations

import os
import subprocess
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..constants import TOLERANCE
from ..errors import InvalidParameterError
from ..geometry.abstraction import Abstraction
from .session import PICK_DISTANCE, Studio


# --------------------------------------------------------------------------- the notebook's scripted session
@dataclass(frozen=True)
class Session:
    """What :func:`scripted_session` did: the logo after each step and the files it wrote.

    Attributes
    ----------
    name : str
        The image's file name.
    steps : tuple of (str, Abstraction, ndarray)
        Each step's caption, the logo then shown and the lock mask then painted ((H, W) bool).
    image : ndarray, shape (H, W, 3)
        The input (faded under the drawings).
    files : tuple of Path
        The downloads written (SVG, JSON, PNG).
    messages : tuple of str
        The studio's line after each action.
    """

    name: str
    steps: tuple[tuple[str, Abstraction, np.ndarray], ...]
    image: np.ndarray
    files: tuple[Path, ...]
    messages: tuple[str, ...]


def scripted_session(
    image: str, folder: str | os.PathLike[str], *, tolerance: float = TOLERANCE, kind: str = "auto"
) -> Session:
    """The studio used without a page: Run; lock a disc around the longest arc's middle and Run again;
    select the longest arc, delete it, undo, delete it again; save the downloads into ``folder``.

    What papermill runs of notebook 14 (a checkable record of the page's steps).

    Raises
    ------
    Img2LogoError
        When a step fails (its line in the studio).
    """
    from .._io import atomic_write

    s = Studio(image, tolerance=tolerance, kind=kind)
    messages, steps = [s.message], []

    def step(ok: bool) -> None:
        messages.append(s.message)
        if not ok:
            raise InvalidParameterError(s.message)

    step(s.run())
    steps.append((f"Run: |A| = {len(s.shown.arcs)}", s.shown, s.mask.copy()))
    longest = max(range(len(s.shown.arcs)), key=lambda i: s.shown.arcs[i].length)
    arc = s.shown.arcs[longest]
    middle = arc.sample(step=1.0)[len(arc.sample(step=1.0)) // 2]
    s.paint([middle], max(s.image.width, s.image.height) / 8.0)
    messages.append(s.message)
    step(s.run())
    steps.append((f"lock mask painted, Run: |A| = {len(s.shown.arcs)}", s.shown, s.mask.copy()))
    longest = max(range(len(s.shown.arcs)), key=lambda i: s.shown.arcs[i].length)
    point = s.shown.arcs[longest].sample(step=1.0)[1]
    s.select_at(point[0], point[1], PICK_DISTANCE)
    messages.append(s.message)
    step(s.delete_selected())
    step(s.undo())
    s.select_at(point[0], point[1], PICK_DISTANCE)
    step(s.delete_selected())
    steps.append((f"arc {longest} deleted: |A| = {len(s.shown.arcs)}", s.shown, s.mask.copy()))
    files = []
    out = Path(folder)
    for fmt, data in s.downloads().items():
        files.append(atomic_write(out / s.download_names()[fmt], lambda f, data=data: f.write(data)))
    return Session(s.name, tuple(steps), s.result.image.rgb, tuple(files), tuple(messages))


def plot_session(session: Session, *, panel_size: float = 3.2) -> Any:
    """The steps of a :class:`Session` side by side: each logo over the faded input, the lock mask in red."""
    from ..experiments.layout import panel_grid
    from ..export.plotting import plot_abstraction

    fig, axes = panel_grid(1, len(session.steps), panel_size, extra_height=0.5)
    for ax, (caption, a, mask) in zip(axes[0], session.steps, strict=True):
        plot_abstraction(a, ax, image=session.image)
        if mask.any():
            overlay = np.zeros((*mask.shape, 4))
            overlay[mask] = (0.9, 0.24, 0.16, 0.35)
            ax.imshow(overlay, extent=(0, a.width, a.height, 0), interpolation="nearest", zorder=3)
        ax.set_title(caption, fontsize=9)
    fig.suptitle(f"{session.name}: the studio's steps, scripted", fontsize=10)
    return fig


# --------------------------------------------------------------------------- make studio
#: The studio's notebook, served by Voila.
STUDIO_NOTEBOOK = "notebooks/14_studio.ipynb"
#: ``make studio``'s port.
STUDIO_PORT = 8866
#: The environment variable that hands the server its token (jupyter_server reads it; the command line
#: would show it to every user of the machine in ``ps``).
TOKEN_VARIABLE = "JUPYTER_TOKEN"
#: The server's security settings (a Voila configuration file): the token (:data:`TOKEN_VARIABLE`) through
#: :class:`~.identity.StudioIdentityProvider`; only the Host names 127.0.0.1, [::1] and localhost
#: (jupyter_server's ``allow_remote_access=False``, ``local_hostnames``: a page whose DNS name was rebound
#: to 127.0.0.1 sends its own name and is refused); kernel websockets only from the same origin (an empty
#: ``allow_origin``); no files of the notebook folder; no other port than the printed one.
VOILA_CONFIG = Path(__file__).with_name("voila.json")
#: Seconds a kernel with no page connected may stay idle before it is ended (a tab closed without its
#: shutdown reaching the server, a plain ``GET /``), and how often the server looks for such kernels.
KERNEL_IDLE_TIMEOUT = 300
KERNEL_CULL_INTERVAL = 60


def new_token() -> str:
    """A fresh secret for one run of the studio (256 random bits, URL-safe)."""
    import secrets

    return secrets.token_urlsafe(32)


def studio_url(port: int, token: str) -> str:
    """The address to open: the page on 127.0.0.1:``port`` with its ``token`` (as Jupyter prints it)."""
    from urllib.parse import quote

    return f"http://127.0.0.1:{int(port)}/?token={quote(token, safe='')}"


def serve_command(
    port: int = STUDIO_PORT,
    root: str | os.PathLike[str] | None = None,
    *,
    idle_timeout: int = KERNEL_IDLE_TIMEOUT,
    cull_interval: int = KERNEL_CULL_INTERVAL,
) -> list[str]:
    """The Voila command serving the studio on 127.0.0.1:``port`` (what ``make studio`` runs; the browser tests too).

    Run it with the token in the environment variable :data:`TOKEN_VARIABLE`
    (:func:`serve_environment`): a request without it gets 403 and starts no kernel. The server takes
    the settings of :data:`VOILA_CONFIG`: only this machine's Host names, kernel websockets only from
    the page's own origin, no files of the notebook folder, no port but ``port``. A closed page ends
    its kernel (its shutdown post carries the XSRF cookie :class:`~.identity.StudioIdentityProvider`
    sets); a kernel that no page is connected to ends after ``idle_timeout`` s idle, looked for every
    ``cull_interval`` s. No browser is opened; an error in a cell shows its one line, not the traceback.
    """
    import sys

    from ..experiments.paths import project_root

    for name, seconds in (("idle_timeout", idle_timeout), ("cull_interval", cull_interval)):
        if isinstance(seconds, bool) or not isinstance(seconds, int) or seconds < 1:
            raise InvalidParameterError(f"{name} must be a whole number of seconds >= 1, got {seconds!r}")
    folder = Path(root) if root is not None else project_root()
    return [
        sys.executable,
        "-m",
        "voila",
        str(folder / STUDIO_NOTEBOOK),
        f"--port={int(port)}",
        "--Voila.ip=127.0.0.1",
        "--no-browser",
        "--theme=light",
        "--show_tracebacks=False",
        "--Voila.config_file_paths",
        str(VOILA_CONFIG.parent),
        f"--MappingKernelManager.cull_idle_timeout={idle_timeout}",
        f"--MappingKernelManager.cull_interval={cull_interval}",
    ]


def serve_environment(token: str, base: dict[str, str] | None = None) -> dict[str, str]:
    """The environment of :func:`serve_command`: ``base`` (default: this process's) with the ``token``."""
    if not token:
        raise InvalidParameterError("the studio's token must not be empty")
    return {**(os.environ if base is None else base), TOKEN_VARIABLE: token}


def stop_server(process: subprocess.Popen, timeout: float = 20.0) -> None:
    """Stop a server and reap it: SIGTERM (Voila and Jupyter shut their kernels down), SIGKILL after ``timeout`` s."""
    process.terminate()
    try:
        process.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()


def main(argv: list[str] | None = None) -> int:
    """``python -m img2logo.studio.serve [--port N]``: print the URL with its new token; serve until Ctrl-C."""
    import argparse
    import sys

    p = argparse.ArgumentParser(prog="make studio", description="Serve the img2logo studio (notebook 14) with Voila.")
    p.add_argument("--port", type=int, default=STUDIO_PORT, help=f"port on 127.0.0.1 (default {STUDIO_PORT})")
    args = p.parse_args(argv)
    try:
        import voila  # noqa: F401
    except ImportError:
        print("img2logo: error: voila is missing: make studio installs the extra [studio]", file=sys.stderr)
        return 2
    token = new_token()
    print(f"img2logo studio: open {studio_url(args.port, token)} (Ctrl-C stops it)", flush=True)
    server = subprocess.Popen(serve_command(args.port), env=serve_environment(token))
    try:
        return server.wait()
    except KeyboardInterrupt:
        stop_server(server)
        print("img2logo studio: stopped", flush=True)
        return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
