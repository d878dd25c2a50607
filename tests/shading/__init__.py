"""Meshes shared by the shading tests: a unit cube and a UV sphere, faces counter-clockwise outside."""

import numpy as np

# Vertex 4x + 2y + z is the corner (x, y, z) of the unit cube.
CUBE_POSITIONS = np.array([(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
CUBE_FACES = (
    [0, 1, 3, 2],  # x = 0
    [4, 6, 7, 5],  # x = 1
    [0, 4, 5, 1],  # y = 0
    [2, 3, 7, 6],  # y = 1
    [0, 2, 6, 4],  # z = 0
    [1, 5, 7, 3],  # z = 1
)


def uv_sphere(rings: int = 12, segments: int = 24) -> tuple[np.ndarray, tuple[list[int], ...]]:
    """A unit sphere: poles, `rings` - 1 latitude rings, triangle fans at the poles, quads between."""
    polar = np.pi * np.arange(1, rings) / rings
    azimuth = 2 * np.pi * np.arange(segments) / segments
    ring = np.stack(
        [
            np.outer(np.sin(polar), np.cos(azimuth)),
            np.outer(np.sin(polar), np.sin(azimuth)),
            np.outer(np.cos(polar), np.ones(segments)),
        ],
        axis=-1,
    ).reshape(-1, 3)
    positions = np.vstack([(0, 0, 1), ring, (0, 0, -1)])
    south = len(positions) - 1

    def at(r: int, s: int) -> int:
        return 1 + r * segments + s % segments

    faces = [[0, at(0, s), at(0, s + 1)] for s in range(segments)]
    faces += [
        [at(r, s), at(r + 1, s), at(r + 1, s + 1), at(r, s + 1)]
        for r in range(rings - 2)
        for s in range(segments)
    ]
    faces += [[south, at(rings - 2, s + 1), at(rings - 2, s)] for s in range(segments)]
    return positions, tuple(faces)
