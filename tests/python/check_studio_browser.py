#!/usr/bin/python3
"""The studio page in a real browser (Debian's chromium through
chromium-driver and python3-selenium): the prim tree loads; selecting a prim
shows its behaviors' variables as typed fields with their docs; changing
one re-renders the preview (its pixels change) and the frame record shows
the new value; behaviors are attached, swapped and detached from the list;
Save writes it into the YAML with the comments kept; an edit
made in an editor shows up in the page. In a 1280 px window the property
panel shows every label whole, without a horizontal scrollbar; an edit
`validate` would refuse (a PNG or /etc/passwd as a mesh) shows its message
next to the field while the preview keeps working; a conflict shows its
diff and offers reload or overwrite, and Save does not pretend otherwise.
Exits 77 (skipped) when chromium or its driver cannot start here.

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
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--window-size=1280,1000"):
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


MESH_SCENE = """# A mesh with a rotation, a box, a camera.
version: 1
capture: {frames: 4, seed: 3}
prims:
  /World: {}
  /World/Crate:
    type: Mesh
    asset: props/crate.glb
    translate: [0, 0, 0.5]
    behaviors:
      rotationRandomizer: {range:minRotation: [0, 0, -30], range:maxRotation: [0, 0, 30]}
  /World/Box: {type: Cube, size: 0.5, translate: [1.5, 0, 0.25]}
  /World/Sun: {type: DistantLight, inputs:intensity: 3000, rotateXYZ: [30, 10, 0]}
  /World/Cam: {type: Camera, translate: [0, -6, 4], rotateXYZ: [55, 0, 0]}
