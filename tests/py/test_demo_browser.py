"""Opens the report of `strictmin demo` in headless Chromium: the page must load without
console errors, every image on it must load, and its screenshot must show the colour-coded
pictures (not a blank page). Run by ctest with STRICTMIN_CLI pointing at the built tool;
exits 77 (skipped) when /usr/bin/chromium is missing (Debian package chromium)."""
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

CLI = os.environ.get("STRICTMIN_CLI", "strictmin")
CHROMIUM = "/usr/bin/chromium"
SKIP = 77

# A copy of index.html with this script appended reports every image that failed to load.
IMAGE_CHECK = """<script>
window.addEventListener('load', () => {
  let failed = 0;
  for (const img of document.images)
    if (!img.complete || img.naturalWidth === 0) { failed++; console.error('image failed to load: ' + img.getAttribute('src')); }
  console.log('strictmin-check: ' + document.images.length + ' images, ' + failed + ' failed');
});
</script>
"""

CONSOLE_PROBLEMS = re.compile(r"Uncaught|ERROR:CONSOLE|Failed to load|Not allowed to load|ERR_FILE_NOT_FOUND|"
                              r"image failed to load|Refused to")


def fail(message):
    print("FAIL: " + message, file=sys.stderr)
    sys.exit(1)


def chromium(url, out_dir, *extra):
    profile = tempfile.mkdtemp(prefix="strictmin-chromium-")
    try:
        p = subprocess.run(
            [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
             "--disable-background-networking", "--disable-component-update", "--disable-sync",
             "--user-data-dir=" + profile, "--enable-logging=stderr", "--v=0", *extra, url],
            capture_output=True, text=True, timeout=180, cwd=out_dir)
    finally:
        shutil.rmtree(profile, ignore_errors=True)
    return p


def console_lines(log):
    return [line for line in log.splitlines() if "CONSOLE" in line or "Uncaught" in line]


def decode_png(path):
    """(width, height, bytes per pixel, rows) of an 8-bit non-interlaced PNG, with zlib only."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail(path + " is not a PNG")
    pos, idat, ihdr = 8, [], None
    while pos < len(data):
        n, = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
        pos += 12 + n
    w, h, depth, ctype, _, _, interlace = ihdr
    if depth != 8 or interlace != 0 or ctype not in (0, 2, 4, 6):
        fail(f"{path}: unexpected PNG format (depth {depth}, colour type {ctype}, interlace {interlace})")
    bpp = {0: 1, 2: 3, 4: 2, 6: 4}[ctype]
    raw = zlib.decompress(b"".join(idat))
    stride = w * bpp
    rows, prev, i = [], bytearray(stride), 0
    for _ in range(h):
        f = raw[i]
        line = bytearray(raw[i + 1:i + 1 + stride])
        i += 1 + stride
        if f == 1:
            for x in range(bpp, stride):
                line[x] = (line[x] + line[x - bpp]) & 255
        elif f == 2:
            line = bytearray((a + b) & 255 for a, b in zip(line, prev))
        elif f == 3:
            for x in range(stride):
                line[x] = (line[x] + ((line[x - bpp] if x >= bpp else 0) + prev[x]) // 2) & 255
        elif f == 4:
            for x in range(stride):
                a = line[x - bpp] if x >= bpp else 0
                b, c = prev[x], (prev[x - bpp] if x >= bpp else 0)
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return w, h, bpp, rows


def main():
    if not os.path.exists(CHROMIUM):
        print(f"skipped: {CHROMIUM} not found (apt-get install chromium)", file=sys.stderr)
        return SKIP
    with tempfile.TemporaryDirectory(prefix="strictmin-demo-") as tmp:
        out = os.path.join(tmp, "demo")
        p = subprocess.run([CLI, "demo", "--out", out, "--quiet"], capture_output=True, text=True, timeout=300)
        if p.returncode != 0:
            fail(f"strictmin demo exited {p.returncode}\nstdout: {p.stdout}\nstderr: {p.stderr}")
        index = os.path.join(out, "index.html")
        if "index.html" not in p.stdout or not os.path.exists(index):
            fail("demo did not say where its index.html is: " + p.stdout)
        with open(index, encoding="utf-8") as f:
            html = f.read()

        # Every referenced file exists; nothing is fetched from the network.
        refs = re.findall(r'(?:src|href)="([^"]*)"', html)
        images = re.findall(r'<img [^>]*src="([^"]*)"', html)
        for ref in refs:
            if ref.startswith("#"):
                continue
            if ":" in ref or ref.startswith("/"):
                fail("index.html refers to a non-relative address: " + ref)
            if not os.path.exists(os.path.join(out, ref)):
                fail("index.html refers to a missing file: " + ref)
        if len(images) < 10:
            fail(f"expected the demo's pictures and histograms, found {len(images)} images")
        if "<script" in html:
            fail("the report must not need scripts")

        # 1. The page as it is: no console errors, and a screenshot that is not blank.
        shot = os.path.join(tmp, "shot.png")
        p = chromium("file://" + index, out, "--screenshot=" + shot, "--window-size=1400,1000",
                     "--hide-scrollbars")
        problems = [line for line in console_lines(p.stderr) if CONSOLE_PROBLEMS.search(line)]
        if problems:
            fail("console errors:\n" + "\n".join(problems))
        if not os.path.exists(shot):
            fail(f"chromium wrote no screenshot (exit {p.returncode}):\n{p.stderr[-3000:]}")
        w, h, bpp, rows = decode_png(shot)
        if bpp < 3:
            fail("the screenshot is not an RGB picture")
        if (w, h) != (1400, 1000):
            fail(f"screenshot is {w}x{h}, not 1400x1000")
        colours, non_white, deep_blue = set(), 0, 0
        for row in rows[::2]:
            for x in range(0, w * bpp, 2 * bpp):
                r, g, b = row[x], row[x + 1], row[x + 2]
                colours.add((r >> 3, g >> 3, b >> 3))
                if r < 245 or g < 245 or b < 245:
                    non_white += 1
                if b > 110 and r < 40 and g < 40:  # the dark blue of low distortion in the pictures
                    deep_blue += 1
        sampled = (h // 2) * (w // 2)
        if len(colours) < 50 or non_white < sampled // 20:
            fail(f"the screenshot looks blank: {len(colours)} colours, {non_white} of {sampled} sampled pixels not white")
        if deep_blue < 200:
            fail(f"the colour-coded pictures do not show in the screenshot ({deep_blue} dark blue pixels)")

        # 2. A copy with a script that reports every image that failed to load.
        check = os.path.join(out, "index-check.html")
        with open(check, "w", encoding="utf-8") as f:
            f.write(html.replace("</body>", IMAGE_CHECK + "</body>"))
        p = chromium("file://" + check, out, "--screenshot=" + os.path.join(tmp, "check.png"),
                     "--window-size=1400,1000")
        lines = console_lines(p.stderr)
        summary = [line for line in lines if "strictmin-check:" in line]
        if not summary:
            fail("the image check did not run:\n" + p.stderr[-3000:])
        m = re.search(r"strictmin-check: (\d+) images, (\d+) failed", summary[0])
        if not m or int(m.group(1)) != len(images) or int(m.group(2)) != 0:
            fail("images failed to load:\n" + "\n".join(lines))
        print(f"ok: {len(images)} images load, no console errors, screenshot {w}x{h} with {len(colours)} colours")
    return 0


if __name__ == "__main__":
    sys.exit(main())
