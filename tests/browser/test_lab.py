"""A lesson notebook, run in JupyterLab in headless Chromium, as a student would.

The test starts JupyterLab on a free localhost port over a temporary copy of
``notebooks/``, opens lesson 02, runs all cells from the Run menu, then clicks
the scan-conversion stepper's Next button and checks that the active edge table
shown beside it changes; the same for lesson 07 and its depth-sort stepper
(the pair being tested changes), for lesson 08 and its floating-perimeter
stepper (the facet or edge described changes) and for lesson 09 and its
fill-variant stepper (the span described changes). Screenshots go to
``tests/browser/screenshots/`` (their paths are printed; ``pytest -rP`` shows
them).

The browser is Debian's chromium, driven by Playwright (no browser downloads).
The test skips only when no chromium can be found; every other problem fails.
"""

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

import pytest
from playwright.sync_api import Page, sync_playwright

ROOT = Path(__file__).resolve().parents[2]
LESSON = "02_scan_conversion.ipynb"
VISIBILITY_LESSON = "07_visibility.ipynb"
DEPTH_SORT_TITLE = "depth sort: one pair, swap or split per step"  # DepthSortView's heading
PAIR_CAPTION = re.compile(r"no pair under test|S = \S+, S' = \S+")  # DepthSortView.settled
SURFACES_LESSON = "08_grid_surfaces.ipynb"
PERIMETER_TITLE = "floating perimeter: one facet, edge or update per step"  # perimeter_stepper's
PERIMETER_CAPTION = re.compile(r"^\s*(start:|viewing case \d|facet \d+)")  # PerimeterView.text
SHADING_LESSON = "09_fast_shading.ipynb"
FILL_TITLE = "fill variants: one span at a time"  # fill_stepper's
FILL_CAPTION = re.compile(r"^\s*(span \d+ of|no span yet)")  # FillView.text
FAST_PHONG_TITLE = "fast Phong: one sample per step"  # fast_phong_stepper's
ANTIALIAS_LESSON = "10_antialiasing.ipynb"
DISLOP_TITLE = "DISLOP_L: one column per step"  # dislop_stepper's
DISLOP_CAPTION = re.compile(r"^\s*(column \d+ of|start: \d+ columns)")  # DislopView.text
FAST_PHONG_CAPTION = re.compile(r"^\s*(sample \d+ of|start: \d+ samples)")  # FastPhongView.text
EXERCISE = "exercises/05_span_rule.ipynb"
SCREENSHOTS = Path(__file__).resolve().parent / "screenshots"
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
SERVER_START_S = 90
RUN_ALL_S = 120
STEP_S = 10  # one click of Next: a round trip to the kernel and back
KERNEL_IDLE = re.compile(r"^(?!No Kernel).* \| Idle$")  # the status bar, once a kernel is up
NEXT_CLICKS = 6
NEXT_LABEL = re.compile(r"^\s*(next\b.*|▶\|)\s*$", re.IGNORECASE)  # Stepper.next_button
STEP_LABEL = re.compile(r"^step \d+ / \d+")  # Stepper.label: "step k / n: <event kind>"
AET_CAPTION = re.compile(r"^\s*AET\b")  # ScanConversionView.aet_html: "AET of row y" / "AET: empty"

pytestmark = pytest.mark.xdist_group("browser")


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
def lab_root(tmp_path_factory):
    """A fresh copy of notebooks/ that JupyterLab serves; the exercise test edits its answer cell."""
    root_dir = tmp_path_factory.mktemp("lab") / "notebooks"
    shutil.copytree(
        ROOT / "notebooks", root_dir, ignore=shutil.ignore_patterns(".*", "__pycache__")
    )
    return root_dir


@pytest.fixture(scope="module")
def lab_url(lab_root):
    """Base URL of a JupyterLab serving `lab_root`, with the project's settings."""
    root_dir = lab_root
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
                "--ServerApp.token=", "--ServerApp.password=",
                f"--ServerApp.root_dir={root_dir}",
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
            viewport={"width": 1400, "height": 1000},
            timeout=60_000,
        )
        try:
            yield context
        finally:
            context.close()


def _screenshot(page: Page, name):
    SCREENSHOTS.mkdir(exist_ok=True)
    path = SCREENSHOTS / name
    page.screenshot(path=path, timeout=30_000)
    print(f"screenshot: {path}")
    return path


def _open(page: Page, lab_url, notebook):
    page.set_default_timeout(30_000)
    page.goto(f"{lab_url}/lab/tree/{notebook}", wait_until="domcontentloaded")
    page.locator(".jp-NotebookPanel .jp-Cell").first.wait_for(timeout=60_000)


def _run_all_cells(page: Page, notebook_stem):
    """Run > Run All Cells, then wait until every code cell has run and the kernel is idle."""
    page.locator(".jp-StatusBar-TextItem", has_text=KERNEL_IDLE).wait_for(timeout=60_000)
    page.get_by_role("menuitem", name="Run", exact=True).click()
    page.get_by_role("menuitem", name="Run All Cells", exact=True).click()
    try:  # Run All stops at the first error, leaving the cells below it unrun
        page.wait_for_function(
            """() => {
                const prompts = [...document.querySelectorAll('.jp-CodeCell .jp-InputPrompt')];
                const indicator = document.querySelector('.jp-Notebook-ExecutionIndicator');
                return prompts.some(p => /\\[\\d+\\]/.test(p.textContent))
                    && !prompts.some(p => p.textContent.includes('[*]'))
                    && indicator?.dataset.status === 'idle';
            }""",
            timeout=RUN_ALL_S * 1000,
        )
    finally:
        _screenshot(page, f"{notebook_stem}-run-all.png")
    tracebacks = page.locator(".jp-OutputArea-output", has_text="Traceback (most recent call last)")
    assert tracebacks.count() == 0, tracebacks.first.inner_text()
    prompts = page.locator(".jp-CodeCell .jp-InputPrompt").all_text_contents()
    assert all(re.search(r"\[\d+\]", prompt) for prompt in prompts), f"cells left unrun: {prompts}"


