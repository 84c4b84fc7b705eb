#!/usr/bin/python3
"""The studio page in a real browser (Debian's chromium through
chromium-driver and python3-selenium): the prim tree loads; selecting a prim
shows its behaviors' variables as typed fields with their docs; changing
one re-renders the preview (its pixels change) and the frame record shows
the new value; behaviors are attached, swapped and detached from the list;
Save writes it into the YAML with the comments kept; an edit
made in an editor shows up in the page. Exits 77 (skipped) when chromium
or its driver cannot start here.

usage: check_studio_browser.py SDGBEHAVE SOURCE_DIR"""
import os
import shutil
import subprocess
import sys
import tempfile
import time

from checklib import check, finish
from studio_server import Studio

SKIP = 77


def browser():
    try:
        from selenium import webdriver
        from selenium.webdriver.chrome.service import Service
    except ImportError as e:
        print(f"skipped: python3-selenium is missing ({e})")
        sys.exit(SKIP)
    options = webdriver.ChromeOptions()
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--window-size=1400,1000"):
        options.add_argument(flag)
    options.binary_location = shutil.which("chromium") or "/usr/bin/chromium"
    driver_path = shutil.which("chromedriver") or "/usr/bin/chromedriver"
    try:
        return webdriver.Chrome(service=Service(driver_path), options=options)
    except Exception as e:  # no browser, no driver, no display support: a machine limit, not a failure
        print(f"skipped: chromium could not start here ({type(e).__name__}: {str(e).splitlines()[0] if str(e) else ''})")
        sys.exit(SKIP)


def wait_for(condition, what, timeout=30):
    end = time.time() + timeout
    while time.time() < end:
        try:
            value = condition()
            if value:
                return value
        except Exception:
            pass
        time.sleep(0.1)
    raise AssertionError(f"timed out waiting for {what}")


def main():
    binary, root = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    from selenium.webdriver.common.by import By
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "scene.yaml")
        shutil.copy(os.path.join(root, "scenes/examples/location_randomizer.yaml"), scene)
        comments = [l for l in open(scene).read().splitlines() if l.startswith("#")]
        studio = Studio(binary, scene)
        driver = browser()
        try:
            driver.get(studio.url)
            box = wait_for(lambda: next(d for d in driver.find_elements(By.CSS_SELECTOR, "#tree div")
                                        if d.get_attribute("data-path") == "/World/Box"), "the prim tree")
            preview = driver.find_element(By.ID, "preview")
            wait_for(lambda: driver.execute_script("return arguments[0].complete && arguments[0].naturalWidth > 0", preview),
                     "the first preview")
            # Frame 1: the box (interval 2) has moved by then.
            driver.execute_script("goTo(1)")
            wait_for(lambda: "/World/Box" in driver.find_element(By.ID, "record").text, "frame 1's record")
            wait_for(lambda: driver.execute_script("return arguments[0].complete && arguments[0].naturalWidth > 0", preview),
                     "frame 1's preview")
            before = preview.screenshot_as_png
            box.click()
            key = "behaviors:locationRandomizer:range:maxPosition"
            fields = wait_for(lambda: driver.find_elements(By.CSS_SELECTOR, f"input[data-attribute='{key}']"),
                              "the maxPosition fields")
            check(len(fields) == 3, f"vector3d shown as {len(fields)} fields")
            check("Upper bound" in (fields[0].get_attribute("title") or ""), "the variable's doc is not a tooltip")
            interval = driver.find_element(By.CSS_SELECTOR, "input[data-attribute='behaviors:locationRandomizer:interval']")
            check(interval.get_attribute("type") == "number" and interval.get_attribute("min") == "0", "interval field")
            version = driver.execute_script("return state.version")
            # What typing a value and leaving the field does (clear() would fire
            # a change of its own and re-render the panel under our feet).
            driver.execute_script("arguments[0].value = '4'; arguments[0].dispatchEvent(new Event('change'))", fields[0])
            wait_for(lambda: driver.execute_script("return state.version") > version and driver.execute_script(
                "return arguments[0].complete && arguments[0].naturalWidth > 0", preview), "a new preview")
            wait_for(lambda: "/World/Box" in driver.find_element(By.ID, "record").text, "the record after the edit")
            time.sleep(0.3)
            after = preview.screenshot_as_png
            check(after != before, "the preview's pixels did not change after the edit")
            # Attach a behavior from the registry's list, then swap it for another.
            from selenium.webdriver.support.ui import Select
            Select(driver.find_element(By.ID, "attachChoice")).select_by_value("rotationRandomizer")
            driver.find_element(By.ID, "attachButton").click()
            wait_for(lambda: driver.find_elements(By.CSS_SELECTOR, "button[data-detach='rotationRandomizer']"),
                     "the attached behavior's section")
            Select(driver.find_element(By.ID, "attachChoice")).select_by_value("lightRandomizer")
            Select(driver.find_element(By.ID, "swapFrom")).select_by_value("rotationRandomizer")
            driver.find_element(By.ID, "attachButton").click()
            wait_for(lambda: driver.find_elements(By.CSS_SELECTOR, "button[data-detach='lightRandomizer']") and not
                     driver.find_elements(By.CSS_SELECTOR, "button[data-detach='rotationRandomizer']"), "the swap")
            driver.find_element(By.CSS_SELECTOR, "button[data-detach='lightRandomizer']").click()
            wait_for(lambda: not driver.find_elements(By.CSS_SELECTOR, "button[data-detach='lightRandomizer']"),
                     "the detach")
            # Save, accepting the diff the page shows first.
            driver.find_element(By.ID, "saveButton").click()
            alert = wait_for(lambda: driver.switch_to.alert, "the diff before saving")
            check("range:maxPosition: [4, 1, 0]" in alert.text, f"the diff shown: {alert.text}")
            alert.accept()
            wait_for(lambda: "range:maxPosition: [4, 1, 0]" in open(scene).read(), "the file on disk")
            saved = open(scene).read().splitlines()
            check(all(c in saved for c in comments), "comments lost on save")
            check(subprocess.run([binary, "validate", scene], capture_output=True).returncode == 0, "saved file invalid")
            # An edit in an editor shows up.
            time.sleep(0.05)
            text = open(scene).read()
            open(scene, "w").write(text.replace("radius: 0.2", "radius: 0.35"))
            wait_for(lambda: "changed on disk" in driver.find_element(By.ID, "message").text, "the reload note")

            def select_ball():
                ball = next(d for d in driver.find_elements(By.CSS_SELECTOR, "#tree div")
                            if d.get_attribute("data-path") == "/World/Ball")
                ball.click()
                return True
            wait_for(select_ball, "the ball in the reloaded tree")
            wait_for(lambda: driver.find_element(By.CSS_SELECTOR, "input[data-attribute='radius']").get_property("value")
                     == "0.35", "the new radius in the panel")
        finally:
            driver.quit()
            studio.stop()
    return finish("tree, typed fields with docs, live preview and record, save with comments, disk edits")


if __name__ == "__main__":
    sys.exit(main())
