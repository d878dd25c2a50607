"""Every lesson and a sample of the exercise notebooks, run in JupyterLab in headless Chromium.

The sample (`tests.test_notebooks.IN_CHROMIUM`) has one exercise of each stage;
the other exercise notebooks are the same template and run with a kernel only
(tests/test_notebooks.py).

The window is 1280 × 800 with the file browser open. For each notebook the
test runs all cells from the Run menu and then checks, each as its own
subtest (pytest's ``subtests``), what a student would notice:

- ``runs``: every code cell ran and none shows a traceback;
- ``fits``: no output, and nothing inside one (canvas, image, table, widget
  box), reaches past the visible width of the notebook; text and tables may
  instead scroll inside a box of their own that fits (an element whose style
  attribute says ``overflow-x: auto``), figures may not;
- ``no ipympl chrome``: no "Figure N" header and no toolbar over a figure;
- ``no raw repr``: no output text shows a dataclass repr such as ``Span(y=3, ...``;
- ``never silent``: no cell runs longer than `SILENT_S` seconds without
  showing anything (measured in the page: from the cell's start to its
  first output, between outputs, and from the last output to its end);
- ``steppers narrate``: every stepper's Next moves it on, and the sentence
  under its "step k / n: kind" label changes and says more than the kind;
- lesson-specific checks: the views of the steppers of lessons 02, 07, 08,
  09 and 10 change as they step, and in lesson 02 a vertex of the
  `PolygonEditor` dragged with the mouse changes the fill and the edge table.

A last test answers exercise 05 and checks its report and comparison.

Screenshots go to ``tests/browser/screenshots/`` (or ``$SCANVIZ_SCREENSHOTS``;
their paths are printed, ``pytest -rP`` shows them). Each pytest-xdist worker
starts one JupyterLab over a temporary copy of ``notebooks/`` and one
chromium, and the notebooks are shared out between the workers.

The browser is Debian's chromium, driven by Playwright (no browser downloads).
The tests skip only when no chromium can be found; every other problem fails.
"""

import io
import itertools
import json
import os
import re
import shutil
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request
from pathlib import Path

import numpy as np
import pytest
from playwright.sync_api import Locator, Page, sync_playwright
from playwright.sync_api import TimeoutError as PlaywrightTimeout

from tests.test_notebooks import IN_CHROMIUM

ROOT = Path(__file__).resolve().parents[2]
NOTEBOOK_DIR = ROOT / "notebooks"
NOTEBOOKS = sorted(
    [p.relative_to(NOTEBOOK_DIR).as_posix() for p in NOTEBOOK_DIR.glob("[01]*.ipynb")]
    + [f"exercises/{name}" for name in IN_CHROMIUM]
)
SCREENSHOTS = Path(
    os.environ.get("SCANVIZ_SCREENSHOTS") or Path(__file__).resolve().parent / "screenshots"
)
CHROMIUM_FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
VIEWPORT = {"width": 1280, "height": 800}  # issue 23: a 1280 px window, the file browser open
SERVER_START_S = 90
RUN_ALL_S = 240
STEP_S = 10  # one click of Next: a round trip to the kernel and back
NARRATION_S = 3  # how long the narration may lag behind the step label
SILENT_S = 5.0  # the longest a cell may run with nothing new to show
SETTLED_S = 1.0  # the page has settled when nothing in the notebook changed for this long
TOLERANCE_PX = 1  # sub-pixel rounding of bounding boxes
KERNEL_IDLE = re.compile(r"^(?!No Kernel).* \| Idle$")  # the status bar, once a kernel is up
NEXT_LABEL = re.compile(r"^\s*next ▶\s*$")  # Stepper.next_button
STEP_LABEL = re.compile(r"^step (\d+) / (\d+): (\S+)$")  # Stepper.label
NARRATED_STEPS = 3  # Next clicks per stepper whose narration is checked
RAW_REPR = re.compile(r"\b[A-Z][A-Za-z]+\((\w+=)")  # e.g. "Span(y=3, ..." or "EdgeEntry(edge=0"
TRACEBACK = re.compile(r"Traceback \(most recent call last\)|^\w*(Error|Exception)\b.*:", re.M)