def _click_next(page: Page, stepper, times):
    """Click the stepper's Next `times` times, each time waiting for its step label to move on."""
    next_button = stepper.locator("button.jupyter-button").filter(has_text=NEXT_LABEL).first
    label = stepper.locator(".widget-label", has_text=STEP_LABEL).first
    for _ in range(times):
        before = label.text_content()
        next_button.click()
        page.wait_for_function(
            "([label, before]) => label.textContent !== before",
            arg=[label.element_handle(), before],
            timeout=STEP_S * 1000,
        )


def test_lesson_runs_and_steps_in_jupyterlab(lab_url, browser):
    page = browser.new_page()
    _open(page, lab_url, LESSON)
    _run_all_cells(page, Path(LESSON).stem)

    steppers = page.locator(".jp-OutputArea-output").filter(
        has=page.locator("button.jupyter-button").filter(has_text=NEXT_LABEL)
    )
    assert steppers.count() > 0, f"{LESSON} shows no stepper with a Next button"
    stepper = steppers.first
    stepper.scroll_into_view_if_needed()
    aet = stepper.locator(".widget-html-content").filter(has_text=AET_CAPTION).first
    before = aet.text_content()
    _click_next(page, stepper, NEXT_CLICKS)
    after = aet.text_content()
    page.locator(".jp-StatusBar-TextItem", has_text=KERNEL_IDLE).wait_for()  # figures redrawn
    _screenshot(page, f"{Path(LESSON).stem}-stepped.png")
    assert after != before, f"the AET table did not change in {NEXT_CLICKS} steps:\n{before}"


def _caption_before_and_after_stepping(page: Page, lab_url, lesson, title, caption, clicks):
    """Run `lesson`, press Next `clicks` times on the stepper titled `title`; its caption before and after."""
    _open(page, lab_url, lesson)
    _run_all_cells(page, Path(lesson).stem)
    stepper = page.locator(".jp-OutputArea-output", has_text=title).first
    stepper.scroll_into_view_if_needed()
    shown = stepper.locator(".widget-html-content").filter(has_text=caption).first
    before = shown.inner_text()
    _click_next(page, stepper, clicks)
    page.locator(".jp-StatusBar-TextItem", has_text=KERNEL_IDLE).wait_for()  # figures redrawn
    _screenshot(page, f"{Path(lesson).stem}-stepped.png")
    return before, shown.inner_text()


def test_visibility_lesson_runs_and_its_depth_sort_stepper_steps(lab_url, browser):
    before, after = _caption_before_and_after_stepping(
        browser.new_page(), lab_url, VISIBILITY_LESSON, DEPTH_SORT_TITLE, PAIR_CAPTION, NEXT_CLICKS
    )
    assert after != before, f"the pair tested did not change in {NEXT_CLICKS} steps"


def test_grid_surfaces_lesson_08_runs_and_its_perimeter_stepper_steps(lab_url, browser):
    before, after = _caption_before_and_after_stepping(
        browser.new_page(),
        lab_url,
        SURFACES_LESSON,
        PERIMETER_TITLE,
        PERIMETER_CAPTION,
        NEXT_CLICKS,
    )
    assert after != before, f"the step shown did not change in {NEXT_CLICKS} steps"


def test_fast_shading_lesson_09_runs_and_its_fill_and_fast_phong_steppers_step(lab_url, browser):
    page = browser.new_page()
    clicks = NEXT_CLICKS * 5  # the edge table's events come before any span
    before, after = _caption_before_and_after_stepping(
        page, lab_url, SHADING_LESSON, FILL_TITLE, FILL_CAPTION, clicks
    )
    assert after != before, f"the span shown did not change in {clicks} steps"
    stepper = page.locator(".jp-OutputArea-output", has_text=FAST_PHONG_TITLE).first
    stepper.scroll_into_view_if_needed()
    shown = stepper.locator(".widget-html-content").filter(has_text=FAST_PHONG_CAPTION).first
    before = shown.inner_text()
    _click_next(page, stepper, NEXT_CLICKS)
    page.locator(".jp-StatusBar-TextItem", has_text=KERNEL_IDLE).wait_for()  # figures redrawn
    _screenshot(page, f"{Path(SHADING_LESSON).stem}-fast-phong-stepped.png")
    assert shown.inner_text() != before, f"the sample shown did not change in {NEXT_CLICKS} steps"


def test_antialiasing_lesson_10_runs_and_its_dislop_stepper_steps(lab_url, browser):
    before, after = _caption_before_and_after_stepping(
        browser.new_page(), lab_url, ANTIALIAS_LESSON, DISLOP_TITLE, DISLOP_CAPTION, NEXT_CLICKS
    )
    assert after != before, f"the column shown did not change in {NEXT_CLICKS} steps"


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
    _answer_with(lab_root / EXERCISE, closed_span.source)
    page = browser.new_page()
    _open(page, lab_url, EXERCISE)
    _run_all_cells(page, Path(EXERCISE).stem)
    report = page.locator(".jp-OutputArea-output", has_text="hidden cases are graded later").first
    text = report.inner_text()
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
    _screenshot(page, f"{Path(EXERCISE).stem}-checked.png")
