"""The four kinds of HTML report opened as a person would: in headless Chromium (Debian's chromium and
chromium-driver, driven by python3-selenium).

Each report is made by the real command line (REPOSE_CLI), opened from a file:// address with the network
unused, and must: load with no console error; draw its 3-D view (the particle's colour on a sizeable part of
the canvas, the view not a blank background); and change its picture when the slider is moved with the
keyboard. Screenshots are kept in REPOSE_REPORT_DIR for a person to look at.

Run by ctest as output.ReportsInHeadlessChromium (tests/CMakeLists.txt).
"""
import json
import os
import subprocess
import time

import pytest
from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys

CLI = os.environ["REPOSE_CLI"]
OUT = os.environ.get("REPOSE_REPORT_DIR", "/tmp/repose-reports")

# Pixel statistics of the first 3-D view, computed in the page: the share of pixels that differ from the
# background colour (#f4f6f8) and the share in the particle's orange (#d9a441, shaded: red well above blue).
CANVAS_STATS = """
const view = document.querySelector('canvas.view');
const c = document.createElement('canvas');
c.width = view.width; c.height = view.height;
const ctx = c.getContext('2d');
ctx.drawImage(view, 0, 0);
const px = ctx.getImageData(0, 0, c.width, c.height).data;
let drawn = 0, particle = 0;
for (let i = 0; i < px.length; i += 4) {
  const [r, g, b] = [px[i], px[i + 1], px[i + 2]];
  if (Math.abs(r - 0xf4) + Math.abs(g - 0xf6) + Math.abs(b - 0xf8) > 12) drawn++;
  if (r > b + 50 && g > b + 10) particle++;
}
return {drawn: drawn / (px.length / 4), particle: particle / (px.length / 4), pixels: c.toDataURL()};
"""


def make(name, *args):
    os.makedirs(OUT, exist_ok=True)
    subprocess.run([CLI, *args], check=True, cwd=OUT, stdout=subprocess.DEVNULL, timeout=600)
    return os.path.join(OUT, name)


@pytest.fixture(scope="module")
def browser():
    options = webdriver.ChromeOptions()
    for flag in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--window-size=1200,1400",
                 # WebGL without a GPU: Chromium's software renderer, which it no longer picks by itself.
                 "--use-angle=swiftshader", "--enable-unsafe-swiftshader"):
        options.add_argument(flag)
    options.binary_location = "/usr/bin/chromium"
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
    yield driver
    driver.quit()


