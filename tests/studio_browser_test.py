#!/usr/bin/python3
"""hapcine studio in a real headless Chromium (docs/studio.md).

    studio_browser_test.py HAPCINE WORK_DIR [--screenshots DIR] [--keep]

Makes a short two-shot synthetic film, starts `hapcine studio` on a free
port, and drives the page: play (the playhead follows), seek by clicking the
timeline (video.currentTime follows), drag an effect block, set shot 1's gain
to 0, save, export the haptic track. Checks against the written files that
the track changed exactly there (zero in shot 1 after the documented cut
crossfade, identical before the cut) and that the edits file holds the moved
effect; checks that a stale save gets the conflict message; and that the
video, the timeline and the seat view render (pixels in each element's
rectangle of a screenshot that differ from its background).
Exit 77 (ctest: skipped) when Chromium, chromedriver or Selenium is absent.
"""
import argparse
import csv
import json
import os
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
import zlib

SKIP = 77
CHROMIUM_FLAGS = ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update", "--disable-sync",
                  "--window-size=1440,1000", "--autoplay-policy=no-user-gesture-required", "--mute-audio"]
PRESET, CUT_S, CUT_RAMP_S, DURATION_S = "hard_cut", 2.0, 0.5, 4.0


def fail(message):
    print(f"FAIL: {message}", flush=True)
    sys.exit(1)


def check(condition, message):
    if not condition:
        fail(message)
    print(f"ok: {message}", flush=True)


def find_browser():
    """chromium and chromedriver paths, or None when either is missing."""
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    driver = shutil.which("chromedriver") or ("/usr/bin/chromedriver" if os.path.exists("/usr/bin/chromedriver") else None)
    return (chromium, driver) if chromium and driver else None


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def make_film(hapcine, work):
    films = os.path.join(work, "films")
    film = os.path.join(films, f"{PRESET}.mp4")
    if not os.path.exists(film):
        subprocess.run([hapcine, "synth", PRESET, "-o", films, "--width", "256", "--height", "144",
                        "--duration-s", str(DURATION_S), "--supersample", "1"], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return film


def start_studio(hapcine, film, port, log_path):
    """The server process once it prints its URL."""
    log = open(log_path, "w")
    proc = subprocess.Popen([hapcine, "studio", film, "--port", str(port)], stdout=subprocess.PIPE,
                            stderr=log, text=True)
    deadline = time.time() + 120
    while time.time() < deadline:
        line = proc.stdout.readline()
        if not line:
            if proc.poll() is not None:
                fail(f"hapcine studio exited with {proc.returncode} (log: {log_path})")
            continue
        print(f"studio: {line.rstrip()}", flush=True)
        if "serving" in line and "http://" in line:
            return proc, line[line.index("http://"):].split()[0]
    fail("hapcine studio did not print its URL within 120 s")


def http_json(method, url, body=None):
    data = json.dumps(body).encode() if body is not None else None
    request = urllib.request.Request(url, data=data, method=method,
                                     headers={"Content-Type": "application/json"} if data else {})
    try:
        with urllib.request.urlopen(request, timeout=60) as response:
            return response.status, json.loads(response.read() or b"{}")
    except urllib.error.HTTPError as e:
        return e.code, json.loads(e.read() or b"{}")


def read_track(path):
    """{t: (9 actuator coordinates)} of a haptic CSV."""
    rows = {}
    with open(path) as f:
        lines = [line for line in f if not line.startswith("#") and line.strip()]
    reader = csv.DictReader(lines)
    columns = [c for c in reader.fieldnames if c[:2] in ("hx", "hy", "hz", "lx", "ly", "lz", "rx", "ry", "rz")
               or c.split("_")[0] in ("head", "left", "right")]
    for row in reader:
        rows[round(float(row[reader.fieldnames[0]]), 6)] = tuple(float(row[c]) for c in columns)
    if not columns or not rows:
        fail(f"{path}: no actuator columns found in {reader.fieldnames}")
    return rows


# ---- PNG decoding (8-bit RGB/RGBA, non-interlaced: what Chromium writes)
def decode_png(data):
    """(width, height, channels, rows of bytes)."""
    pos, chunks, header = 8, [], None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            chunks.append(body)
        pos += 12 + length
    width, height, depth, color, _, _, interlace = header
    if depth != 8 or color not in (2, 6) or interlace:
        fail(f"unexpected PNG format depth={depth} color={color}")
    channels = 4 if color == 6 else 3
    raw = zlib.decompress(b"".join(chunks))
    return width, height, channels, unfilter(raw, width, height, channels)


def unfilter(raw, width, height, bpp):
    stride, rows, prev, pos = width * bpp, [], bytearray(width * bpp), 0
    for _ in range(height):
        kind, line = raw[pos], bytearray(raw[pos + 1:pos + 1 + stride])
        pos += 1 + stride
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + ((a + b) >> 1)) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return rows