# What each lesson's stepper views show (the view's caption), to see them change as they step.
AET_CAPTION = re.compile(r"^\s*AET\b")  # ScanConversionView.aet_html: "AET of row y" / "AET: empty"
DEPTH_SORT_TITLE = "depth sort: one pair, swap or split per step"  # DepthSortView's heading
PAIR_CAPTION = re.compile(r"no pair under test|S = \S+, S' = \S+")  # DepthSortView.settled
PERIMETER_TITLE = "floating perimeter: one facet, edge or update per step"
PERIMETER_CAPTION = re.compile(r"^\s*(start:|viewing case \d|facet \d+)")  # PerimeterView.text
FILL_TITLE = "fill variants: one span at a time"
FILL_CAPTION = re.compile(r"^\s*(span \d+ of|no span yet)")  # FillView.text
FAST_PHONG_TITLE = "fast Phong: one sample per step"
FAST_PHONG_CAPTION = re.compile(r"^\s*(sample \d+ of|start: \d+ samples)")  # FastPhongView.text
DISLOP_TITLE = "DISLOP_L: one column per step"
DISLOP_CAPTION = re.compile(r"^\s*(column \d+ of|start: \d+ columns)")  # DislopView.text
SCAN_TITLE = "Scan conversion: edge table and active edge table"  # scan_conversion_stepper's
VIEW_CHANGES = {  # notebook: [(stepper title, caption of the view, Next clicks)]
    "02_scan_conversion.ipynb": [(SCAN_TITLE, AET_CAPTION, 6)],
    "07_visibility.ipynb": [(DEPTH_SORT_TITLE, PAIR_CAPTION, 6)],
    "08_grid_surfaces.ipynb": [(PERIMETER_TITLE, PERIMETER_CAPTION, 6)],
    "09_fast_shading.ipynb": [
        (FILL_TITLE, FILL_CAPTION, 30),  # the edge table's events come before any span
        (FAST_PHONG_TITLE, FAST_PHONG_CAPTION, 6),
    ],
    "10_antialiasing.ipynb": [(DISLOP_TITLE, DISLOP_CAPTION, 6)],
}
EDITOR_LESSON = "02_scan_conversion.ipynb"
EDITOR_POLYGON = [(4, 1), (1, 11), (9, 5), (12, 8), (12, 1)]  # lesson 02's PolygonEditor
EXERCISE = "exercises/05_span_rule.ipynb"


def _free_port():
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def _wait_until_answering(url, server, log_path):
    deadline = time.monotonic() + SERVER_START_S
    while time.monotonic() < deadline:
        if server.poll() is not None:
            pytest.fail(f"JupyterLab exited with {server.returncode}:\n{log_path.read_text()}")
        try:
            with urllib.request.urlopen(url, timeout=5) as response:
                if response.status == 200:
                    return
        except (urllib.error.URLError, OSError):
            pass
        time.sleep(0.5)
    pytest.fail(f"JupyterLab did not answer {url} in {SERVER_START_S} s:\n{log_path.read_text()}")


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    """Headless Debian chromium with a fresh profile, driven by Playwright.

    Skips only when there is no chromium.
    """
    executable = shutil.which("chromium") or "/usr/bin/chromium"
    if not os.access(executable, os.X_OK):
        reason = "no chromium found (make test installs Debian's chromium where it can)"
        print(f"scanviz: skipping the browser test: {reason}")
        pytest.skip(reason)
    profile = tmp_path_factory.mktemp("chromium-profile")
    with sync_playwright() as playwright:
        context = playwright.chromium.launch_persistent_context(
            profile,
            executable_path=executable,
            args=CHROMIUM_FLAGS,
            viewport=VIEWPORT,
            timeout=60_000,
        )
        try:
            yield context
        finally:
            context.close()


@pytest.fixture(scope="module")
def lab_root(tmp_path_factory, browser):
    """A fresh copy of notebooks/ that JupyterLab serves (after `browser`: no chromium, no copy)."""
    root_dir = tmp_path_factory.mktemp("lab") / "notebooks"
    shutil.copytree(NOTEBOOK_DIR, root_dir, ignore=shutil.ignore_patterns(".*", "__pycache__"))
    return root_dir


