#!/usr/bin/env python3
"""The web page (web/, built by scripts/web.sh into target/web/) tested in headless Chromium,
driven over the DevTools protocol on a pipe (standard library only):

- the page loads its module and draws a first frame;
- kilgard, single-pass and pom of the bricks on the wall, drawn in the page, match the
  command line's CPU renderer (`bumpmap render --backend cpu`) at 40 dB or more;
- every file the page's save menu offers (the normal map as 8- or 16-bit PNG or KTX2 with its
  mips, the heights, the ambient occlusion, the bent normals) is the file `bumpmap normalmap`
  writes, byte for byte;
- `inspect`'s verdict on an image given through the file input is the command line's, on a
  float OpenEXR too;
- a height field and a GLB given through the page's file input are drawn (against the command
  line with the same files and options), and a file that is not an image, a PNG that says it is
  16384² texels and a glTF without its buffers each give a message in the page and leave it
  working; after a trap (what a module out of memory ends in) the page starts a fresh module,
  says so, and draws again.

    scripts/test_web.py [--cli target/debug/bumpmap] [--screenshot docs/web_page.png] [--bench]

Without Chromium it says so and exits 0, unless CI is set (then 1). --bench prints the frame
times at 800×600 and the time from loading to the first frame (BENCHMARKS.md).
"""

import argparse
import base64
import functools
import http.server
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import threading
import time
import zlib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SITE = ROOT / "target" / "web"
MIN_PSNR = 40.0
# The canvas's pixels as base64.
CANVAS = ("(() => { const c = document.getElementById('frame');"
          " const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;"
          " let s = ''; for (let i = 0; i < d.length; i += 0x8000)"
          " s += String.fromCharCode(...d.subarray(i, i + 0x8000)); return btoa(s); })()")  # the same bytes in, wasm's f32 math against the native build's (FMA, libm)


def exr_rgb(width, height, rgb):
    """An uncompressed scanline OpenEXR file of 32-bit float R, G, B (`rgb`: row 0 first, three
    floats a pixel), written from the format's specification: the page's reader is not asked to
    read a file made by its own writer."""
    def attribute(name, kind, value):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value

    def channel(name):
        return name.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1)  # FLOAT, sampled 1×1

    window = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = (attribute("channels", "chlist", b"".join(channel(c) for c in "BGR") + b"\0")
              + attribute("compression", "compression", b"\0")
              + attribute("dataWindow", "box2i", window) + attribute("displayWindow", "box2i", window)
              + attribute("lineOrder", "lineOrder", b"\0")
              + attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0))
              + attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0))
              + attribute("screenWindowWidth", "float", struct.pack("<f", 1.0)) + b"\0")
    start = 8 + len(header) + 8 * height
    lines, offsets = [], []
    for y in range(height):
        row = rgb[3 * width * y:3 * width * (y + 1)]
        data = b"".join(struct.pack(f"<{width}f", *row[k::3]) for k in (2, 1, 0))  # B, G, R
        offsets.append(start + sum(len(line) for line in lines))
        lines.append(struct.pack("<ii", y, len(data)) + data)
    return b"\x76\x2f\x31\x01" + struct.pack("<i", 2) + header + struct.pack(f"<{height}Q", *offsets) + b"".join(lines)


