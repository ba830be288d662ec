#!/usr/bin/env python3
"""ctest report.html_browser: a report's index.html opened in Debian's headless Chromium, driven
through the DevTools protocol (python3-websocket). For each page (a fresh report of three scenes,
and the committed reports/index.html):
  - it loads with no console error, no uncaught exception and no request other than file: and data:;
  - its summary table has one row per scene (the "### " headings of its README.md's Scenes);
  - every summary verdict links to its scene's section, which exists;
  - every plot is shown (an embedded image that decoded);
  - a click on a numeric column sorts it ascending, a second click descending; the scene column
    sorts by name;
  - the engine filter hides the other engines' error columns;
  - a screenshot of the top of the page is kept as a test artefact (ARTEFACT_DIR/NAME-top.png).
Usage: html_browser.py DROPCHECK SOURCE_DIR ARTEFACT_DIR
Exit 77 (skipped) where Chromium or python3-websocket is missing."""
import base64
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import urllib.request

DROPCHECK, SOURCE, ARTEFACTS = sys.argv[1:4]
try:
    import websocket
except ImportError:
    print("html_browser: SKIPPED: no websocket module (Debian: python3-websocket)")
    sys.exit(77)
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-headless-shell")
if not CHROMIUM:
    print("html_browser: SKIPPED: no chromium (Debian: chromium)")
    sys.exit(77)


