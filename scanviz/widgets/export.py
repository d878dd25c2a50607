"""A stepper's steps as pictures: an animated GIF or a folder of PNG frames.

A frame is what the stepper shows at one step, drawn from the same trace:
its label (``step k / n: kind``), its narration and the figure of every view
that has one, stacked top to bottom. Views that are only HTML tables have no
figure and are left out of the pictures. The stepper is moved to each step
as its slider would move it, and put back where it was.

For slides, handouts and pages without a kernel: ``stepper.save("scan.gif")``,
``stepper.save("frames/")`` (PNG files ``step_00000.png``, ...), or on the
command line ``python -m scanviz trace --vertices "..." --gif scan.gif``.
"""

from __future__ import annotations

import html
import io
import os
import re
import textwrap
from collections.abc import Iterable
from pathlib import Path

from ..conventions import check_int

MAX_FRAMES = 120  # a GIF of every step of a long trace: thinned evenly to this many frames
HOLD_LAST_MS = 2000  # the last frame stays this long before the GIF loops
FONT_SIZE = 15
MARGIN = 10


def frame_steps(total: int, steps: Iterable[int] | None = None, max_frames: int = MAX_FRAMES):
    """The steps to draw: `steps` as given, or 0..total thinned evenly to `max_frames` (ends kept).

    >>> frame_steps(4)
    [0, 1, 2, 3, 4]
    >>> frame_steps(100, max_frames=5)
    [0, 25, 50, 75, 100]
    >>> frame_steps(10, [3, 7])
    [3, 7]
    """
    max_frames = check_int("max_frames", max_frames, 2, 10_000)
    if steps is None:
        if total + 1 <= max_frames:
            return list(range(total + 1))
        return sorted({round(k * total / (max_frames - 1)) for k in range(max_frames)})
    chosen = [check_int("a step", step, 0, total) for step in steps]
    if not chosen:
        raise ValueError("'steps' must name at least one step")
    if len(chosen) > 10_000:
        raise ValueError(f"'steps' may name at most 10000 steps; got {len(chosen)}")
    return chosen


def _font(size: int = FONT_SIZE):
    import matplotlib
    from PIL import ImageFont

    path = Path(matplotlib.get_data_path()) / "fonts" / "ttf" / "DejaVuSans.ttf"
    return ImageFont.truetype(str(path), size) if path.exists() else ImageFont.load_default(size)


def _figure_image(figure):
    from PIL import Image

    buffer = io.BytesIO()
    figure.savefig(buffer, format="png")
    buffer.seek(0)
    return Image.open(buffer).convert("RGB")


def _header(lines: list[str], width: int, font):
    from PIL import Image, ImageDraw

    line_height = round(FONT_SIZE * 1.4)
    image = Image.new("RGB", (width, 2 * MARGIN + line_height * len(lines)), "white")
    draw = ImageDraw.Draw(image)
    for k, line in enumerate(lines):
        draw.text((MARGIN, MARGIN + k * line_height), line, fill=(20, 20, 20), font=font)
    return image