def png_rgba(data):
    """An 8-bit RGB or RGBA PNG's pixels as (width, height, RGBA bytes): enough of a reader for
    the files the command line writes (non-interlaced, any filter)."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, (w, h, depth, color) = 8, b"", (0, 0, 0, 0)
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and color in (2, 6) and interlace == 0, (depth, color, interlace)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    bpp = 4 if color == 6 else 3
    raw, stride = zlib.decompress(idat), w * bpp
    out, prev = bytearray(), bytearray(stride)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        prev = line
        if bpp == 4:
            out += line
        else:
            for x in range(w):
                out += line[3 * x:3 * x + 3] + b"\xff"
    return w, h, bytes(out)


def huge_png_header():
    """A PNG that says it is 16384×16384 RGBA: its header, and one row of its pixels."""
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    header = chunk(b"IHDR", struct.pack(">IIBBBBB", 16384, 16384, 8, 6, 0, 0, 0))
    return b"\x89PNG\r\n\x1a\n" + header + chunk(b"IDAT", zlib.compress(bytes(1 + 4 * 16384))) + chunk(b"IEND", b"")


def psnr(a, b):
    """PSNR over RGB of two RGBA byte strings of one size."""
    assert len(a) == len(b), (len(a), len(b))
    se = sum((a[i] - b[i]) ** 2 for i in range(len(a)) if i % 4 != 3)
    n = len(a) // 4 * 3
    return math.inf if se == 0 else 10 * math.log10(255 ** 2 * n / se)


class Chromium:
    """Headless Chromium driven over --remote-debugging-pipe: JSON messages, each ended by NUL,
    read by Chromium on its fd 3 and written on its fd 4."""

    def __init__(self, exe, profile):
        to_chrome, self._write = os.pipe()
        self._read, from_chrome = os.pipe()
        # Above anything the child's 3 and 4 could collide with.
        hi_in, hi_out = os.dup2(to_chrome, 103), os.dup2(from_chrome, 104)

        def fds():
            os.dup2(hi_in, 3)
            os.dup2(hi_out, 4)

        self.proc = subprocess.Popen(
            [exe, "--headless=new", "--no-sandbox", "--disable-gpu", "--remote-debugging-pipe",
             f"--user-data-dir={profile}", "--no-first-run", "--hide-scrollbars", "about:blank"],
            preexec_fn=fds, pass_fds=(3, 4, 103, 104), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        for fd in (to_chrome, from_chrome, hi_in, hi_out):
            os.close(fd)
        self._id, self._buffer, self.session = 0, b"", None

    def send(self, method, timeout=120, **params):
        self._id += 1
        message = {"id": self._id, "method": method, "params": params}
        if self.session:
            message["sessionId"] = self.session
        os.write(self._write, json.dumps(message).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while True:
            while b"\0" not in self._buffer:
                if time.monotonic() > deadline:
                    raise TimeoutError(f"{method}: no answer in {timeout} s")
                chunk = os.read(self._read, 1 << 20)
                if not chunk:
                    raise RuntimeError("Chromium closed the pipe")
                self._buffer += chunk
            raw, self._buffer = self._buffer.split(b"\0", 1)
            reply = json.loads(raw)
            if reply.get("id") == self._id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply["result"]

    def evaluate(self, expression, timeout=120):
        r = self.send("Runtime.evaluate", timeout=timeout, expression=expression, awaitPromise=True,
                      returnByValue=True)
        if "exceptionDetails" in r:
            raise RuntimeError(f"{expression}: {r['exceptionDetails']}")
        return r["result"].get("value")

    def drawn(self, showing, timeout=60):
        """The page's state once a frame showing `showing` is drawn (not while it says it is
        preparing it)."""
        return self.wait_for(f"bumpmap.state().status.includes({json.dumps(showing)})"
                             " && bumpmap.state().status.includes('drawn in') && bumpmap.state()", timeout)

    def wait_for(self, expression, timeout=60):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            value = self.evaluate(expression)
            if value:
                return value
            time.sleep(0.05)
        raise TimeoutError(f"{expression} never held")

    def close(self):
        self.proc.kill()
        self.proc.wait()


def serve(directory):
    handler = functools.partial(QuietHandler, directory=str(directory))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server


class QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


def cli_render(cli, out, options):
    args = [cli, "render", "--backend", "cpu", "-o", str(out)]
    for name, value in options.items():
        args += [f"--{name}", str(value)]
    subprocess.run(args, check=True, capture_output=True)
    return png_rgba(out.read_bytes())


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cli", default=str(ROOT / "target" / "debug" / "bumpmap"))
    parser.add_argument("--screenshot", help="also save the page as it looks, as a PNG")
    parser.add_argument("--bench", action="store_true", help="print frame times at 800x600")
    args = parser.parse_args()
    exe = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")
    if not exe:
        print("test_web: no Chromium on this machine; the page is not tested here", file=sys.stderr)
        return 1 if os.environ.get("CI") else 0
    if not (SITE / "bumpmap_web.wasm").exists():
        subprocess.run([str(ROOT / "scripts" / "web.sh"), "build"], check=True)
    server = serve(SITE)
    url = f"http://127.0.0.1:{server.server_address[1]}/index.html"
    work = Path(tempfile.mkdtemp(prefix="bumpmap-web-"))
    chrome = Chromium(exe, work / "profile")
    failures = []

    def check(ok, what):
        print(("ok   " if ok else "FAIL ") + what)
        if not ok:
            failures.append(what)

    try:
        target = chrome.send("Target.createTarget", url="about:blank")["targetId"]
        chrome.session = chrome.send("Target.attachToTarget", targetId=target, flatten=True)["sessionId"]
        chrome.send("Emulation.setDeviceMetricsOverride", width=1100, height=700, deviceScaleFactor=1,
                    mobile=False)
        started = time.monotonic()
        chrome.send("Page.navigate", url=url)
        chrome.wait_for("document.body && document.body.dataset.ready === 'yes'")
        first_frame = time.monotonic() - started
        state = chrome.evaluate("bumpmap.state()")
        check(state["error"] == "" and "drawn in" in state["status"], f"the page loads and draws: {state}")
        # Dragging: the kept scene drawn again with the light turned, and back where it was.
        first = chrome.evaluate(CANVAS)
        moved = chrome.evaluate("bumpmap.draw({}, false, {light: [0.3, 0.4]}).then(r => r.status)")
        turned = chrome.evaluate(CANVAS)
        chrome.evaluate("bumpmap.draw({}, false, {light: [0, 0]}).then(r => r.status)")
        check(moved == 0 and turned != first and chrome.evaluate(CANVAS) == first,
              "a drag turns the light, drawing the kept scene, and turning it back gives the first frame")
        # A real drag with the mouse: moves faster than frames are drawn come together, and the
        # last one is drawn (the kept scene, not prepared again).
        box = chrome.evaluate("(() => { const r = document.getElementById('frame').getBoundingClientRect();"
                              " return [r.x + r.width / 2, r.y + r.height / 2]; })()")
        chrome.evaluate("document.getElementById('status').textContent = 'before the drag'")
        chrome.send("Input.dispatchMouseEvent", type="mousePressed", x=box[0], y=box[1], button="left", clickCount=1)
        for step in range(1, 9):
            chrome.send("Input.dispatchMouseEvent", type="mouseMoved", x=box[0] + 12 * step, y=box[1] - 6 * step,
                        button="left", buttons=1)
        chrome.send("Input.dispatchMouseEvent", type="mouseReleased", x=box[0] + 96, y=box[1] - 48, button="left",
                    clickCount=1)
        dragged = chrome.wait_for("bumpmap.state().status.includes('; drawn in') && bumpmap.state()")
        check(chrome.evaluate(CANVAS) != first and not dragged["error"], f"a mouse drag moves the light: {dragged}")
        chrome.evaluate("bumpmap.draw({}, false, {light: [0, 0]}).then(r => r.status)")

        options = {"scene": "wall", "size": 256, "light": "dir:0.4,0.5,1"}
        drawn = []  # each technique's frame, none the same as another's
        for technique in ["kilgard", "single-pass", "pom"]:
            text = "\\n".join(f"{k}={v}" for k, v in {**options, "technique": technique}.items())
            page = chrome.evaluate(f'bumpmap.render("{text}")')
            w, h, native = cli_render(args.cli, work / f"{technique}.png", {**options, "technique": technique})
            got = base64.b64decode(page["data"]) if page["status"] == 0 else b""
            ok = page["status"] == 0 and (page["width"], page["height"]) == (w, h) and len(got) == len(native)
            value = psnr(got, native) if ok else 0.0
            lit = sum(got[i] for i in range(0, len(got), 4)) / max(1, len(got) // 4)
            check(ok and value >= MIN_PSNR and lit > 10 and got not in drawn,
                  f"{technique} on the wall in the page against the command line: {value:.1f} dB "
                  f"(red mean {lit:.1f}, CRC {zlib.crc32(got):08x})")
            drawn.append(got)

        # Every file the save menu offers, against the command line's.
        made_by = {
            "normal-png-8": ["-o", "{out}"],
            "normal-png-16": ["-o", "{out}", "--bits", "16"],
            "normal-ktx2-8": ["-o", "{out}", "--mips"],
            "normal-ktx2-16": ["-o", "{out}", "--mips", "--bits", "16"],
            "heights-png-16": ["-o", "{unused}", "--height-out", "{out}", "--bits", "16"],
            "occlusion-png-8": ["-o", "{unused}", "--ao-out", "{out}"],
            "bent-png-8": ["-o", "{unused}", "--bent-normals-out", "{out}"],
        }
        menu = chrome.evaluate("Array.from(document.querySelector('select[name=save-as]').options, o => o.value)")
        check(sorted(menu) == sorted(made_by), f"the save menu offers the files tested here: {menu}")
        for entry in menu:
            page = chrome.evaluate(f'bumpmap.mapFile("scale=4", "bricks@256", "{entry}")')
            out = work / f"{entry}.{'ktx2' if 'ktx2' in entry else 'png'}"
            cli = [a.format(out=out, unused=work / "unused.png") for a in made_by.get(entry, [])]
            subprocess.run([args.cli, "normalmap", "bricks@256", "--scale", "4", *cli], check=True, capture_output=True)
            got = base64.b64decode(page["data"]) if page["status"] == 0 else page["data"].encode()
            check(page["status"] == 0 and got == out.read_bytes(),
                  f"{entry} as the page saves it is normalmap's file, byte for byte ({len(got)} bytes)")
        # What the file input gives the page below: the normal map's PNG.
        shutil.copy(work / "normal-png-8.png", work / "n.png")
        # The button itself: the occlusion (seconds of horizons) made, saved and said.
        chrome.evaluate("document.querySelector('select[name=save-as]').value = 'occlusion-png-8';"
                        "document.getElementById('export').click(); true")
        # The module works in a worker: the page answers at once, still saying what it makes.
        asked = time.monotonic()
        meanwhile = chrome.evaluate("bumpmap.state().status")
        answered_ms = (time.monotonic() - asked) * 1000
        check(meanwhile.startswith("making") and answered_ms < 200,
              f"the page answers while the worker makes the map: '{meanwhile}' in {answered_ms:.0f} ms")
        said = chrome.wait_for("bumpmap.state().status.startsWith('saved') && bumpmap.state()")
        check(said["status"].startswith("saved bricks_ao.png") and not said["error"],
              f"the save button names the file it saved: {said['status']}")

        # The user's own heights through the file input.
        heights = work / "heights.png"
        subprocess.run([args.cli, "normalmap", "pinwheel@128", "-o", str(work / "unused.png"),
                        "--height-out", str(heights)], check=True, capture_output=True)
        doc = chrome.send("DOM.getDocument")["root"]["nodeId"]
        node = chrome.send("DOM.querySelector", nodeId=doc, selector="input[name=file]")["nodeId"]
        chrome.send("DOM.setFileInputFiles", files=[str(heights)], nodeId=node)
        state = chrome.drawn("heights.png")
        canvas = chrome.evaluate(CANVAS)
        w, h, native = cli_render(args.cli, work / "dropped.png", {
            "scene": "torus", "technique": "single-pass", "bump-scale": 4, "width": 512, "height": 512,
            "height-field": heights})
        value = psnr(base64.b64decode(canvas), native)
        check(value >= MIN_PSNR, f"heights from the file input drawn as the command line draws them: {value:.1f} dB")

        # inspect's verdict on an image given through the file input: the command line's lines.
        chrome.send("DOM.setFileInputFiles", files=[str(work / "n.png")], nodeId=node)
        chrome.drawn("n.png")
        chrome.evaluate("document.getElementById('inspect').click()")
        verdict = chrome.wait_for("bumpmap.state().verdict")
        cli = subprocess.run([args.cli, "inspect", str(work / "n.png")], check=True, capture_output=True, text=True)
        check(verdict.splitlines()[1:] == cli.stdout.strip().splitlines()[1:] and "convention: opengl" in verdict,
              f"inspect's verdict in the page is the command line's: {verdict.splitlines()[2:3]}")
        # A float normal map (OpenEXR, decoded in the module): n.png's vectors, signed.
        w, h, rgba = png_rgba((work / "n.png").read_bytes())
        signed = [c / 127.5 - 1.0 for i, c in enumerate(rgba) if i % 4 != 3]
        (work / "n_float.exr").write_bytes(exr_rgb(w, h, signed))
        chrome.send("DOM.setFileInputFiles", files=[str(work / "n_float.exr")], nodeId=node)
        chrome.wait_for("bumpmap.state().status.includes('n_float.exr') && bumpmap.state().status.includes('drawn in')")
        chrome.evaluate("document.getElementById('inspect').click()")
        verdict = chrome.wait_for("(bumpmap.state().verdict || bumpmap.state().error)")
        cli = subprocess.run([args.cli, "inspect", str(work / "n_float.exr")], capture_output=True, text=True)
        check(verdict.splitlines()[1:] == cli.stdout.strip().splitlines()[1:] and "floating point" in verdict
              and "convention: opengl" in verdict,
              f"inspect's verdict on an OpenEXR in the page is the command line's: {verdict.splitlines()[:3]}")
        chrome.send("DOM.setFileInputFiles", files=[str(work / "n.png")], nodeId=node)
        chrome.drawn("n.png")
        # The same image drawn as the normal map it is.
        chrome.evaluate("const s = document.querySelector('select[name=\"image-is\"]'); s.value = 'normal-map';"
                        " s.dispatchEvent(new Event('input', {bubbles: true}))")
        chrome.drawn("normal map: n.png")
        w, h, native = cli_render(args.cli, work / "as_normal_map.png", {
            "scene": "torus", "technique": "single-pass", "bump-scale": 4, "width": 512, "height": 512,
            "normal-map": work / "n.png"})
        value = psnr(base64.b64decode(chrome.evaluate(CANVAS)), native)
        check(value >= MIN_PSNR, f"an image given as the normal map drawn as `render --normal-map` draws it: {value:.1f} dB")
        chrome.evaluate("const t = document.querySelector('select[name=\"image-is\"]'); t.value = 'heights';"
                        " t.dispatchEvent(new Event('input', {bubbles: true}))")

        # A model through the file input: drawn with its own material, as the command line does.
        cube = work / "cube.glb"
        subprocess.run([args.cli, "tangents", str(ROOT / "crates/bumpmap-io/tests/data/mikktspace/cube.obj"),
                        "-o", str(cube)], check=True, capture_output=True)
        chrome.send("DOM.setFileInputFiles", files=[str(cube)], nodeId=node)
        chrome.drawn("cube.glb")
        w, h, native = cli_render(args.cli, work / "cube.png", {
            "scene": f"mesh:{cube}", "technique": "single-pass", "bump-scale": 4, "width": 512, "height": 512})
        value = psnr(base64.b64decode(chrome.evaluate(CANVAS)), native)
        check(value >= MIN_PSNR, f"a GLB from the file input drawn as `render --scene mesh:` draws it: {value:.1f} dB")

        for name, data, says in [
            ("notes.png", b"these are not pixels", "notes.png"),
            ("huge.png", huge_png_header(), "16384"),
            ("parts.gltf", b'{"asset":{"version":"2.0"},"buffers":[{"uri":"parts.bin","byteLength":48}]}', "parts"),
        ]:
            (work / name).write_bytes(data)
            chrome.send("DOM.setFileInputFiles", files=[str(work / name)], nodeId=node)
            try:
                state = chrome.wait_for(f"bumpmap.state().error.includes('{name}') && bumpmap.state()", timeout=20)
            except TimeoutError:
                state = chrome.evaluate("bumpmap.state()")
            check(name in state["error"] and says in state["error"], f"{name}: a message in the page: {state['error']!r}")
        chrome.send("DOM.setFileInputFiles", files=[str(heights)], nodeId=node)
        state = chrome.drawn("heights.png")
        check("heights.png" in state["status"], f"the page draws again after them: {state['status']}")

        # After a trap the page starts a fresh module and draws again.
        chrome.evaluate("bumpmap.trapForTest()")
        state = chrome.drawn("bricks")
        check("started again" in state["error"] and "drawn in" in state["status"],
              f"after a trap the module is started again and draws: {state['error']!r}, {state['status']!r}")

        if args.bench:
            # The page as it opens (the torus, bricks), each frame drawn and put on the canvas.
            print(f"load to first frame: {first_frame * 1000:.0f} ms")
            chrome.send("Page.navigate", url=url)
            chrome.wait_for("document.body && document.body.dataset.ready === 'yes'")
            for technique in ["single-pass", "pom"]:
                for w, h in [(800, 600), (512, 512)]:
                    draw = f'bumpmap.draw({{width: {w}, height: {h}, technique: "{technique}"}}).then(r => r.ms)'
                    times = sorted(chrome.evaluate(draw) for _ in range(7))
                    print(f"{technique} {w}x{h}: prepared and drawn, median {times[3]:.0f} ms, fastest {times[0]:.0f} ms")
                    # What a drag costs: the kept scene drawn with the light turned a little more.
                    drag = "bumpmap.draw({}, false, {light: [Math.random(), 0.2]}).then(r => r.ms)"
                    times = sorted(chrome.evaluate(drag) for _ in range(7))
                    print(f"{technique} {w}x{h}: drawn (a drag), median {times[3]:.0f} ms, fastest {times[0]:.0f} ms")
        if args.screenshot:
            chrome.send("Page.navigate", url=url)
            chrome.wait_for("document.body && document.body.dataset.ready === 'yes'")
            # The page as a user leaves it after saving a map the menu offers.
            chrome.drawn("bricks")
            chrome.evaluate("document.querySelector('select[name=save-as]').value = 'occlusion-png-8';"
                            "document.getElementById('export').click(); true")
            chrome.wait_for("bumpmap.state().status.startsWith('saved')")
            shot = chrome.send("Page.captureScreenshot", format="png")["data"]
            Path(args.screenshot).write_bytes(base64.b64decode(shot))
            print(f"wrote {args.screenshot}")
    finally:
        chrome.close()
        server.shutdown()
        shutil.rmtree(work, ignore_errors=True)
    if failures:
        print(f"test_web: {len(failures)} failed", file=sys.stderr)
        return 1
    print("test_web: all passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
