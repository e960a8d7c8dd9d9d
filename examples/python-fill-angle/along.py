# The fill-angle hook of `tranche slice --fill-angle-script along.py`: fill each long, thin
# island along its length (lines the length of a bar are stronger in bending and need fewer
# turns); anything else keeps the default 45°/135° alternation. Trusted code: it runs inside
# the slicer with your rights. See docs/fill-angle-script.md.
import math


def principal_axis(outline):
    """The direction (degrees) along which the polygon is longest, and how elongated it is
    (the ratio of its second moments of area about its two principal axes)."""
    a = sx = sy = sxx = syy = sxy = 0.0
    n = len(outline)
    for i in range(n):
        (x0, y0), (x1, y1) = outline[i], outline[(i + 1) % n]
        c = x0 * y1 - x1 * y0
        a += c / 2
        sx += (x0 + x1) * c / 6
        sy += (y0 + y1) * c / 6
        sxx += (x0 * x0 + x0 * x1 + x1 * x1) * c / 12
        syy += (y0 * y0 + y0 * y1 + y1 * y1) * c / 12
        sxy += (x0 * y1 + 2 * x0 * y0 + 2 * x1 * y1 + x1 * y0) * c / 24
    cx, cy = sx / a, sy / a
    mxx, myy, mxy = sxx - a * cx * cx, syy - a * cy * cy, sxy - a * cx * cy
    angle = 0.5 * math.degrees(math.atan2(2 * mxy, mxx - myy))
    mean = (mxx + myy) / 2
    spread = math.hypot((mxx - myy) / 2, mxy)
    ratio = (mean + spread) / max(mean - spread, 1e-12)
    return angle % 180, ratio


def fill_angle(ctx):
    angle, ratio = principal_axis(ctx.outer)
    if ratio > 9:  # at least 3 times longer than wide
        return angle
    return ctx.default_angle
