"""The colour ring of Wang (1989, §3.4): phases of a complex function as colours.

A surface z = |F(x + iy)| is coloured by the phase arg F through a closed
ring of 3·S colours (spec §2.9). Each third of the ring blends two of the
three primaries linearly in S steps, so exactly two are ever mixed ("binary
colours"), and the last entry blends back into the first::

    entries 0 .. S-1     green -> red     phases   0° .. 120°
    entries S .. 2S-1    red   -> blue    phases 120° .. 240°
    entries 2S .. 3S-1   blue  -> green   phases 240° .. 360°

Entry k stands for the phase 360° k / (3S); entry 3S wraps to entry 0.
A phase selects an entry by the dissertation's printed rule
``int(phase * (size - 1) / 2 pi)`` after moving it into [0, 2 pi), and a
triangle takes the entry of its vertices' mean phase, made continuous
across ±pi first. The interactive marker of Fig. 3-10 swaps one entry for
a marker colour: every triangle of that phase lights up at no extra cost.
Derivations and pictures: ``docs/colour-ring.md``.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from ..conventions import as_array, check_int, short_repr

MAX_RING_STEPS = 4096
"""Largest number of steps per segment (a 12,288-colour ring; the dissertation's largest is 192)."""


def _size(size: object) -> int:
    if isinstance(size, bool) or not isinstance(size, numbers.Integral):
        raise TypeError(f"'size' must be an int; got {short_repr(size)}")
    if size < 1:
        raise ValueError(f"'size' must be >= 1 (the number of ring entries); got {size}")
    return int(size)


def _phases(name: str, value: object) -> np.ndarray:
    """`value` as a float64 array of phases in [-pi, pi] (the range of numpy.angle)."""
    phases = as_array(value, f"{name!r} must be an array of numbers", copy=True)
    bad = np.argwhere(~(np.abs(phases) <= math.pi))  # also catches NaN
    if bad.size:
        where = tuple(int(i) for i in bad[0])
        raise ValueError(
            f"{name!r} must be phases in [-pi, pi] (as numpy.angle gives); "
            f"{name}{list(where)} is {phases[where]}"
        )
    return phases


def colour_ring(steps: int = 64) -> np.ndarray:
    """The closed ring of 3·steps colours, green -> red -> blue -> green.

    Parameters
    ----------
    steps : int
        S, the entries per segment, 1..`MAX_RING_STEPS`. The dissertation
        uses S = 32 (96 colours) and S = 64 (192 colours, its Fig. 3-8).

    Returns
    -------
    (3 S, 3) ndarray of float64
        RGB in [0, 1]. Entry k = s S + m (segment s, step m, t = m / S) is
        (t, 1 - t, 0), (1 - t, 0, t) or (0, t, 1 - t) for s = 0, 1, 2: the
        channels sum to 1, adjacent entries (the last and the first
        included) differ by 1/S in two channels. For an 8-bit colour
        look-up table scale by 255: ``np.rint(255 * ring).astype(np.uint8)``.

    Notes
    -----
    The endpoint convention is lost with Fig. 3-8; this one starts each
    segment at its pure primary (spec §2.9 [REC]), so entries 0, S and 2S
    are pure green, red and blue.

    Examples
    --------
    >>> colour_ring(2)
    array([[0. , 1. , 0. ],
           [0.5, 0.5, 0. ],
           [1. , 0. , 0. ],
           [0.5, 0. , 0.5],
           [0. , 0. , 1. ],
           [0. , 0.5, 0.5]])
    >>> colour_ring(64).shape
    (192, 3)
    """
    steps = check_int("steps", steps, 1, MAX_RING_STEPS)
    t = np.arange(steps) / steps
    zero = np.zeros(steps)
    segments = ((t, 1 - t, zero), (1 - t, zero, t), (zero, t, 1 - t))  # G->R, R->B, B->G
    return np.concatenate([np.stack(rgb, axis=1) for rgb in segments])


def _entry(phase: np.ndarray, size: int) -> np.ndarray:
    """The printed rule: a negative phase moves up by 2 pi, then int(phase (size - 1) / 2 pi)."""
    phase = np.where(phase < 0, phase + 2 * math.pi, phase)
    return (phase * (size - 1) / (2 * math.pi)).astype(np.int64)


def ring_index(phase: object, size: int) -> np.ndarray:
    """The ring entry of each phase (per pixel or per vertex).

    Parameters
    ----------
    phase : array_like of float
        Phases in [-pi, pi], e.g. ``numpy.angle(F)``.
    size : int
        Entries in the ring, >= 1 (``len(colour_ring(steps))``).

    Returns
    -------
    ndarray of int64, the shape of `phase`
        ``int(p (size - 1) / 2 pi)`` with p = phase, plus 2 pi if negative.

    Notes
    -----
    The factor size - 1 (191 for the 192-colour ring) is as the dissertation
    prints it: phases [2 pi k / (size - 1), 2 pi (k + 1) / (size - 1)) take
    entry k, so entries 0..size-2 share the whole circle and entry size - 1
    is reached only at p = 2 pi (a phase that rounds to 2 pi on moving up).
    The colours run 1/size of a turn behind the nominal phase of each entry
    at most; across 0 the index jumps from size - 2 to 0, a step of 2/S
    in one channel instead of 1/S.

    Examples
    --------
    >>> ring_index([0.0, np.pi / 2, np.pi, -np.pi / 2, -1e-300], 192).tolist()
    [0, 47, 95, 143, 191]
    """
    return _entry(_phases("phase", phase), _size(size))


def triangle_ring_index(phases: object, size: int) -> np.ndarray:
    """The ring entry of each triangle from its vertices' phases, continuous across ±pi.

    Parameters
    ----------
    phases : (T, 3) array_like of float
        The phases of each triangle's three vertices, in [-pi, pi], in the
        triangle's vertex order (the rule below is sequential).
    size : int
        Entries in the ring, >= 1.

    Returns
    -------
    (T,) ndarray of int64
        The dissertation's pseudo-code (spec §2.9, cleaned)::

            for i in 1..3:
                if pa[i] < 0 and pa[j] - pa[i] > pi for some j != i:  pa[i] += 2 pi
            avg = (pa[1] + pa[2] + pa[3]) / 3;  if avg < 0: avg += 2 pi
            entry = int(avg (size - 1) / 2 pi)

        Vertex i is compared with the phases as already adjusted for
        vertices before it. The entry scale is that of `ring_index`.

    Examples
    --------
    Phases 3pi/4, -3pi/4 and pi straddle the cut at ±pi: -3pi/4 becomes
    5pi/4, the mean is pi (entry 95), not the naive pi/3 (entry 31):

    >>> triangle_ring_index([[3 * np.pi / 4, -3 * np.pi / 4, np.pi]], 192).tolist()
    [95]
    """
    pa = _phases("phases", phases)
    if pa.ndim != 2 or pa.shape[1] != 3:
        raise ValueError(f"'phases' must be a (T, 3) array; got shape {pa.shape}")
    size = _size(size)
    pa = pa.copy()
    for i in range(3):
        others = pa[:, [j for j in range(3) if j != i]]
        straddles = (pa[:, i] < 0) & (others - pa[:, i : i + 1] > math.pi).any(axis=1)
        pa[straddles, i] += 2 * math.pi
    return _entry((pa[:, 0] + pa[:, 1] + pa[:, 2]) / 3, size)


def replace_entry(ring: object, entry: int, marker: object = (1.0, 1.0, 1.0)) -> np.ndarray:
    """A copy of `ring` with one entry swapped for a marker colour (the phase marker of Fig. 3-10).

    Parameters
    ----------
    ring : (N, 3) array_like of float
        RGB in [0, 1], e.g. `colour_ring`.
    entry : int
        The entry to mark, 0..N-1 (negative indices are refused).
    marker : RGB
        Components in [0, 1]; default white, which the ring never contains.

    Returns
    -------
    (N, 3) ndarray of float64
        The ring with row `entry` set to `marker`; `ring` is unchanged. Every
        triangle whose entry is `entry` (`marked_triangles`) shows the marker.

    Examples
    --------
    >>> replace_entry(colour_ring(1), 2).tolist()
    [[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 1.0]]
    """
    marked = as_array(ring, "'ring' must be an (N, 3) array of numbers", copy=True)
    if marked.ndim != 2 or marked.shape[1] != 3 or len(marked) == 0:
        raise ValueError(f"'ring' must be an (N, 3) array with N >= 1; got shape {marked.shape}")
    if not ((marked >= 0) & (marked <= 1)).all():
        raise ValueError("'ring' colours must be in [0, 1]")
    entry = _ring_entry(entry, len(marked))
    colour = np.array(marker, dtype=np.float64) if _is_rgb(marker) else None
    if colour is None or not ((colour >= 0) & (colour <= 1)).all():
        raise ValueError(f"'marker' must be 3 numbers in [0, 1]; got {short_repr(marker)}")
    marked[entry] = colour
    return marked


def marked_triangles(entries: object, entry: int) -> np.ndarray:
    """The triangles that a marker on ring entry `entry` lights up.

    Parameters
    ----------
    entries : (T,) array_like of int
        Each triangle's ring entry (`triangle_ring_index`).
    entry : int
        The marked entry, >= 0.

    Returns
    -------
    (M,) ndarray of int64
        The indices t with ``entries[t] == entry``, increasing.

    Examples
    --------
    >>> marked_triangles([3, 5, 3, 0], 3).tolist()
    [0, 2]
    """
    indices = np.asarray(entries)
    if indices.ndim != 1 or (indices.size and indices.dtype.kind not in "iu"):
        raise ValueError(f"'entries' must be a 1-D array of ints; got {short_repr(entries)}")
    return np.flatnonzero(indices == _ring_entry(entry, None)).astype(np.int64)


def _ring_entry(entry: object, size: int | None) -> int:
    if isinstance(entry, bool) or not isinstance(entry, numbers.Integral):
        raise TypeError(f"'entry' must be an int; got {short_repr(entry)}")
    if entry < 0 or (size is not None and entry >= size):
        bound = "" if size is None else f" and < {size} (the ring's size)"
        raise ValueError(f"'entry' must be >= 0{bound}; got {short_repr(entry)}")
    return int(entry)


def _is_rgb(value: object) -> bool:
    try:
        items = list(value)  # type: ignore[call-overload]
    except TypeError:
        return False
    return len(items) == 3 and all(
        isinstance(v, numbers.Real) and not isinstance(v, bool) for v in items
    )
