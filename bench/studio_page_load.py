#!/usr/bin/python3
"""How fast the studio page shows a film, in headless Chromium (docs/studio.md, "Long films").

    bench/studio_page_load.py URL [--runs N]

URL: a running `hapcine studio` (e.g. http://127.0.0.1:8795/). Prints, per run, the time from
the navigation to the whole film's curves drawn (hapcineStudio.state.readyMs) and the part spent
asking for and parsing the film, its edits and the overview curves; then one timeline redraw at
the whole film, 10 min and 10 s (the view's own curves loaded).
"""
import argparse
import os
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
import studio_browser_test as T  # noqa: E402

REDRAW = ("const tl = hapcineStudio.timeline; const t0 = performance.now();"
          "for (let i = 0; i < 20; i++) tl.draw({editsModel: hapcineStudio.state.edits, selectedShot: 0});"
          "return (performance.now() - t0) / 20")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("url")
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    browser = T.find_browser()
    if not browser:
        sys.exit("chromium and chromedriver are needed")
    driver = T.open_browser(browser[1], tempfile.mkdtemp(prefix="hapcine-chromium-"))
    try:
        for run in range(args.runs):
            driver.get("about:blank")
            driver.get(args.url)
            T.wait_for(driver, "return window.hapcineStudio && hapcineStudio.state.readyMs", "the page", 60)
            ready, fetched = driver.execute_script(
                "return [hapcineStudio.state.readyMs, hapcineStudio.state.curvesLoadMs]")
            print(f"run {run}: curves drawn {ready:.0f} ms after the navigation started "
                  f"(film, edits, overview curves: {fetched:.0f} ms)")
        duration = driver.execute_script("return hapcineStudio.state.film.duration_s")
        for span in (duration, 600, 10):
            start = max(0.0, duration / 2 - span / 2) if span < duration else 0.0
            driver.execute_script("hapcineStudio.setView(arguments[0], arguments[1])", start, start + span)
            if span < duration:
                T.wait_for(driver, "return hapcineStudio.timeline.visibleCurves() === hapcineStudio.timeline.detail",
                           "the view's curves", 30)
            time.sleep(0.2)
            print(f"redraw, {span:g} s in view: {driver.execute_script(REDRAW):.1f} ms")
    finally:
        driver.quit()


if __name__ == "__main__":
    main()
