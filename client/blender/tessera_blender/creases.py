"""Blender creases as Tessera sharpness, and back.

Blender's own subdivision hands a crease c in [0, 1] to OpenSubdiv as the
sharpness 10 c^2 (BKE_subdiv_crease_to_sharpness_f), and Tessera follows
OpenSubdiv's sharpness scale, where 10 and more is infinitely sharp
(docs/FORMATS.md, tag files). So the same crease gives the same surface in
Blender's Subdivision Surface modifier and in Tessera.
"""

import math

INFINITE_SHARPNESS = 10.0


def sharpness_of_crease(crease):
    """Tessera sharpness of a Blender crease value (clamped to [0, 1])."""
    c = min(max(float(crease), 0.0), 1.0)
    return INFINITE_SHARPNESS * c * c


def crease_of_sharpness(sharpness):
    """The Blender crease value that gives `sharpness`."""
    s = min(max(float(sharpness), 0.0), INFINITE_SHARPNESS)
    return math.sqrt(s / INFINITE_SHARPNESS)


def sharpness_text(sharpness):
    """As tag files and edit scripts write it: `inf` for infinitely sharp."""
    if sharpness >= INFINITE_SHARPNESS:
        return "inf"
    return repr(float(sharpness))