@pytest.fixture(scope="module")
def lab_url(lab_root):
    """Base URL of a JupyterLab serving `lab_root`, with the project's settings."""
    tmp = lab_root.parent
    env = dict(
        os.environ,
        # the news-popup override (see the Makefile's `lab` target), and no user settings
        JUPYTER_CONFIG_PATH=os.pathsep.join(
            p for p in [str(ROOT / ".jupyter"), os.environ.get("JUPYTER_CONFIG_PATH")] if p
        ),
        JUPYTERLAB_SETTINGS_DIR=str(tmp / "user-settings"),
        JUPYTERLAB_WORKSPACES_DIR=str(tmp / "workspaces"),
    )
    port = _free_port()
    log_path = tmp / "jupyterlab.log"
    with log_path.open("wb") as log:
        server = subprocess.Popen(
            [
                sys.executable, "-m", "jupyter", "lab", "--no-browser", "--allow-root",
                f"--port={port}", "--ServerApp.ip=127.0.0.1", "--ServerApp.port_retries=0",
                "--ServerApp.token=", "--ServerApp.password=", "--ServerApp.disable_check_xsrf=True",
                f"--ServerApp.root_dir={lab_root}",
            ],
            env=env, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
        )  # fmt: skip
    try:
        url = f"http://127.0.0.1:{port}"
        _wait_until_answering(f"{url}/lab", server, log_path)
        yield url
    finally:
        server.terminate()
        try:
            server.wait(timeout=15)
        except subprocess.TimeoutExpired:
            server.kill()
            server.wait(timeout=15)


def _screenshot(page: Page, name):
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    path = SCREENSHOTS / name
    page.screenshot(path=path, timeout=30_000)
    print(f"screenshot: {path}")
    return path


def _stem(notebook):
    return notebook.removesuffix(".ipynb").replace("/", "-")


def _open(page: Page, lab_url, notebook):
    """Open `notebook` in a workspace of its own (nothing else open), the file browser shown."""
    page.set_default_timeout(30_000)
    page.goto(f"{lab_url}/lab/workspaces/{_stem(notebook)}/tree/{notebook}")
    page.locator(".jp-NotebookPanel .jp-Cell").first.wait_for(timeout=60_000)
    file_browser = page.locator("#filebrowser")
    if not file_browser.is_visible():
        page.locator(".jp-SideBar.jp-mod-left [data-id='filebrowser']").click()
    file_browser.wait_for(state="visible")


def _shut_down_kernels(lab_url):
    """End every session of this worker's JupyterLab (one notebook is open at a time)."""
    with urllib.request.urlopen(f"{lab_url}/api/sessions", timeout=10) as response:
        sessions = json.load(response)
    for session in sessions:
        request = urllib.request.Request(f"{lab_url}/api/sessions/{session['id']}", method="DELETE")
        urllib.request.urlopen(request, timeout=30).close()


# Installed before Run All: per code cell, its index among all cells, when it finished (its
# prompt got a number) and when anything was added to its outputs (nodes, text, an image's src).
WATCH_CELLS = """() => {
    const all = [...document.querySelectorAll('.jp-Notebook .jp-Cell')];
    const cells = all.filter(cell => cell.matches('.jp-CodeCell'));
    const record = {start: performance.now(), index: cells.map(cell => all.indexOf(cell)),
                    done: cells.map(() => null), shown: cells.map(() => [])};
    cells.forEach((cell, i) => {
        const prompt = cell.querySelector('.jp-InputPrompt');
        new MutationObserver(() => {
            if (record.done[i] === null && /\\[\\d+\\]/.test(prompt.textContent)) {
                record.done[i] = performance.now();
            }
        }).observe(prompt, {childList: true, characterData: true, subtree: true});
        new MutationObserver(mutations => {
            if (mutations.some(m => m.addedNodes.length || m.type !== 'childList')) {
                record.shown[i].push(performance.now());
            }
        }).observe(cell.querySelector('.jp-OutputArea'), {
            childList: true, characterData: true, subtree: true, attributeFilter: ['src'],
        });
    });
    record.changed = performance.now();  // the last change anywhere in the notebook
    new MutationObserver(() => { record.changed = performance.now(); }).observe(
        document.querySelector('.jp-Notebook'),
        {childList: true, characterData: true, subtree: true, attributes: true});
    window.scanvizCells = record;
}"""