def frame_image(stepper, step: int):
    """The picture of `stepper` at `step` (a PIL image): label, narration, every view's figure."""
    from PIL import Image

    stepper.slider.value = step
    figures = [getattr(view, "figure", None) for view in stepper.views]
    pictures = [_figure_image(figure) for figure in figures if figure is not None]
    width = max([picture.width for picture in pictures] + [480])
    sentence = html.unescape(re.sub(r"<[^>]+>", "", stepper.narration.value))
    per_line = max(20, (width - 2 * MARGIN) * 2 // FONT_SIZE)  # about half an em a character
    lines = [stepper.label.value, *textwrap.wrap(sentence, per_line)]
    parts = [_header(lines, width, _font()), *pictures]
    frame = Image.new("RGB", (width, sum(part.height for part in parts)), "white")
    top = 0
    for part in parts:
        frame.paste(part, ((width - part.width) // 2, top))
        top += part.height
    return frame


def save_steps(
    stepper,
    path: str | os.PathLike,
    *,
    steps: Iterable[int] | None = None,
    max_frames: int = MAX_FRAMES,
    milliseconds: int | None = None,
) -> list[Path]:
    """Save `stepper`'s steps as a GIF (`path` ends in .gif) or as PNG frames in folder `path`.

    Parameters
    ----------
    stepper : Stepper
    path : str or os.PathLike
        ``*.gif``: one animated GIF that loops. Anything else: a folder
        (created if missing) that gets ``step_00000.png``, ... one per frame.
    steps : iterable of int, optional
        The steps to draw (0 is the start, len(trace) the end). Default: every
        step, thinned evenly to `max_frames` frames, the first and last kept.
    max_frames : int
        At most this many frames when `steps` is not given (2..10000).
    milliseconds : int, optional
        Time per frame in the GIF (default: the stepper's play interval).

    Returns
    -------
    list of pathlib.Path
        The files written.

    Raises
    ------
    ValueError
        If the stepper refused its trace (too long to step through), or a
        step is out of range.
    """
    if stepper.slider is None:
        raise ValueError("this stepper refused its trace (too long): record less, then save")
    chosen = frame_steps(len(stepper.model), steps, max_frames)
    if milliseconds is None:
        milliseconds = stepper.play.interval
    milliseconds = check_int("milliseconds", milliseconds, 10, 60_000)
    path, frames = Path(path), _frames(stepper, chosen)
    if path.suffix.lower() == ".gif":
        _write_gif(frames, path, milliseconds)
        return [path]
    path.mkdir(parents=True, exist_ok=True)
    written = []
    for step, frame in zip(chosen, frames, strict=True):
        written.append(path / f"step_{step:05d}.png")
        frame.save(written[-1])
    return written


def _frames(stepper, steps: list[int]) -> list:
    """The pictures of `steps`, on canvases of one size; the stepper is put back where it was."""
    start = stepper.slider.value
    try:
        return _padded([frame_image(stepper, step) for step in steps])
    finally:
        stepper.slider.value = start


def _padded(frames: list) -> list:
    """The frames on white canvases of the largest frame's size (narrations wrap differently)."""
    from PIL import Image

    width, height = max(f.width for f in frames), max(f.height for f in frames)
    canvases = [Image.new("RGB", (width, height), "white") for _ in frames]
    for canvas, frame in zip(canvases, frames, strict=True):
        canvas.paste(frame, (0, 0))
    return canvases


def _write_gif(frames: list, target, milliseconds: int) -> None:
    """One looping GIF of `frames` (same size) into `target`, a path or a file."""
    durations = [milliseconds] * len(frames)
    durations[-1] = max(milliseconds, HOLD_LAST_MS)
    frames[0].save(
        target, format="GIF", save_all=True, append_images=frames[1:], duration=durations, loop=0
    )


def gif_data_uri(stepper, *, max_frames: int = 16, milliseconds: int = 700) -> str:
    """A small looping GIF of `stepper` as a ``data:`` URI, for a page without a kernel."""
    import base64

    if stepper.slider is None:
        return ""
    chosen = frame_steps(len(stepper.model), None, max_frames)
    frames = _frames(stepper, chosen)
    buffer = io.BytesIO()
    scale = min(1.0, 720 / max(f.width for f in frames))
    if scale < 1.0:
        frames = [f.resize((round(f.width * scale), round(f.height * scale))) for f in frames]
    _write_gif(frames, buffer, milliseconds)
    return "data:image/gif;base64," + base64.b64encode(buffer.getvalue()).decode("ascii")


def static_html(widget) -> str:
    """An HTML still of an ipywidgets tree: its text, tables and pictures, without controls.

    What a page without a kernel shows where the widget would be: labels and
    HTML as they are, images inline, a matplotlib canvas (ipympl) as its
    figure; sliders, buttons and other controls are left out.
    """
    import base64

    import ipywidgets as widgets

    if isinstance(widget, widgets.Box):
        inner = "".join(static_html(child) for child in widget.children)
        style = "display:flex;flex-wrap:wrap;gap:8px" if isinstance(widget, widgets.HBox) else ""
        return f"<div style='{style}'>{inner}</div>"
    if isinstance(widget, widgets.HTML | widgets.HTMLMath):
        return f"<div>{widget.value}</div>"
    if isinstance(widget, widgets.Label):
        return f"<div>{html.escape(widget.value)}</div>"
    if isinstance(widget, widgets.Image) and widget.value:
        data = base64.b64encode(widget.value).decode("ascii")
        return f"<img src='data:image/{widget.format};base64,{data}' style='max-width:100%'>"
    figure = getattr(widget, "figure", None)
    if figure is not None and hasattr(figure, "savefig"):
        buffer = io.BytesIO()
        figure.savefig(buffer, format="png")
        data = base64.b64encode(buffer.getvalue()).decode("ascii")
        return f"<img src='data:image/png;base64,{data}' style='max-width:100%'>"
    if isinstance(widget, widgets.Output):
        return "".join(_output_html(output) for output in widget.outputs)
    return ""


def _output_html(output: dict) -> str:
    data = output.get("data", {})
    if "image/png" in data:
        return f"<img src='data:image/png;base64,{data['image/png']}' style='max-width:100%'>"
    if "text/html" in data:
        return data["text/html"]
    text = output.get("text") or data.get("text/plain", "")
    return f"<pre>{html.escape(text)}</pre>" if text else ""