def drawn_fraction(png):
    """The fraction of an element screenshot's pixels that differ from its most common colour."""
    width, height, channels, rows = decode_png(png)
    counts = {}
    step = 2  # every other pixel and row: enough, and fast in pure Python
    for y in range(0, height, step):
        row = rows[y]
        for x in range(0, width, step):
            key = bytes(row[x * channels:x * channels + 3])
            counts[key] = counts.get(key, 0) + 1
    background = max(counts, key=counts.get)
    total = sum(counts.values())
    differ = sum(n for color, n in counts.items()
                 if sum(abs(color[i] - background[i]) for i in range(3)) > 30)
    return differ / total


# ---- the browser
def open_browser(driver_path, profile):
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    options = webdriver.ChromeOptions()
    for flag in CHROMIUM_FLAGS + [f"--user-data-dir={profile}"]:
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service(driver_path), options=options)


def wait_for(driver, script, what, timeout=30):
    deadline = time.time() + timeout
    while time.time() < deadline:
        value = driver.execute_script(script)
        if value:
            return value
        time.sleep(0.1)
    fail(f"timed out waiting for {what}")


def click_timeline_at(driver, t, lane="angles"):
    """Clicks the timeline canvas at time t, in the middle of a lane, at viewport coordinates
    (Selenium's element offsets count from the in-view centre, which moves when the page scrolls)."""
    from selenium.webdriver.common.action_chains import ActionChains
    x, y = driver.execute_script(
        "const canvas = document.getElementById('timeline');"
        "const lane = hapcineStudio.lanes.find(l => l.key === arguments[1]);"
        "canvas.scrollIntoView({block: 'nearest'});"
        "const r = canvas.getBoundingClientRect();"
        "return [r.left + hapcineStudio.timeToX(arguments[0]), r.top + lane.top + lane.height / 2];", t, lane)
    actions = ActionChains(driver)
    actions.w3c_actions.pointer_action.move_to_location(round(x), round(y))
    actions.w3c_actions.pointer_action.click()
    actions.perform()


def video_time(driver):
    return driver.execute_script("return document.getElementById('video').currentTime")


def step_play(driver):
    driver.execute_script("document.getElementById('video').play()")
    wait_for(driver, "return document.getElementById('video').currentTime > 0.4", "the video to play")
    x0 = driver.execute_script("return parseFloat(document.getElementById('playhead').style.left)")
    time.sleep(0.3)
    x1 = driver.execute_script("return parseFloat(document.getElementById('playhead').style.left)")
    driver.execute_script("document.getElementById('video').pause()")
    check(x1 > x0, f"playing moves the playhead ({x0:.1f} -> {x1:.1f} px)")


def step_seek(driver):
    for target in (1.3, 3.1):
        click_timeline_at(driver, target)
        wait_for(driver, f"return Math.abs(document.getElementById('video').currentTime - {target}) < 0.05",
                 f"the video to seek to {target} s")
        check(True, f"a click on the timeline at {target} s seeks the video there ({video_time(driver):.3f} s)")