def _run_all_cells(page: Page):
    """Run > Run All Cells and wait until the kernel is idle.

    Returns {cell index: (seconds it ran, its longest silence in seconds)} for the code cells run.
    """
    page.locator(".jp-StatusBar-TextItem", has_text=KERNEL_IDLE).wait_for(timeout=60_000)
    page.evaluate(WATCH_CELLS)
    page.get_by_role("menuitem", name="Run", exact=True).click()
    page.get_by_role("menuitem", name="Run All Cells", exact=True).click()
    # Run All stops at the first error, leaving the cells below it unrun
    page.wait_for_function(
        """() => {
            const prompts = [...document.querySelectorAll('.jp-CodeCell .jp-InputPrompt')];
            const indicator = document.querySelector('.jp-Notebook-ExecutionIndicator');
            return window.scanvizCells.done.some(done => done !== null)
                && !prompts.some(p => p.textContent.includes('[*]'))
                && indicator?.dataset.status === 'idle';
        }""",
        timeout=RUN_ALL_S * 1000,
    )
    try:  # widgets and figures arrive after the kernel is idle: let the page settle
        page.wait_for_function(
            f"() => performance.now() - window.scanvizCells.changed > {SETTLED_S * 1000}",
            timeout=RUN_ALL_S * 1000 // 4,
        )
    except PlaywrightTimeout:
        pass  # something keeps changing (an animation): measure it as it is
    record = page.evaluate("window.scanvizCells")
    timings, start = {}, record["start"]
    for index, done, shown in zip(record["index"], record["done"], record["shown"], strict=True):
        if done is None:  # not run
            continue
        moments = [start, *sorted(t for t in shown if start < t < done), done]
        timings[index] = ((done - start) / 1000, max(np.diff(moments)) / 1000)
        start = done  # the kernel starts the next cell as it answers this one
    return timings


def _errors(page: Page):
    """The text of every output showing a traceback, and the indices of the code cells not run."""
    texts = page.locator(
        ".jp-OutputArea-output[data-mime-type='application/vnd.jupyter.stderr']"
    ).all_inner_texts()
    prompts = page.locator(".jp-Notebook .jp-Cell").evaluate_all(
        "cells => cells.map(c => c.matches('.jp-CodeCell') ? "
        "c.querySelector('.jp-InputPrompt').textContent : '[not code]')"
    )
    unrun = [k for k, p in enumerate(prompts) if not re.search(r"\[(\d+|not code)\]", p)]
    return [t for t in texts if TRACEBACK.search(t)], unrun


# Every element of every output that reaches past the notebook's visible content box, top-most
# only (not its children). Text, tables and boxes may overflow inside a box of their own: an
# element of the output whose own style says it scrolls sideways (overflow or overflow-x auto
# or scroll, set in its style attribute: ipywidgets' boxes scroll by default, which hides a
# table's last columns without a word) and that itself fits. Figures (canvas, img, svg) must
# fit whole.
TOO_WIDE = """(tolerance) => {
    const firstCell = document.querySelector('.jp-Notebook .jp-Cell');
    let scroller = firstCell.parentElement;
    while (scroller && !/(auto|scroll)/.test(getComputedStyle(scroller).overflowY)) {
        scroller = scroller.parentElement;
    }
    const box = scroller.getBoundingClientRect();
    const left = box.left + scroller.clientLeft, right = left + scroller.clientWidth;
    const outside = el => {
        const r = el.getBoundingClientRect();
        return r.width > 0 && r.height > 0
            && (r.left < left - tolerance || r.right > right + tolerance);
    };
    const name = el => el.tagName.toLowerCase()
        + [...el.classList].slice(0, 3).map(c => '.' + c).join('')
        + (el.textContent.trim() ? ` ("${el.textContent.trim().slice(0, 30)}...")` : '');
    const problems = [];
    if (scroller.scrollWidth > scroller.clientWidth + tolerance) {
        problems.push({cell: -1, what: 'the notebook itself',
                       detail: `scrolls sideways: ${scroller.scrollWidth} px of content in ${scroller.clientWidth} px`});
    }
    const cells = [...document.querySelectorAll('.jp-Notebook .jp-Cell')];
    cells.forEach((cell, index) => {
        for (const output of cell.querySelectorAll('.jp-OutputArea-output')) {
            const wide = new Set();
            for (const el of [output, ...output.querySelectorAll('*')]) {
                if (!outside(el)) continue;
                const figure = el.matches('canvas, img, svg');
                let inScrollBox = false;
                for (let a = el.parentElement; !figure && a && a !== output; a = a.parentElement) {
                    if (/(auto|scroll)/.test(a.style.overflowX) && !outside(a)) {
                        inScrollBox = true;
                        break;
                    }
                }
                if (inScrollBox) continue;
                wide.add(el);
                if (wide.has(el.parentElement)) continue;
                const r = el.getBoundingClientRect();
                problems.push({cell: index, what: name(el),
                               detail: `spans x ${Math.round(r.left)}..${Math.round(r.right)} px, the notebook ${Math.round(left)}..${Math.round(right)} px`});
            }
        }
    });
    return problems;
}"""

