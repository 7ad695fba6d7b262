"""The studio's server locked to its user: the token, this machine's Host names and origins, no kernel left behind.

``make test-browser`` runs it. A server as ``make studio`` starts it (:func:`browser_support.start_studio`:
Voila with a new token) is asked over HTTP with any Host, Origin and cookies
(:mod:`http.client`), and its kernels are counted as the processes it started
(``ipykernel_launcher``), so that "no kernel" means no process and no memory held. The last test
opens and closes the page 10 times in Debian's chromium. It skips, saying why, where chromium,
playwright or Voila is missing.
"""

from __future__ import annotations

import http.client
import re
import time
import urllib.parse
from pathlib import Path

import pytest
from browser_support import CHROMIUM, CHROMIUM_ARGS, skip_unless_installed, start_studio

from img2logo.studio.serve import stop_server

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parents[2]
#: Seconds to wait for Voila to answer, and for a page (the notebook's first Run) on a loaded machine.
START_TIMEOUT = 60.0
PAGE_TIMEOUT = 180.0
#: The culling of the HTTP tests' server: a kernel that no page is connected to ends after IDLE s idle.
IDLE, CULL_INTERVAL = 20, 2
#: Seconds the kernels of closed pages have to end: far below make studio's culling (300 s), so only the
#: pages' own shutdown can end them in time.
SHUTDOWN_WAIT = 60.0
#: A kernel id that no kernel has.
NO_KERNEL = "0d2b7c9e-1111-4222-8333-444455556666"


def _kernels(process) -> list:
    """The kernels the server runs now: its child processes that are IPython kernels."""
    import psutil

    found = []
    for child in psutil.Process(process.pid).children(recursive=True):
        try:
            if "ipykernel_launcher" in " ".join(child.cmdline()):
                found.append(child)
        except psutil.NoSuchProcess:
            pass
    return found


def _alive(process, kernel_id: str) -> bool:
    """Whether the kernel ``kernel_id`` still runs (its connection file kernel-<id>.json names it)."""
    return any(kernel_id in " ".join(k.cmdline()) for k in _kernels(process))


def _wait_for_kernels(process, count: int, timeout: float) -> int:
    """Poll until the server runs ``count`` kernels or ``timeout`` s passed; the number it runs then."""
    deadline = time.monotonic() + timeout
    while (n := len(_kernels(process))) != count and time.monotonic() < deadline:
        time.sleep(0.5)
    return n


def _ask(studio, path: str, *, host: str | None = None, method: str = "GET", headers=None, body=None):
    """One request to the server with exactly this Host (default 127.0.0.1:port): (status, headers, body)."""
    conn = http.client.HTTPConnection("127.0.0.1", studio.port, timeout=PAGE_TIMEOUT)
    try:
        conn.request(method, path, body=body, headers={"Host": host or f"127.0.0.1:{studio.port}", **(headers or {})})
        response = conn.getresponse()
        if response.status == 101:  # a websocket accepted: nothing more to read
            return response.status, response.headers, ""
        return response.status, response.headers, response.read().decode("utf-8", "replace")
    finally:
        conn.close()


def _websocket(studio, kernel_id: str, *, origin: str, host: str | None = None, cookie: str = "") -> int:
    """The status of a kernel websocket's opening handshake (101: accepted)."""
    headers = {
        "Upgrade": "websocket",
        "Connection": "Upgrade",
        "Sec-WebSocket-Key": "dGhlIHNhbXBsZSBub25jZQ==",
        "Sec-WebSocket-Version": "13",
        "Origin": origin,
    }
    if cookie:
        headers["Cookie"] = cookie
    return _ask(studio, f"/api/kernels/{kernel_id}/channels", host=host, headers=headers)[0]


def _cookies(headers) -> dict[str, str]:
    return dict(c.split(";")[0].split("=", 1) for c in headers.get_all("Set-Cookie") or [])


@pytest.fixture(scope="module")
def studio(tmp_path_factory):
    """``make studio``'s server with its token, culling kernels no page is connected to after IDLE s."""
    skip_unless_installed("voila", "psutil")
    try:
        server = start_studio(
            tmp_path_factory.mktemp("studio-http"), ROOT, START_TIMEOUT, idle_timeout=IDLE, cull_interval=CULL_INTERVAL
        )
    except RuntimeError as e:
        pytest.fail(str(e))
    try:
        yield server
    finally:
        stop_server(server.process)


@pytest.fixture(scope="module")
def page(studio):
    """The page fetched with the token (as the printed URL opens it): its kernel id and its cookies."""
    status, headers, html = _ask(studio, f"/?token={studio.token}")
    assert status == 200, html[-500:]
    kernel_id = re.search(r'"kernelId": "([0-9a-f-]{36})"', html).group(1)
    return kernel_id, _cookies(headers)


# --------------------------------------------------------------------------- the token
def test_without_the_token_every_request_gets_403_and_no_kernel_starts(studio):
    for path in ("/", "/?token=not-the-token", "/login", f"/api/kernels/{NO_KERNEL}", "/voila/render/x"):
        assert (status := _ask(studio, path)[0]) == 403, f"{path}: {status}"
    assert "this studio needs its token" in _ask(studio, "/")[2]
    assert _ask(studio, f"/voila/api/shutdown/{NO_KERNEL}", method="POST", body="")[0] == 403
    assert _websocket(studio, NO_KERNEL, origin=f"http://127.0.0.1:{studio.port}") == 403
    assert _ask(studio, "/voila/files/figure.png")[0] == 403  # no file of the notebook folder, looked up or not
    assert _kernels(studio.process) == []