def step_drag_keyframe(driver):
    """Drags effect 0 by 30 px towards the larger free room; returns its new (start, end)."""
    from selenium.webdriver.common.action_chains import ActionChains
    state = "hapcineStudio.state.edits.keyframes()"
    if not driver.execute_script(f"return {state}.length"):
        driver.execute_script("document.getElementById('video').currentTime = 0.2")
        wait_for(driver, "return Math.abs(document.getElementById('video').currentTime - 0.2) < 0.01", "seek to 0.2 s")
        driver.find_element("id", "add-keyframe").click()
    segments = driver.execute_script(f"return {state}")
    before = segments[0]
    room_left = before["start_s"]
    room_right = (segments[1]["start_s"] if len(segments) > 1 else DURATION_S) - before["end_s"]
    pixels = 30 if room_right >= room_left else -30
    seconds_per_px = driver.execute_script("return hapcineStudio.xToTime(1) - hapcineStudio.xToTime(0)")
    fps = driver.execute_script("return hapcineStudio.state.film.fps")
    expected = max(-room_left, min(room_right, pixels * seconds_per_px))
    block = driver.find_element("id", "keyframe-0")
    ActionChains(driver).click_and_hold(block).move_by_offset(pixels // 2, 0).move_by_offset(pixels // 2, 0) \
        .release().perform()
    after = driver.execute_script(f"return {state}[0]")
    moved = after["start_s"] - before["start_s"]
    length_change = (after["end_s"] - after["start_s"]) - (before["end_s"] - before["start_s"])
    check(abs(moved - expected) <= 1 / fps + 1e-6 and moved != 0 and abs(length_change) < 1e-5,
          f"dragging keyframe-0 by {pixels} px moves it by {moved:+.3f} s (expected {expected:+.3f} s within a frame): "
          f"{before['start_s']:.3f}-{before['end_s']:.3f} -> {after['start_s']:.3f}-{after['end_s']:.3f} s, same length")
    return after


def step_gain_zero(driver):
    from selenium.webdriver.common.keys import Keys
    click_timeline_at(driver, CUT_S + 0.7)
    wait_for(driver, "return hapcineStudio.state.selectedShot === 1", "shot 1 selected")
    gain = driver.find_element("id", "gain-input")
    gain.clear()
    gain.send_keys("0", Keys.TAB)
    wait_for(driver, "return hapcineStudio.state.edits.shotEdit(1).gain === 0", "the gain edit")
    check(True, "shot 1's gain input set to 0")
    # Undo and redo through the keyboard.
    from selenium.webdriver.common.action_chains import ActionChains
    driver.execute_script("document.activeElement.blur()")
    ActionChains(driver).key_down(Keys.CONTROL).send_keys("z").key_up(Keys.CONTROL).perform()
    undone = driver.execute_script("return hapcineStudio.state.edits.shotEdit(1).gain")
    ActionChains(driver).key_down(Keys.CONTROL).key_down(Keys.SHIFT).send_keys("z").key_up(Keys.SHIFT).key_up(Keys.CONTROL).perform()
    redone = driver.execute_script("return hapcineStudio.state.edits.shotEdit(1).gain")
    check(undone is None and redone == 0, "Ctrl+Z undoes the gain edit, Ctrl+Shift+Z redoes it")


def step_save(driver):
    started = time.time()
    driver.find_element("id", "save").click()
    status = wait_for(driver, "const s = document.getElementById('save-status').textContent;"
                              "return s.startsWith('Saved') || s.startsWith('Not saved') ? s : ''", "the save", 60)
    check(status.startswith("Saved"), f"save: '{status}' in {time.time() - started:.2f} s")
    return time.time() - started


def step_export(driver, path, previous_mtime):
    driver.find_element("id", "export-haptic").click()
    text = wait_for(driver, "const s = document.getElementById('export-text').textContent;"
                            "return s.startsWith('Wrote') || s.startsWith('Export failed') ? s : ''", "the export", 60)
    check(text.startswith("Wrote") and os.path.exists(path) and os.path.getmtime(path) != previous_mtime,
          f"export haptic: '{text}'")


def compare_tracks(before, after):
    check(set(before) == set(after), f"the edited track has the same {len(before)} sample times")
    cut_end = CUT_S + CUT_RAMP_S
    same = [t for t in before if t < CUT_S - 1e-6]
    zero = [t for t in before if t >= cut_end + 0.05]
    check(all(before[t] == after[t] for t in same), f"shot 0 unchanged ({len(same)} samples before the cut)")
    check(any(any(abs(v) > 1e-3 for v in before[t]) for t in zero), "the original track moves in shot 1")
    worst = max(max(abs(v) for v in after[t]) for t in zero)
    check(worst < 1e-9, f"shot 1 is zero after the {CUT_RAMP_S} s cut crossfade ({len(zero)} samples, max |x| {worst:g})")


def step_conflict(driver, base_url):
    """A save from another client makes this page's next save stale."""
    from selenium.webdriver.common.keys import Keys
    film_id = driver.execute_script("return hapcineStudio.state.film.id")
    status, edits = http_json("GET", f"{base_url}api/films/{film_id}/edits")
    edits.setdefault("x-note", "another tab")
    status, answer = http_json("PUT", f"{base_url}api/films/{film_id}/edits", edits)
    check(status == 200, f"a save from another client: {status} {answer}")
    gain = driver.find_element("id", "gain-input")
    gain.clear()
    gain.send_keys("0.5", Keys.TAB)
    driver.find_element("id", "save").click()
    text = wait_for(driver, "const s = document.getElementById('save-status').textContent;"
                            "return s.startsWith('Not saved') || s.startsWith('Saved') ? s : ''", "the stale save")
    check("saved elsewhere" in text and driver.find_elements("id", "reload-edits"),
          f"a stale save shows the conflict and offers reload: '{text}'")
    driver.find_element("id", "reload-edits").click()
    wait_for(driver, "return document.getElementById('save-status').textContent.startsWith('Reloaded')", "reload")
    check(driver.execute_script("return hapcineStudio.state.edits.shotEdit(1).gain") == 0, "reload brings the saved edits back")


def step_panel_controls(driver):
    """The shot panel's other controls and the effect buttons edit the state; undo walks back."""
    from selenium.webdriver.support.ui import Select
    edit = "return hapcineStudio.state.edits.shotEdit(0)"
    click_timeline_at(driver, 0.3)
    wait_for(driver, "return hapcineStudio.state.selectedShot === 0", "shot 0 selected")
    Select(driver.find_element("id", "model-select")).select_by_value("semantic")
    Select(driver.find_element("id", "washout-select")).select_by_value("off")
    driver.find_element("id", "mute-checkbox").click()
    got = driver.execute_script(edit)
    check(got == {"shot": 0, "model": "semantic", "mute": True, "washout": {"mode": "off"}},
          f"model, washout and mute of shot 0 in the edits: {got}")
    driver.find_element("id", "reset-shot").click()
    check(driver.execute_script(edit) == {"shot": 0}, "reset-shot removes the shot's edits")
    count = "return hapcineStudio.state.edits.keyframes().length"
    segments = driver.execute_script("return hapcineStudio.state.edits.keyframes()")
    n = len(segments)
    bounds = [0.0] + [x for k in segments for x in (k["start_s"], k["end_s"])] + [DURATION_S]
    gap_start, _ = max(zip(bounds[::2], bounds[1::2]), key=lambda g: g[1] - g[0])
    click_timeline_at(driver, gap_start + 0.05, lane="fov")  # in the largest free gap
    driver.find_element("id", "add-keyframe").click()
    added = driver.execute_script(count)
    driver.find_element("id", "delete-keyframe").click()
    check(added == n + 1 and driver.execute_script(count) == n,
          f"add-keyframe adds an effect at the playhead ({n} -> {added}), delete-keyframe deletes it")
    for _ in range(6):
        driver.find_element("id", "undo").click()
    got, now = driver.execute_script(edit), driver.execute_script(count)
    check(got == {"shot": 0} and now == n, f"the undo button walks the six steps back: {got}, {now} effects")


def step_render_check(driver, shots_dir):
    """Each of video, timeline and seat view draws something (and the page screenshots for the docs)."""
    wait_for(driver, "return document.getElementById('video').readyState >= 2", "a video frame")
    for element_id, minimum in (("video", 0.2), ("timeline", 0.05), ("seat-view", 0.03)):
        element = driver.find_element("id", element_id)
        png = element.screenshot_as_png
        fraction = drawn_fraction(png)
        check(fraction > minimum, f"#{element_id} renders: {100 * fraction:.1f} % of its pixels differ from its background")


def step_docs_screenshots(driver, shots_dir):
    """The page after the edits (shot 1 muted, the moved effect selected), and the seat and
    the timeline on their own, for docs/studio.md."""
    if not shots_dir:
        return
    click_timeline_at(driver, 0.9)
    wait_for(driver, "return Math.abs(document.getElementById('video').currentTime - 0.9) < 0.05", "seek to 0.9 s")
    driver.find_element("id", "keyframe-0").click()
    time.sleep(0.5)
    save_page_screenshot(driver, os.path.join(shots_dir, "studio_page.png"))
    for element_id in ("timeline-area", "seat-panel", "shot-panel"):
        with open(os.path.join(shots_dir, f"studio_{element_id.replace('-', '_')}.png"), "wb") as f:
            f.write(driver.find_element("id", element_id).screenshot_as_png)


def save_page_screenshot(driver, path, scale=0.75):
    """The window, scaled down (a small PNG for the docs)."""
    import base64
    width, height = driver.execute_script("return [window.innerWidth, window.innerHeight]")
    shot = driver.execute_cdp_cmd("Page.captureScreenshot", {
        "format": "png",
        "clip": {"x": 0, "y": 0, "width": width, "height": height, "scale": scale}})
    with open(path, "wb") as f:
        f.write(base64.b64decode(shot["data"]))


def browser_log_errors(driver):
    """Console errors, apart from the favicon and the stale save's expected 409."""
    expected = ("favicon", "status of 409")
    return [e for e in driver.get_log("browser")
            if e["level"] == "SEVERE" and not any(x in e["message"] for x in expected)]


def run(args, driver_path):
    work = os.path.abspath(args.work_dir)
    os.makedirs(work, exist_ok=True)
    started = time.time()
    film = make_film(args.hapcine, work)
    stem = os.path.splitext(film)[0]
    for leftover in (f"{stem}.edits.json", f"{stem}.haptic.csv"):
        if os.path.exists(leftover):
            os.remove(leftover)
    print(f"film ready in {time.time() - started:.1f} s", flush=True)
    proc, url = start_studio(args.hapcine, film, free_port(), os.path.join(work, "studio.log"))
    profile = tempfile.mkdtemp(prefix="hapcine-chromium-")
    driver = None
    try:
        film_id = http_json("GET", f"{url}api/films")[1][0]["id"]
        status, answer = http_json("POST", f"{url}api/films/{film_id}/export", {"kind": "haptic"})
        check(status == 200 and os.path.exists(answer.get("path", "")), f"export before editing: {answer}")
        track_path = answer["path"]
        before = read_track(track_path)
        driver = open_browser(driver_path, profile)
        loaded = time.time()
        driver.get(url)
        wait_for(driver, "return window.hapcineStudio && hapcineStudio.state.film && hapcineStudio.state.curvesLoadMs",
                 "the page to load the film")
        print(f"page loaded in {time.time() - loaded:.2f} s (curves {driver.execute_script('return hapcineStudio.state.curvesLoadMs'):.0f} ms)")
        step_render_check(driver, args.screenshots)
        step_play(driver)
        step_seek(driver)
        moved = step_drag_keyframe(driver)
        step_gain_zero(driver)
        step_save(driver)
        saved = json.load(open(f"{stem}.edits.json"))
        kf = saved.get("keyframes", [{}])[0]
        check(abs(kf.get("start_s", -1) - moved["start_s"]) < 1e-5 and abs(kf.get("end_s", -1) - moved["end_s"]) < 1e-5,
              f"the edits file holds the moved effect {kf}")
        check(any(s.get("shot") == 1 and s.get("gain") == 0 for s in saved.get("shots", [])),
              f"the edits file holds shot 1's gain 0: {saved.get('shots')}")
        step_export(driver, track_path, os.path.getmtime(track_path))
        compare_tracks(before, read_track(track_path))
        step_docs_screenshots(driver, args.screenshots)
        step_conflict(driver, url)
        step_panel_controls(driver)
        errors = browser_log_errors(driver)
        check(not errors, f"no errors in the browser console {errors}")
    finally:
        if driver:
            driver.quit()
        proc.terminate()
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
        shutil.rmtree(profile, ignore_errors=True)
    print(f"PASS in {time.time() - started:.1f} s")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("hapcine")
    parser.add_argument("work_dir")
    parser.add_argument("--screenshots", help="folder for the screenshots (docs/images takes them from here)")
    args = parser.parse_args()
    browser = find_browser()
    try:
        import selenium  # noqa: F401
    except ImportError:
        browser = None
    if not browser:
        print("SKIP: chromium, chromedriver or python3-selenium is not installed")
        return SKIP
    if args.screenshots:
        os.makedirs(args.screenshots, exist_ok=True)
    run(args, browser[1])
    return 0


if __name__ == "__main__":
    sys.exit(main())