# The text of each output, inline <code> (deliberate code in prose) left out.
OUTPUT_TEXTS = """() => [...document.querySelectorAll('.jp-Notebook .jp-Cell')].flatMap((cell, index) =>
    [...cell.querySelectorAll('.jp-OutputArea-output')].map(output => {
        const copy = output.cloneNode(true);
        copy.querySelectorAll('code, style, script').forEach(c => c.remove());
        return [index, copy.textContent];
    }))"""

# ipympl chrome over or above a figure: a "Figure N" header shown, a toolbar shown or one
# that fades in when the mouse comes over the figure.
IPYMPL_CHROME = """() => {
    const cells = [...document.querySelectorAll('.jp-Notebook .jp-Cell')];
    const where = el => `cell ${cells.indexOf(el.closest('.jp-Cell'))}`;
    return [
        ...[...document.querySelectorAll('.jp-Notebook .jupyter-matplotlib-header')]
            .filter(el => el.getBoundingClientRect().height > 0 && el.textContent.trim())
            .map(el => `${where(el)}: a header "${el.textContent.trim()}"`),
        ...[...document.querySelectorAll('.jp-Notebook .jupyter-matplotlib-toolbar')]
            .filter(el => getComputedStyle(el).visibility !== 'hidden'
                          || el.matches('.jupyter-matplotlib-toolbar-fadein-fadeout'))
            .map(el => `${where(el)}: a toolbar`),
    ];
}"""


def _steppers(page: Page) -> list[Locator]:
    """Every Stepper in the outputs: the box holding a "step k / n: kind" label and Next."""
    labels = page.locator(".jp-OutputArea-output .widget-label").filter(has_text=STEP_LABEL)
    return [labels.nth(k).locator("xpath=..") for k in range(labels.count())]


def _narrates(page: Page, stepper: Locator, name: str):
    """Click Next up to `NARRATED_STEPS` times; what is wrong with the narration line, if anything."""
    label = stepper.locator(":scope > .widget-label").filter(has_text=STEP_LABEL).first
    narration = label.locator("xpath=following-sibling::*[1]")
    next_button = stepper.locator("button").filter(has_text=NEXT_LABEL).first
    stepper.scroll_into_view_if_needed()
    problems, sentence = [], narration.inner_text().strip()
    for _ in range(NARRATED_STEPS):
        if next_button.is_disabled():
            break
        before = label.text_content()
        next_button.click()
        page.wait_for_function(
            "([label, before]) => label.textContent !== before",
            arg=[label.element_handle(), before],
            timeout=STEP_S * 1000,
        )
        step, _, kind = STEP_LABEL.match(label.text_content()).groups()
        try:  # the narration is sent after the label
            page.wait_for_function(
                "([line, before]) => line.innerText.trim() !== before",
                arg=[narration.element_handle(), sentence],
                timeout=NARRATION_S * 1000,
            )
        except PlaywrightTimeout:
            pass  # reported below
        previous, sentence = sentence, narration.inner_text().strip()
        if sentence == previous:
            problems.append(f"{name} step {step}: the narration did not change: {sentence!r}")
        elif sentence.lower() in {kind.lower(), kind.replace("_", " ").lower()}:
            problems.append(f"{name} step {step}: the narration is only the event kind {kind!r}")
        elif len(sentence.split()) < 4 or not re.search(r"[.!?]$", sentence):
            problems.append(f"{name} step {step}: the narration is not a sentence: {sentence!r}")
    return problems