# --------------------------------------------------------------------------- Host and Origin
def test_only_this_machines_host_names_are_answered(studio):
    path = f"/api/kernels/{NO_KERNEL}?token={studio.token}"  # 404 once answered: no such kernel
    for host in (f"127.0.0.1:{studio.port}", f"localhost:{studio.port}", f"[::1]:{studio.port}"):
        assert _ask(studio, path, host=host)[0] == 404, host
    for host in (
        f"evil.example:{studio.port}",
        "evil.example",
        f"127.0.0.1.evil.example:{studio.port}",
        f"localhost.evil.example:{studio.port}",
    ):  # a page whose name was rebound to 127.0.0.1
        assert _ask(studio, path, host=host)[0] == 403, host
        assert _ask(studio, f"/?token={studio.token}", host=host)[0] == 403, host
    assert _kernels(studio.process) == []


def test_the_kernel_websocket_takes_only_the_pages_own_origin(studio, page):
    kernel_id, cookies = page
    cookie = "; ".join(f"{k}={v}" for k, v in cookies.items())
    local = f"http://127.0.0.1:{studio.port}"
    assert _websocket(studio, kernel_id, origin=local, cookie=cookie) == 101
    assert _websocket(studio, kernel_id, origin="http://evil.example", cookie=cookie) == 403
    assert _websocket(studio, kernel_id, origin=f"http://localhost:{studio.port}", cookie=cookie) == 403
    rebound = f"evil.example:{studio.port}"  # DNS rebinding: the page's own name, Origin and Host agree
    assert _websocket(studio, kernel_id, origin=f"http://{rebound}", host=rebound, cookie=cookie) == 403
    url_token = f"{kernel_id}/channels?token={studio.token}"
    assert _ask(studio, f"/api/kernels/{url_token}", host=rebound, headers={"Origin": f"http://{rebound}"})[0] == 403


# --------------------------------------------------------------------------- kernels end
def test_the_pages_shutdown_post_with_its_xsrf_cookie_ends_its_kernel(studio):
    status, headers, html = _ask(studio, f"/?token={studio.token}")
    assert status == 200
    kernel_id = re.search(r'"kernelId": "([0-9a-f-]{36})"', html).group(1)
    cookies = _cookies(headers)
    assert "_xsrf" in cookies  # what the page's script reads and posts back
    cookie = "; ".join(f"{k}={v}" for k, v in cookies.items())
    local = {
        "Cookie": cookie,
        "Origin": f"http://127.0.0.1:{studio.port}",
        "Content-Type": "application/x-www-form-urlencoded",
    }
    shutdown = f"/voila/api/shutdown/{kernel_id}"
    assert _ask(studio, shutdown, method="POST", headers=local, body="_xsrf=forged")[0] == 403
    assert _ask(studio, shutdown, method="POST", headers=local, body="")[0] == 403
    assert _alive(studio.process, kernel_id)
    body = urllib.parse.urlencode({"_xsrf": urllib.parse.unquote(cookies["_xsrf"])})
    assert _ask(studio, shutdown, method="POST", headers=local, body=body)[0] == 204  # after the kernel stopped
    deadline = time.monotonic() + 5.0  # far below IDLE: the shutdown ended it, not the culling
    while _alive(studio.process, kernel_id) and time.monotonic() < deadline:
        time.sleep(0.2)
    assert not _alive(studio.process, kernel_id)


def test_a_plain_get_leaves_no_kernel_behind(studio):
    before = len(_kernels(studio.process))
    for _ in range(2):
        assert _ask(studio, f"/?token={studio.token}")[0] == 200  # each starts a kernel; no page connects
    assert len(_kernels(studio.process)) >= before + 1
    # idle for IDLE s with no page connected, found within CULL_INTERVAL s; the rest is slack for a slow machine
    assert _wait_for_kernels(studio.process, 0, IDLE + CULL_INTERVAL + 60.0) == 0


# --------------------------------------------------------------------------- a designer's tabs
def test_ten_pages_opened_and_closed_leave_no_kernel(tmp_path, record_property):
    skip_unless_installed("playwright", "voila", "ipycanvas", "psutil", chromium=True)
    from playwright.sync_api import sync_playwright

    studio = start_studio(tmp_path, ROOT, START_TIMEOUT)  # make studio's own culling: 300 s, longer than the wait
    try:
        before = len(_kernels(studio.process))
        opened = []
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
            try:
                context = browser.new_context(viewport={"width": 1366, "height": 768})
                for _ in range(10):
                    page = context.new_page()
                    page.set_default_timeout(PAGE_TIMEOUT * 1000)
                    page.goto(studio.url)
                    page.wait_for_selector(".img2logo-studio")  # the widgets are up: so is the page's unload hook
                    opened.append(len(_kernels(studio.process)))
                    page.close(run_before_unload=True)  # as closing the tab does
                after = _wait_for_kernels(studio.process, 0, SHUTDOWN_WAIT)
            finally:
                browser.close()
        record_property("kernels", f"before {before}, while each page was open {opened}, after {after}")
        print(f"kernels: before {before}, while each page was open {opened}, {SHUTDOWN_WAIT:.0f} s after: {after}")
        assert before == 0 and min(opened) >= 1
        assert after == 0, f"{after} kernels left; Voila's log: {studio.log}"
    finally:
        stop_server(studio.process)
