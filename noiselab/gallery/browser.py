"""Open a page in real headless Chromium and report what went wrong: missing files, console errors, media that will not play.

Talks to Chromium over the DevTools protocol on a pipe (``--remote-debugging-pipe``:
file descriptors 3 and 4, messages as JSON terminated by a NUL byte), so it
needs no websocket library and no network port. Used by the tests and by
``noiselab gallery --check``.
"""
from __future__ import annotations

import json
import os
import select
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--mute-audio", "--autoplay-policy=no-user-gesture-required", "--allow-file-access-from-files"]


def find_chromium():
    """Path of a Chromium executable, or None."""
    for name in ("chromium", "chromium-browser", "google-chrome", "chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


class _Pipe:
    def __init__(self, proc, to_browser, from_browser):
        self.proc, self.w, self.r = proc, to_browser, from_browser
        self.buf = b""
        self.next_id = 0
        self.events = []

    def send(self, method, params=None, session=None):
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        os.write(self.w, json.dumps(msg).encode() + b"\0")
        return self.next_id

    def _read(self, deadline):
        while b"\0" not in self.buf:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError("Chromium did not answer in time")
            ready, _, _ = select.select([self.r], [], [], left)
            if ready:
                chunk = os.read(self.r, 1 << 20)
                if not chunk:
                    raise RuntimeError("Chromium closed the DevTools pipe")
                self.buf += chunk
        raw, self.buf = self.buf.split(b"\0", 1)
        return json.loads(raw)

    def call(self, method, params=None, session=None, timeout=30.0):
        mid = self.send(method, params, session)
        deadline = time.monotonic() + timeout
        while True:
            msg = self._read(deadline)
            if msg.get("id") == mid:
                if "error" in msg:
                    raise RuntimeError(f"{method}: {msg['error']}")
                return msg.get("result", {})
            if "method" in msg:
                self.events.append(msg)

    def pump(self, seconds):
        deadline = time.monotonic() + seconds
        try:
            while True:
                self.events.append(self._read(deadline))
        except TimeoutError:
            pass


_STATUS_JS = """
(() => {
  const imgs = [...document.querySelectorAll('img')];
  const vids = [...document.querySelectorAll('video')];
  return JSON.stringify({
    ready: document.readyState,
    wantsCheck: !!document.getElementById('status'),
    check: document.body ? document.body.getAttribute('data-check') : null,
    images: imgs.map(i => ({src: i.getAttribute('src'), ok: i.complete && i.naturalWidth > 0, w: i.naturalWidth,
                          shown: i.getBoundingClientRect().width})),
    videos: vids.map(v => ({src: (v.querySelector('source') || v).getAttribute('src'), ready: v.readyState,
                            error: v.error ? v.error.code : null, w: v.videoWidth, duration: v.duration,
                            poster: v.getAttribute('poster')})),
    links: [...document.querySelectorAll('a[href]')].map(a => a.getAttribute('href')),
  });
})()
"""


def check_page(path, *, timeout=60.0, chromium=None, width=1280):
    """Load ``path`` (an HTML file) in headless Chromium and return a report dict.

    Keys: ``console_errors`` (console messages of level error, uncaught
    exceptions, failed resource loads), ``images``, ``videos``, ``links`` (what
    the page holds and whether each loaded; an image's ``w`` is its natural width, ``shown`` the width drawn
    in a window ``width`` CSS px wide), ``check`` (the page's own ``data-check`` verdict), ``browser``
    (version string). The page is opened with ``?check``, so it loads every video, which a reader's page
    does only when one is played.
    """
    chromium = chromium or find_chromium()
    if not chromium:
        raise FileNotFoundError("no Chromium found (install the Debian package 'chromium': ./install.sh test)")
    url = Path(path).resolve().as_uri() + "?check"   # the page then loads every video (they preload none)
    profile = tempfile.mkdtemp(prefix="noiselab-chromium-")
    to_r, to_w = os.pipe()      # we write, Chromium reads on fd 3
    from_r, from_w = os.pipe()  # Chromium writes on fd 4, we read

    def child_fds():
        # (dup2 onto the same number keeps close-on-exec, hence set_inheritable)
        os.dup2(to_r, 3)
        os.dup2(from_w, 4)
        os.set_inheritable(3, True)
        os.set_inheritable(4, True)

    proc = subprocess.Popen([chromium, *FLAGS, f"--user-data-dir={profile}", "--remote-debugging-pipe", "about:blank"],
                            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            preexec_fn=child_fds, close_fds=False)
    os.close(to_r)
    os.close(from_w)
    pipe = _Pipe(proc, to_w, from_r)
    try:
        version = pipe.call("Browser.getVersion", timeout=timeout)
        target = pipe.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = pipe.call("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        for domain in ("Runtime.enable", "Log.enable", "Page.enable", "Network.enable"):
            pipe.call(domain, session=session)
        # the window a reader on a laptop has: label sizes are judged at this width
        pipe.call("Emulation.setDeviceMetricsOverride", {"width": width, "height": 900, "deviceScaleFactor": 1,
                                                          "mobile": False}, session=session)
        pipe.call("Page.navigate", {"url": url}, session=session)
        deadline = time.monotonic() + timeout
        status = None
        while time.monotonic() < deadline:
            pipe.pump(0.5)
            res = pipe.call("Runtime.evaluate", {"expression": _STATUS_JS, "returnByValue": True}, session=session)
            status = json.loads(res["result"]["value"])
            settled = all(v["ready"] >= 2 or v["error"] is not None for v in status["videos"])
            if status["ready"] == "complete" and settled and (status["check"] is not None or not status["wantsCheck"]):
                break
        pipe.pump(0.5)
        errors = []
        for ev in pipe.events:
            m, p = ev.get("method"), ev.get("params", {})
            if m == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
                errors.append("console: " + " ".join(str(a.get("value", a.get("description", ""))) for a in p.get("args", [])))
            elif m == "Runtime.exceptionThrown":
                d = p.get("exceptionDetails", {})
                errors.append("exception: " + str(d.get("exception", {}).get("description", d.get("text"))))
            elif m == "Log.entryAdded" and p.get("entry", {}).get("level") == "error":
                e = p["entry"]
                errors.append(f"log ({e.get('source')}): {e.get('text')} {e.get('url', '')}".strip())
            elif m == "Network.loadingFailed" and not p.get("canceled"):
                errors.append(f"network: {p.get('errorText')} (request {p.get('requestId')})")
        status = status or {}
        return {"browser": version.get("product"), "console_errors": errors, "check": status.get("check"),
                "images": status.get("images", []), "videos": status.get("videos", []), "links": status.get("links", [])}
    finally:
        try:
            pipe.send("Browser.close")
            proc.wait(timeout=10)
        except Exception:
            proc.kill()
            proc.wait()
        os.close(to_w)
        os.close(from_r)
        shutil.rmtree(profile, ignore_errors=True)