"""


def no_alert(driver, seconds=1.0):
    from selenium.common.exceptions import NoAlertPresentException
    end = time.time() + seconds
    while time.time() < end:
        try:
            driver.switch_to.alert
            return False
        except NoAlertPresentException:
            time.sleep(0.1)
    return True


def mesh_edits_layout_and_conflicts(driver, binary, root, tmp):
    """Refused edits beside their field, labels at 1280 px, the conflict flow."""
    from selenium.webdriver.common.by import By
    folder = os.path.join(tmp, "mesh")
    os.makedirs(os.path.join(folder, "props"))
    os.makedirs(os.path.join(folder, "textures"))
    shutil.copy(os.path.join(root, "scenes/props/crate.glb"), os.path.join(folder, "props"))
    shutil.copy(os.path.join(root, "scenes/textures/wood.png"), os.path.join(folder, "textures"))
    scene = os.path.join(folder, "mesh.yaml")
    open(scene, "w").write(MESH_SCENE)
    studio = Studio(binary, scene)
    try:
        driver.get(studio.url)
        preview = driver.find_element(By.ID, "preview")
        loaded = lambda: driver.execute_script("return arguments[0].complete && arguments[0].naturalWidth > 0", preview)

        def select(path):
            row = next(d for d in driver.find_elements(By.CSS_SELECTOR, "#tree div") if d.get_attribute("data-path") == path)
            row.click()
            return True
        wait_for(lambda: select("/World/Crate"), "the crate in the tree")
        asset = wait_for(lambda: driver.find_element(By.CSS_SELECTOR, "input[data-attribute='asset']"), "the asset field")
        wait_for(loaded, "the first preview")

        # The panel fits its labels in a 1280 px window: none cut, no sideways scrolling.
        check(driver.execute_script("return window.innerWidth") <= 1280, "the window is wider than 1280 px")
        labels = driver.execute_script(
            "return [...document.querySelectorAll('#panel label')].map(l => [l.textContent, l.scrollWidth, l.clientWidth])")
        check(any(name == "range:maxRotation" for name, _, _ in labels), f"labels: {labels}")
        cut = [name for name, scroll, client in labels if scroll > client + 1]
        check(not cut, f"labels cut at 1280 px: {cut}")
        panel = driver.execute_script("const p = document.getElementById('panel'); return [p.scrollWidth, p.clientWidth]")
        check(panel[0] <= panel[1], f"the panel scrolls sideways at 1280 px: {panel}")

        # Edits validate refuses: the message beside the field, the old value back, the preview still drawn.
        for value, message in (("textures/wood.png", "is not a mesh format sdgbehave reads"),
                               ("/etc/passwd", "is not a mesh format sdgbehave reads"),
                               ("../../../../etc/passwd", "is not a mesh format sdgbehave reads")):
            asset = driver.find_element(By.CSS_SELECTOR, "input[data-attribute='asset']")
            driver.execute_script("arguments[0].value = arguments[1]; arguments[0].dispatchEvent(new Event('change'))",
                                  asset, value)
            shown = wait_for(lambda: driver.execute_script(
                "const e = document.querySelector(\"[data-field-error='asset']\");"
                "const field = document.querySelector(\"input[data-attribute='asset']\");"
                "return e && e.textContent.includes(arguments[0]) && "
                "[e.textContent, e.closest('.row').contains(field), field.value];", value),
                f"the message beside the field for {value}")
            text, same_row, field_value = shown
            check(message in text, f"{value}: {text}")
            check(same_row, "the message is not in the field's row")
            check(field_value == "props/crate.glb", f"the field did not get its old value back: {field_value}")
        driver.execute_script("goTo(1)")
        wait_for(loaded, "a preview after the refused edits")
        check(driver.find_element(By.ID, "message").text == "", f"message: {driver.find_element(By.ID, 'message').text}")
        check(open(scene).read() == MESH_SCENE, "a refused edit reached the file")

        # A conflict: an edit here, another on disk.
        select("/World/Box")
        size = wait_for(lambda: driver.find_element(By.CSS_SELECTOR, "input[data-attribute='size']"), "the size field")
        driver.execute_script("arguments[0].value = '0.75'; arguments[0].dispatchEvent(new Event('change'))", size)
        wait_for(lambda: "unsaved" in driver.find_element(By.ID, "status").text, "the unsaved edit")
        time.sleep(0.05)
        open(scene, "w").write(MESH_SCENE + "# changed in an editor\n")
        conflict = driver.find_element(By.ID, "conflict")
        wait_for(lambda: conflict.is_displayed(), "the conflict box")
        diff = wait_for(lambda: driver.find_element(By.ID, "conflictDiff").text, "the conflict's diff")
        check("(on disk now)" in diff and "+# changed in an editor" in diff and "size: 0.75" in diff, f"diff: {diff}")
        # Save does not ask to confirm something that cannot work.
        driver.find_element(By.ID, "saveButton").click()
        check(no_alert(driver), "Save asked for confirmation during a conflict")
        wait_for(lambda: "refused during a conflict" in driver.find_element(By.ID, "message").text, "Save's message")
        # An edit meanwhile says what is possible, beside its field.
        size = driver.find_element(By.CSS_SELECTOR, "input[data-attribute='size']")
        driver.execute_script("arguments[0].value = '0.8'; arguments[0].dispatchEvent(new Event('change'))", size)
        text = wait_for(lambda: driver.execute_script(
            "const e = document.querySelector(\"[data-field-error='size']\"); return e && e.textContent"),
            "the refused edit")
        check("reload" in text and "overwrite" in text and "save or reload" not in text, f"refused edit: {text}")
        # Overwrite, after confirming with the diff.
        driver.find_element(By.ID, "conflictOverwrite").click()
        alert = wait_for(lambda: driver.switch_to.alert, "the overwrite confirmation")
        check("size: 0.75" in alert.text, f"confirmation: {alert.text}")
        alert.accept()
        wait_for(lambda: not conflict.is_displayed(), "the conflict to end")
        text = open(scene).read()
        check("size: 0.75" in text and "changed in an editor" not in text, f"overwritten file:\n{text}")
        # Another conflict, left by reloading: the disk wins.
        size = driver.find_element(By.CSS_SELECTOR, "input[data-attribute='size']")
        driver.execute_script("arguments[0].value = '0.6'; arguments[0].dispatchEvent(new Event('change'))", size)
        wait_for(lambda: "unsaved" in driver.find_element(By.ID, "status").text, "the second unsaved edit")
        time.sleep(0.05)
        open(scene, "w").write(text + "# changed again\n")
        wait_for(lambda: conflict.is_displayed(), "the second conflict")
        driver.find_element(By.ID, "conflictReload").click()
        wait_for(lambda: driver.switch_to.alert, "the reload confirmation").accept()
        wait_for(lambda: not conflict.is_displayed() and "unsaved" not in driver.find_element(By.ID, "status").text,
                 "the reload")
        check(open(scene).read().endswith("# changed again\n"), "reloading wrote the file")
    finally:
        studio.stop()


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
            studio.stop()
            mesh_edits_layout_and_conflicts(driver, binary, root, tmp)
        finally:
            driver.quit()
            studio.stop()
    return finish("tree, typed fields with docs, live preview and record, save with comments, disk edits; labels at "
                  "1280 px; refused edits beside their field; the conflict's diff, reload and overwrite")


if __name__ == "__main__":
    sys.exit(main())