def _view_changes(page: Page, title, caption, clicks):
    """Click Next `clicks` times on the stepper titled `title`; its view's caption before and after."""
    stepper = page.locator(".jp-OutputArea-output", has_text=title).first
    stepper.scroll_into_view_if_needed()
    shown = stepper.locator(".widget-html-content").filter(has_text=caption).first
    label = stepper.locator(".widget-label").filter(has_text=STEP_LABEL).first
    next_button = stepper.locator("button").filter(has_text=NEXT_LABEL).first
    before = shown.inner_text()
    for _ in range(clicks):
        step_before = label.text_content()
        next_button.click()
        page.wait_for_function(
            "([label, before]) => label.textContent !== before",
            arg=[label.element_handle(), step_before],
            timeout=STEP_S * 1000,
        )
    page.locator(".jp-StatusBar-TextItem", has_text=KERNEL_IDLE).wait_for()  # figures redrawn
    return before, shown.inner_text()


def _pixels(locator: Locator):
    """The element's screenshot as an (h, w, 3) uint8 array (one pixel a CSS pixel)."""
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(locator.screenshot())).convert("RGB"))


def _vertex_markers(pixels, window=7, share=0.6):
    """Centres (x, y) in pixels of the editor's vertex markers: crimson dots 6 pt across.

    A marker is where most of a `window`-pixel square is crimson (the 1.5 pt
    outline fills less of it); nearby hits are merged. A marker half hidden
    under a sample dot may be missed.
    """
    r, g, b = (pixels[..., k].astype(int) for k in range(3))
    crimson = (r > 150) & (r - g > 90) & (r - b > 60)
    sums = np.pad(crimson, ((1, 0), (1, 0))).cumsum(0).cumsum(1)
    inside = sums[window:, window:] - sums[:-window, window:]
    inside = inside - sums[window:, :-window] + sums[:-window, :-window]
    centres = []  # [sum of x, sum of y, count]
    for y, x in zip(*np.nonzero(inside >= share * window**2), strict=True):
        for c in centres:
            if abs(c[0] / c[2] - x) < window and abs(c[1] / c[2] - y) < window:
                c[0], c[1], c[2] = c[0] + x, c[1] + y, c[2] + 1
                break
        else:
            centres.append([x, y, 1])
    return [(sx / n + window / 2, sy / n + window / 2) for sx, sy, n in centres]


def _screen_from_pixels(markers, vertices):
    """(miss, scale, offset, pairing): screen = offset + scale * (x, -y) puts marker k on
    vertex pairing[k], at most `miss` screen pixels off.

    The axes have equal aspect and y up; the pairing is the best of all.
    """
    best = None
    for pairing in itertools.permutations(range(len(vertices)), len(markers)):
        v = np.array([vertices[i] for i in pairing], float)
        design = np.zeros((2 * len(v), 3))
        design[0::2, 0], design[0::2, 2] = 1, v[:, 0]
        design[1::2, 1], design[1::2, 2] = 1, -v[:, 1]
        (x0, y0, scale), *_ = np.linalg.lstsq(design, np.ravel(markers), rcond=None)
        miss = np.abs(design @ (x0, y0, scale) - np.ravel(markers)).max()
        if scale > 0 and (best is None or miss < best[0]):
            best = miss, scale, np.array([x0, y0]), pairing
    return best


def _filled(pixels):
    """How many pixels show the coverage's blue (Blues at 1/1.6), not the white background."""
    r, g, b = (pixels[..., k].astype(int) for k in range(3))
    return int(((b > 150) & (b - r > 60) & (g < b)).sum())


