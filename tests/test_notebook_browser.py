"""The notebook widget in a real browser: JupyterLab serving a notebook with `vsgl.view`, opened
in headless Chromium driven by Selenium. Running the cell shows the widget's frame; a drag on
it orbits the camera and a new frame replaces the old; moving the pointer without a button
pressed (a no-op) leaves the frame alone.

Needs Debian's `chromium` and `chromium-driver` (scripts/setup.sh installs them) and the test
extra's `selenium` and `jupyterlab`; without them it skips, except under CI (CI=true), where a
missing one is a failure."""

from __future__ import annotations

import os
import pathlib
import shutil
import socket
import subprocess
import sys
import time

import pytest

from optional_packages import optional_import

REPO = pathlib.Path(__file__).resolve().parents[1]
_CELL = """import vsgl
scene = vsgl.scenes.load("cornell_box")
view = vsgl.view(scene, "direct", size=(160, 90))
view"""


def _tool(name: str) -> str:
    path = shutil.which(name)
    if path is None:
        if os.environ.get("CI"):
            pytest.fail(f"CI must have {name} (scripts/setup.sh installs Debian's chromium and chromium-driver)")
        pytest.skip(f"{name} is not installed (apt-get install chromium chromium-driver)")
    return path


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _wait(what: str, check, timeout: float, every: float = 0.2):
    deadline = time.time() + timeout
    while time.time() < deadline:
        value = check()
        if value:
            return value
        time.sleep(every)
    pytest.fail(f"timed out after {timeout:.0f} s waiting for {what}")


@pytest.mark.gpu
@pytest.mark.slow
def test_a_drag_in_the_browser_changes_the_frame_and_a_hover_does_not(tmp_path):
    chromium, driver_path = _tool("chromium"), _tool("chromedriver")
    webdriver = optional_import("selenium.webdriver", "pip install selenium (the test extra)")
    optional_import("jupyterlab", "pip install jupyterlab (the test extra)")
    nbformat = optional_import("nbformat", "pip install nbformat (the test extra)")
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys

    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell(_CELL)]
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    nbformat.write(nb, tmp_path / "live.ipynb")
    port, token = _free_port(), "vsgl-browser-test"
    log = open(tmp_path / "lab.log", "w")
    lab = subprocess.Popen(
        [sys.executable, "-m", "jupyter", "lab", "--no-browser", f"--port={port}", f"--IdentityProvider.token={token}",
         f"--ServerApp.root_dir={tmp_path}", "--allow-root", "--LabApp.news_url=", "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate"],
        stdout=log, stderr=subprocess.STDOUT, cwd=REPO)
    browser = None
    try:
        def listening():
            try:
                socket.create_connection(("127.0.0.1", port), 0.2).close()
                return True
            except OSError:
                return lab.poll() is not None and pytest.fail(f"JupyterLab exited: {(tmp_path / 'lab.log').read_text()[-2000:]}")
        _wait("JupyterLab to listen", listening, 60)
        options = webdriver.ChromeOptions()
        options.binary_location = chromium
        for arg in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--window-size=1200,900"):
            options.add_argument(arg)
        browser = webdriver.Chrome(options=options, service=webdriver.ChromeService(executable_path=driver_path))
        browser.get(f"http://127.0.0.1:{port}/lab/tree/live.ipynb?token={token}")
        _wait("the notebook's cell", lambda: browser.find_elements(By.CSS_SELECTOR, ".jp-Notebook .jp-Cell .cm-content"), 120)
        _wait("the kernel", lambda: "Idle" in browser.find_element(By.TAG_NAME, "body").text, 120)
        browser.find_elements(By.CSS_SELECTOR, ".jp-Notebook .jp-Cell .cm-content")[0].click()
        ActionChains(browser).key_down(Keys.SHIFT).send_keys(Keys.ENTER).key_up(Keys.SHIFT).perform()

        def frame():
            images = browser.find_elements(By.CSS_SELECTOR, ".jp-OutputArea img")
            src = images[0].get_attribute("src") if images else ""
            return (images[0], src) if src and src.startswith(("data:", "blob:")) else None

        image, first_src = _wait("the widget's first frame", frame, 180)
        first = image.screenshot_as_png
        time.sleep(2.0)  # the view stops: the still frame (lossless) follows the first
        image, src = frame()
        still = image.screenshot_as_png
        # A hover (no button held) is a no-op: no new frame comes.
        ActionChains(browser).move_to_element_with_offset(image, 5, 5).move_by_offset(10, 0).perform()
        time.sleep(2.0)
        assert frame()[1] == src, "a pointer move without a button sent a new frame"
        # A short left drag orbits the camera: a new frame, with other pixels.
        ActionChains(browser).move_to_element(image).click_and_hold().move_by_offset(6, 0).move_by_offset(6, 0).release().perform()
        _wait("a frame after the drag", lambda: frame()[1] != src, 60)
        time.sleep(2.0)
        dragged = frame()[0].screenshot_as_png
        assert dragged != still and dragged != first
    finally:
        if browser is not None:
            browser.quit()
        lab.terminate()
        try:
            lab.wait(timeout=20)
        except subprocess.TimeoutExpired:
            lab.kill()
        log.close()