def open_report(browser, path):
    """Loads the page and waits (an event, bounded) until it says it is drawn or shows a problem."""
    browser.get_log("browser")  # forget the previous page's messages
    browser.get("file://" + path)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        state = browser.execute_script(
            "return document.querySelector('.problem') ? 'problem' : document.body.dataset.ready || ''")
        if state:
            break
        time.sleep(0.05)
    errors = [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
    assert state == "true", f"{path}: the page did not finish drawing ({state!r}); console: {errors}"
    assert errors == [], f"{path}: console errors: {errors}"


def assert_drawn(browser, path, shot):
    stats = browser.execute_script(CANVAS_STATS)
    browser.save_screenshot(os.path.join(OUT, shot))
    # Measured: 69-79 % of the pixels drawn (the wall fills most of the view), 6-18 % the particle; a blank
    # view has 0 and 0. The bounds are a quarter of the smallest measured shares.
    assert stats["drawn"] > 0.17, f"{path}: the 3-D view is blank ({stats['drawn']:.3f} of pixels drawn)"
    assert stats["particle"] > 0.015, f"{path}: no particle in the 3-D view ({stats['particle']:.4f})"
    return stats["pixels"]


def move_slider(browser, css, key):
    slider = browser.find_element(By.CSS_SELECTOR, css)
    slider.send_keys(key)


def test_settle_report_plays_the_run(browser):
    path = make("settle.html", "settle", "tetrahedron:edge=1", "--orientation", "axis-angle:1,0.3,0,0.7",
                "--html", "settle.html")
    open_report(browser, path)
    before = assert_drawn(browser, path, "settle-start.png")
    assert browser.find_element(By.CSS_SELECTOR, ".badge").text.startswith("point")
    assert len(browser.find_elements(By.CSS_SELECTOR, ".uplot")) == 3
    move_slider(browser, "input.time-slider", Keys.END)
    after = assert_drawn(browser, path, "settle-end.png")
    assert after != before, "moving the time slider did not change the picture"
    # At the end the tetrahedron rests on a face.
    assert browser.find_element(By.CSS_SELECTOR, ".badge").text.startswith("surface")
    assert browser.execute_script("return document.querySelector('.clock').textContent") != "t = 0"
    # Units in the plots' legends and titles and in the summary (si: the default; axis labels are drawn on
    # the canvas, out of the text's reach).
    text = browser.execute_script("return document.body.innerText")
    for label in ("t (s)", "|ω| (rad/s)", "energies (J;", "phases (s)", "L = 0.6083 m"):
        assert label in text, f"{path}: no '{label}' in the page"
    assert [e for e in browser.get_log("browser") if e["level"] == "SEVERE"] == []


def test_settle_report_shows_the_frictional_modes(browser):
    # A cube thrown sideways onto its face with mu 0.3 slides to a stop (issue 34): the player's badge counts
    # the sliding points, a fourth plot shows the points by mode, the summary the friction's work.
    path = make("settle-friction.html", "settle", "box:x=1,y=1,z=1", "--velocity", "1.5,0,0", "--friction", "0.3",
                "--html", "settle-friction.html")
    open_report(browser, path)
    assert_drawn(browser, path, "settle-friction.png")
    move_slider(browser, "input.time-slider", Keys.RIGHT)  # the first frame is before the first step
    assert browser.find_element(By.CSS_SELECTOR, ".badge").text.endswith("0 sticking, 4 sliding")
    assert len(browser.find_elements(By.CSS_SELECTOR, ".uplot")) == 4
    text = browser.execute_script("return document.body.innerText")
    for label in ("points on the wall by mode", "friction after the landing", "Painlevé"):
        assert label in text, f"{path}: no '{label}' in the page"
    assert [e for e in browser.get_log("browser") if e["level"] == "SEVERE"] == []


def test_poses_report_shows_every_pose(browser):
    path = make("poses.html", "poses", "box:x=1,y=2,z=3", "-n", "300", "--html", "poses.html")
    open_report(browser, path)
    before = assert_drawn(browser, path, "poses-first.png")
    rows = browser.find_elements(By.CSS_SELECTOR, "table.poses tbody tr")
    assert len(rows) == 6  # a box has six faces, all stable
    thumbs = browser.find_elements(By.CSS_SELECTOR, "img.thumb")
    assert len(thumbs) == 6 and all(browser.execute_script("return arguments[0].naturalWidth", t) > 0
                                    for t in thumbs)
    assert len(browser.find_elements(By.CSS_SELECTOR, "svg.bars rect.measured")) == 6
    # One pose numbering: each row's number and hull faces are those of the same pose in the JSON (issue 33;
    # the report once numbered 1-6 by frequency while the JSON and the table used the catalogue's numbers).
    result = json.loads(subprocess.run([CLI, "poses", "box:x=1,y=2,z=3", "-n", "300", "--json"], check=True,
                                       capture_output=True, text=True, timeout=600).stdout)
    shown = [(int(r.find_elements(By.TAG_NAME, "td")[0].text), r.find_elements(By.TAG_NAME, "td")[2].text)
             for r in rows]
    assert shown == [(p["pose"], ", ".join(map(str, p["faces"]))) for p in result["poses"]]
    bar_labels = browser.execute_script(
        "return [...document.querySelectorAll('svg.bars text')].map((t) => t.textContent)")
    assert [str(p["pose"]) for p in result["poses"]] == [t for t in bar_labels if t.isdigit()]
    assert "COM height (m)" in browser.execute_script("return document.body.innerText")
    move_slider(browser, "input.pose-slider", Keys.END)
    after = assert_drawn(browser, path, "poses-last.png")
    assert after != before, "moving the pose slider did not change the picture"
    assert [e for e in browser.get_log("browser") if e["level"] == "SEVERE"] == []


CUBE_TARGET = ("[[[0,0,-1],0.4],[[0,0,1],0.12],[[1,0,0],0.12],[[-1,0,0],0.12],[[0,1,0],0.12],"
               "[[0,-1,0],0.12]]")


def test_design_report_shows_target_achieved_poses_and_history(browser):
    os.makedirs(OUT, exist_ok=True)
    with open(os.path.join(OUT, "cube-target.json"), "w") as f:
        f.write(CUBE_TARGET)
    path = make("design.html", "design", "box:x=1,y=1,z=1", "--target", "cube-target.json", "--html",
                "design.html")
    open_report(browser, path)
    before = assert_drawn(browser, path, "design-first.png")
    text = browser.execute_script("return document.body.innerText")
    assert "reached" in text and "Target and achieved" in text
    # Six outcomes and the "other" row, three bars each (target, start, design).
    assert len(browser.find_elements(By.CSS_SELECTOR, "svg.bars rect")) == 3 * 7
    rows = browser.find_elements(By.CSS_SELECTOR, "table.poses tbody tr")
    # The design rests on faces of every outcome (a folded side can rest on either of its two triangles).
    assert {r.find_elements(By.TAG_NAME, "td")[0].text for r in rows} == {f"outcome {k}" for k in range(1, 7)}
    assert len(browser.find_elements(By.CSS_SELECTOR, ".uplot")) == 1  # the history
    move_slider(browser, "input.pose-slider", Keys.END)
    after = assert_drawn(browser, path, "design-last.png")
    assert after != before, "moving the pose slider did not change the picture"
    # A tossed design: both designs' checks with intervals, and the tossed history too.
    path = make("design-tossed.html", "design", "box:x=1,y=1,z=1", "--target", "cube-target.json", "--model",
                "tossed", "--drop-height", "4", "--velocity-max", "3", "--spin-max", "3", "--restitution", "0.1",
                "--friction", "0.3", "--drops", "60", "--check-drops", "60", "--toss-iterations", "1",
                "--html", "design-tossed.html")
    open_report(browser, path)
    assert_drawn(browser, path, "design-tossed.png")
    text = browser.execute_script("return document.body.innerText")
    for label in ("never saw", "95 % interval", "The toss", "tossed design"):
        assert label in text, f"{path}: no '{label}' in the page"
    assert len(browser.find_elements(By.CSS_SELECTOR, ".uplot")) == 2
    assert [e for e in browser.get_log("browser") if e["level"] == "SEVERE"] == []


def test_paper_report_has_its_table_figures_and_runs(browser):
    path = make(os.path.join("paper", "report.html"), "paper", "--out", "paper", "--frames", "5")
    open_report(browser, path)
    before = assert_drawn(browser, path, "paper-start.png")
    assert len(browser.find_elements(By.CSS_SELECTOR, "table.comparison tbody tr")) >= 20
    figures = browser.find_elements(By.CSS_SELECTOR, ".figures img")
    assert len(figures) >= 10 and all(browser.execute_script("return arguments[0].naturalWidth", f) > 0
                                      for f in figures)
    move_slider(browser, "input.time-slider", Keys.END)
    after = assert_drawn(browser, path, "paper-end.png")
    assert after != before, "moving the time slider did not change the picture"
    # Another case's player replaces the first.
    browser.find_elements(By.CSS_SELECTOR, ".tabs button")[4].click()
    assert browser.find_element(By.CSS_SELECTOR, "section.case h3").text == "tetrahedron"
    assert_drawn(browser, path, "paper-tetrahedron.png")
    assert [e for e in browser.get_log("browser") if e["level"] == "SEVERE"] == []