def _drag_editor_vertex(page: Page):
    """Drag one vertex of the lesson's PolygonEditor with the mouse; what did not change."""
    editor = page.locator(".jp-OutputArea-output", has_text="active edge table per row").first
    editor.scroll_into_view_if_needed()
    canvas = editor.locator(".jupyter-matplotlib-canvas-div").first
    canvas.scroll_into_view_if_needed()
    table = editor.locator(".widget-html-content").filter(has_text=re.compile(r"^\s*edge table"))
    before_table = table.first.inner_text()
    deadline = time.monotonic() + STEP_S  # the figure is drawn once it is in view
    while len(markers := _vertex_markers(before_pixels := _pixels(canvas))) < 3:
        if time.monotonic() > deadline:
            _screenshot(page, f"{_stem(EDITOR_LESSON)}-editor-markers.png")
            pytest.fail(f"found {len(markers)} vertex markers, too few to drag one: {markers}")
        time.sleep(0.25)
    miss, scale, offset, pairing = _screen_from_pixels(markers, EDITOR_POLYGON)
    assert miss < 3, (
        f"the markers {markers} are not the vertices {EDITOR_POLYGON} ({miss:.1f} px off)"
    )
    least_change = 0.5 * scale**2  # half a raster pixel's square, in screen pixels
    centre = offset + scale * np.mean(EDITOR_POLYGON, axis=0) * (1, -1)
    (x, y), box = markers[0], canvas.bounding_box()
    page.mouse.move(box["x"] + x, box["y"] + y)
    page.mouse.down()
    to_x, to_y = (x, y) + 0.5 * (centre - (x, y))  # halfway to the centre: inside the axes
    page.mouse.move(box["x"] + to_x, box["y"] + to_y, steps=8)
    page.mouse.up()
    print(
        f"editor drag: vertex {EDITOR_POLYGON[pairing[0]]} by ({to_x - x:.0f}, {to_y - y:.0f}) px"
    )
    problems = []
    try:
        page.wait_for_function(
            "([table, before]) => table.innerText !== before",
            arg=[table.first.element_handle(), before_table],
            timeout=STEP_S * 1000,
        )
    except PlaywrightTimeout:
        problems.append("the edge table did not change")
    page.locator(".jp-StatusBar-TextItem", has_text=KERNEL_IDLE).wait_for()
    deadline = time.monotonic() + STEP_S  # the redrawn figure comes a moment after the table
    while abs(_filled(after_pixels := _pixels(canvas)) - _filled(before_pixels)) < least_change:
        if time.monotonic() > deadline:
            problems.append(
                f"the fill did not change by a pixel ({least_change:.0f} screen pixels): "
                f"{_filled(before_pixels)} blue screen pixels, then {_filled(after_pixels)}"
            )
            break
        time.sleep(0.25)
    print(f"editor drag: blue pixels {_filled(before_pixels)} -> {_filled(after_pixels)}")
    _screenshot(page, f"{_stem(EDITOR_LESSON)}-editor-dragged.png")
    return problems


def _fail_listing(problems, what):
    assert not problems, f"{len(problems)} {what}:\n" + "\n".join(map(str, problems))