class Browser:
    """One headless Chromium with a fresh profile, and a DevTools session on its page."""

    def __init__(self, profile):
        self.proc = subprocess.Popen(
            [CHROMIUM, "--headless=new", "--no-sandbox", "--disable-gpu", "--no-first-run",
             "--disable-extensions", "--disable-background-networking", "--disable-sync",
             "--remote-debugging-port=0", "--remote-allow-origins=*",
             "--user-data-dir=" + profile, "--window-size=1280,900", "about:blank"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
        port_file = os.path.join(profile, "DevToolsActivePort")
        deadline = time.time() + 60
        while not (os.path.exists(port_file) and open(port_file).read().count("\n") >= 1):
            if time.time() > deadline or self.proc.poll() is not None:
                raise SystemExit("html_browser: Chromium did not start")
            time.sleep(0.1)
        port = open(port_file).read().split("\n")[0]
        targets = json.load(urllib.request.urlopen("http://127.0.0.1:%s/json/list" % port))
        page = next(t for t in targets if t["type"] == "page")
        self.ws = websocket.create_connection(page["webSocketDebuggerUrl"], timeout=60)
        self.next_id = 0
        self.events = []
        for domain in ("Runtime", "Log", "Network", "Page"):
            self.call(domain + ".enable")

    def call(self, method, **params):
        self.next_id += 1
        self.ws.send(json.dumps({"id": self.next_id, "method": method, "params": params}))
        while True:
            msg = json.loads(self.ws.recv())
            if msg.get("id") == self.next_id:
                if "error" in msg:
                    raise SystemExit("html_browser: %s failed: %s" % (method, msg["error"]))
                return msg["result"]
            self.events.append(msg)

    def wait_for(self, method):
        deadline = time.time() + 60
        while time.time() < deadline:
            if any(e.get("method") == method for e in self.events):
                return
            self.events.append(json.loads(self.ws.recv()))
        raise SystemExit("html_browser: no " + method)

    def js(self, expression):
        r = self.call("Runtime.evaluate", expression=expression, returnByValue=True)
        if "exceptionDetails" in r:
            raise SystemExit("html_browser: %s threw %s" % (expression, r["exceptionDetails"]))
        return r["result"].get("value")

    def close(self):
        try:
            self.ws.close()
        finally:
            os.killpg(self.proc.pid, signal.SIGKILL)
            self.proc.wait()


def scene_count(readme):
    """The scenes of a report: the '### ' headings between '## Scenes' and the next '## '."""
    count, inside = 0, False
    for line in open(readme, encoding="utf-8"):
        if line.startswith("## "):
            inside = line.strip() == "## Scenes"
        elif inside and line.startswith("### "):
            count += 1
    return count


CHECKS = r"""
(function () {
  var summary = document.querySelector("main table");
  var heads = Array.prototype.map.call(summary.tHead.rows[0].cells, function (c) {
    return c.textContent.trim(); });
  var rows = function () { return Array.prototype.slice.call(summary.tBodies[0].rows); };
  var column = function (i) { return rows().map(function (r) { return r.cells[i].textContent.trim(); }); };
  var out = {rows: rows().length, heads: heads, broken: [],
             images: document.images.length,
             unshown: Array.prototype.filter.call(document.images, function (i) {
               return !(i.complete && i.naturalWidth > 0); }).map(function (i) { return i.alt; })};
  rows().forEach(function (r) {
    var link = r.cells[r.cells.length - 1].querySelector("a");
    var id = link ? decodeURIComponent(link.getAttribute("href").slice(1)) : "";
    if (!link || !document.getElementById(id)) out.broken.push(r.cells[0].textContent);
  });
  var numeric = heads.indexOf("error ours-f64");
  out.numeric = numeric;
  summary.tHead.rows[0].cells[numeric].click();
  out.ascending = column(numeric);
  summary.tHead.rows[0].cells[numeric].click();
  out.descending = column(numeric);
  summary.tHead.rows[0].cells[0].click();
  out.byName = column(0);
  var select = document.getElementById("engine");
  out.engines = Array.prototype.map.call(select.options, function (o) { return o.value; });
  select.value = "ours";
  select.dispatchEvent(new Event("change"));
  out.shown = Array.prototype.filter.call(summary.tHead.rows[0].cells, function (c) {
    return !c.hidden; }).map(function (c) { return c.textContent.trim(); });
  select.value = "";
  select.dispatchEvent(new Event("change"));
  window.scrollTo(0, 0);
  return out;
})()
"""

UNITS = {"m": 1, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "nm": 1e-9}


def length(text):
    """A summary length ('3.67 cm', '2.4e-11 m *'); None for '—'."""
    parts = text.replace("*", "").split()
    if len(parts) != 2 or parts[1] not in UNITS:
        return None
    return float(parts[0]) * UNITS[parts[1]]


def check_page(name, html, readme):
    profile = tempfile.mkdtemp(prefix="dropcheck-chromium-")
    browser = Browser(profile)
    try:
        browser.call("Page.navigate", url="file://" + os.path.abspath(html))
        browser.wait_for("Page.loadEventFired")
        result = browser.js(CHECKS)
        shot = browser.call("Page.captureScreenshot", format="png",
                            clip={"x": 0, "y": 0, "width": 1280, "height": 900, "scale": 1})
        browser.js("1")  # collects the events sent meanwhile
    finally:
        browser.close()
        shutil.rmtree(profile, ignore_errors=True)
    problems = []
    for e in browser.events:
        method, p = e.get("method"), e.get("params", {})
        if method == "Runtime.exceptionThrown":
            problems.append("uncaught: %s" % p["exceptionDetails"].get("text"))
        elif method == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
            problems.append("console.%s: %s" % (p["type"], p.get("args")))
        elif method == "Log.entryAdded" and p["entry"]["level"] == "error":
            problems.append("log: %s" % p["entry"]["text"])
        elif method == "Network.requestWillBeSent":
            url = p["request"]["url"]
            if not url.startswith(("file:", "data:")):
                problems.append("fetched " + url)
    scenes = scene_count(readme)
    if result["rows"] != scenes:
        problems.append("the summary has %d rows for %d scenes" % (result["rows"], scenes))
    if result["unshown"]:
        problems.append("plots not shown: %s" % result["unshown"])
    if result["images"] == 0:
        problems.append("no plot in the page")
    if result["broken"]:
        problems.append("verdicts without their scene's section: %s" % result["broken"])
    if result["numeric"] < 0:
        problems.append("no 'error ours-f64' column: %s" % result["heads"])
    else:
        values = [v for v in map(length, result["ascending"]) if v is not None]
        back = [v for v in map(length, result["descending"]) if v is not None]
        if values != sorted(values) or len(values) < 2:
            problems.append("not sorted ascending: %s" % result["ascending"])
        if back != sorted(back, reverse=True):
            problems.append("not sorted descending: %s" % result["descending"])
    if result["byName"] != sorted(result["byName"]):
        problems.append("the scene column does not sort by name: %s" % result["byName"])
    if "ours" not in result["engines"]:
        problems.append("no ours in the engine filter: %s" % result["engines"])
    if "error ours" not in result["shown"] or "error ours-f64" in result["shown"]:
        problems.append("the filter on ours shows %s" % result["shown"])
    png = base64.b64decode(shot["data"])
    if not png.startswith(b"\x89PNG") or len(png) < 10000:
        problems.append("the screenshot is not a page (%d bytes)" % len(png))
    os.makedirs(ARTEFACTS, exist_ok=True)
    with open(os.path.join(ARTEFACTS, name + "-top.png"), "wb") as f:
        f.write(png)
    if problems:
        print("html_browser: %s:\n  %s" % (html, "\n  ".join(problems)))
        return False
    print("html_browser: %s: %d summary rows, %d plots shown, sorted both ways, filtered, no "
          "console error, nothing fetched; screenshot %s-top.png (%d bytes)"
          % (html, scenes, result["images"], name, len(png)))
    return True


work = tempfile.mkdtemp(prefix="dropcheck-html-")
try:
    scenes = [os.path.join(SOURCE, "scenarios", s + ".toml")
              for s in ("bounce_e05", "slide_stop", "free_fall")]
    subprocess.run([DROPCHECK, "report"] + scenes +
                   ["--engine", "ours", "--engine", "ours-f64", "--no-timing",
                    "--out", os.path.join(work, "r")], check=True, stdout=subprocess.DEVNULL)
    ok = check_page("fresh", os.path.join(work, "r", "index.html"),
                    os.path.join(work, "r", "README.md"))
    shipped = os.path.join(SOURCE, "reports", "index.html")
    if os.path.exists(shipped):
        ok = check_page("reports", shipped, os.path.join(SOURCE, "reports", "README.md")) and ok
    else:
        print("html_browser: reports/index.html is missing (bash scripts/report.sh makes it)")
        ok = False
finally:
    shutil.rmtree(work, ignore_errors=True)
sys.exit(0 if ok else 1)