@pytest.mark.parametrize("notebook", NOTEBOOKS)
def test_notebook_as_a_student_sees_it(notebook, lab_url, browser, subtests):
    page = browser.new_page()
    stem = _stem(notebook)
    try:
        _open(page, lab_url, notebook)
        began = time.monotonic()
        timings = _run_all_cells(page)
        ran_s = time.monotonic() - began
        _screenshot(page, f"{stem}-run-all.png")
        for k, timing in timings.items():
            print(f"{notebook} cell {k}: {timing[0]:.1f} s, longest silence {timing[1]:.1f} s")
        print(f"{notebook}: Run All took {ran_s:.1f} s")

        tracebacks, unrun = _errors(page)
        with subtests.test("runs"):
            assert not tracebacks, tracebacks[0]
            assert not unrun, f"code cells left unrun: {unrun}"
        with subtests.test("fits"):
            too_wide = page.evaluate(TOO_WIDE, TOLERANCE_PX)
            if too_wide:
                first = next((p["cell"] for p in too_wide if p["cell"] >= 0), None)
                if first is not None:
                    page.locator(".jp-Notebook .jp-Cell").nth(first).locator(
                        ".jp-OutputArea"
                    ).scroll_into_view_if_needed()
                    _screenshot(page, f"{stem}-too-wide.png")
            _fail_listing(
                [f"cell {p['cell']}: {p['what']} {p['detail']}" for p in too_wide],
                "outputs wider than the notebook",
            )
        with subtests.test("shows what it is about"):
            if notebook.startswith("exercises/"):  # released blank: the check reports the stub
                texts = page.evaluate(OUTPUT_TEXTS)
                last = "\n".join(text for cell, text in texts if cell == texts[-1][0])
                for words in ("public cases 0 of", "hidden cases are graded later"):
                    assert words in last, f"the check cell does not say {words!r}:\n{last}"
                assert "NotImplementedError" in last, last
            else:
                assert page.locator(".jp-OutputArea-output").locator("img, canvas").count(), (
                    "the lesson shows no picture"
                )
        with subtests.test("no ipympl chrome"):
            _fail_listing(page.evaluate(IPYMPL_CHROME), "ipympl headers or toolbars shown")
        with subtests.test("no raw repr"):
            _fail_listing(
                [
                    f"cell {index}: ...{text[max(0, m.start() - 40) : m.end() + 40]}..."
                    for index, text in page.evaluate(OUTPUT_TEXTS)
                    for m in [RAW_REPR.search(text)]
                    if m
                ],
                "outputs showing a raw repr",
            )
        with subtests.test("never silent"):
            _fail_listing(
                [
                    f"cell {k}: silent for {t[1]:.1f} s of its {t[0]:.1f} s"
                    for k, t in timings.items()
                    if t[1] > SILENT_S
                ],
                f"cells silent for more than {SILENT_S:g} s",
            )
        not_run = "Run All stopped before the end (see the subtest 'runs')"
        for title, caption, clicks in VIEW_CHANGES.get(notebook, []):
            with subtests.test(f"{title!r} steps"):
                if unrun:
                    pytest.skip(not_run)
                before, after = _view_changes(page, title, caption, clicks)
                _screenshot(page, f"{stem}-{title.split(':')[0].replace(' ', '-')}-stepped.png")
                assert after != before, f"its view did not change in {clicks} steps:\n{before}"
        if notebook == EDITOR_LESSON:
            with subtests.test("PolygonEditor drag"):
                if unrun:
                    pytest.skip(not_run)
                _fail_listing(_drag_editor_vertex(page), "problems after dragging a vertex")
        steppers = _steppers(page)
        if steppers:
            with subtests.test("steppers narrate"):
                problems = []
                for k, stepper in enumerate(steppers):
                    problems += _narrates(page, stepper, f"stepper {k + 1} of {len(steppers)}")
                _screenshot(page, f"{stem}-narrated.png")
                _fail_listing(problems, "narration problems")
        print(
            f"{notebook}: {len(steppers)} steppers; all checks took {time.monotonic() - began:.1f} s"
        )
    finally:
        page.close()
        _shut_down_kernels(lab_url)


def _answer_with(path: Path, source: str) -> None:
    """Put `source` into the notebook's answer cell (found by its marker, as the grader does)."""
    import nbformat

    notebook = nbformat.read(path, as_version=4)
    (cell,) = [c for c in notebook.cells if c.source.startswith("# scanviz: answer ")]
    cell.source = cell.source.split("\n", 1)[0] + "\n" + source
    nbformat.write(notebook, path)


def test_exercise_check_cell_shows_the_diagnostics_and_the_comparison(lab_root, lab_url, browser):
    from scanviz.exercises import check, get

    closed_span = next(v for v in get("span_rule").variants if v.name == "closed_span")
    answered = EXERCISE.replace(".ipynb", "_answered.ipynb")  # the released copy stays blank
    shutil.copy(lab_root / EXERCISE, lab_root / answered)
    _answer_with(lab_root / answered, closed_span.source)
    page = browser.new_page()
    try:
        _open(page, lab_url, answered)
        _run_all_cells(page)
        tracebacks, unrun = _errors(page)
        assert not tracebacks and not unrun, (tracebacks, unrun)
        report = page.locator(".jp-OutputArea-output", has_text="hidden cases are graded later")
        text = report.first.inner_text()
        expected = check("span_rule", source=closed_span.source)  # the same check, here
        assert f"public cases {expected.passed} of {len(expected.cases)}" in text, text
        assert "likely cause: " + closed_span.hint in text
        comparison = (
            page.locator(".jp-OutputArea-output")
            .filter(has=page.get_by_role("button", name="next difference"))
            .first
        )
        comparison.scroll_into_view_if_needed()
        yours = comparison.locator(
            ".widget-html-content", has_text=re.compile(r"^yours \(\d+ events\)")
        ).first
        before = yours.inner_text()
        comparison.get_by_role("button", name="next difference").click()
        page.wait_for_function(
            "([pane, before]) => pane.innerText !== before",
            arg=[yours.element_handle(), before],
            timeout=STEP_S * 1000,
        )
        _screenshot(page, f"{_stem(answered)}-checked.png")
    finally:
        page.close()
        _shut_down_kernels(lab_url)
