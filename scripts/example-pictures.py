#!/usr/bin/python3
"""Pictures of a G-code for the examples' READMEs (PNG, matplotlib; colours as the preview's).

  example-pictures.py side GCODE OUT.png --y Y [--x X0,X1] [--title T]
      a vertical section through the plane y = Y (mm, bed coordinates): every bead that crosses
      it drawn as a box one bead wide and one layer high, so the layers' heights show.
  example-pictures.py top GCODE OUT.png --layers L1,L2,... [--box X0,Y0,X1,Y1]
      the layers (0-based, counted by ;LAYER_CHANGE, as our ;LAYER:) from above, paths coloured by ;TYPE:, the seam of every
      outer wall (where its loop starts) as a black dot.
  example-pictures.py panels OUT.png GCODE:LAYER:TITLE ... [--box X0,Y0,X1,Y1]
      one layer of each G-code side by side, with its title (the infill patterns).

Beads are drawn at 0.45 mm wide; travels are not drawn.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "bench"))
import gcode_moves  # noqa: E402  (the G-code reader the bench scripts share)

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Rectangle
except ImportError:
    sys.exit("example-pictures: needs matplotlib (Debian's python3-matplotlib, scripts/install-deps.sh)")

# The preview's colours (geometry/preview/colours.cpp) by the G-code's ;TYPE: names.
COLOURS = {
    "External perimeter": "#ff7d38",
    "Perimeter": "#e8c21c",
    "Internal infill": "#b03029",
    "Solid infill": "#9654cc",
    "Top solid infill": "#f04040",
    "Bridge infill": "#4d80ba",
    "Skirt/Brim": "#00876e",
    "Ironing": "#2aa7a0",
    "Gap fill": "#a0a0a0",
    "Support material": "#00c000",
    "Support material interface": "#008000",
}
BEAD = 0.45


def read(path):
    """Layers of extrusions: [(z_bottom, z_top, [(type, x0, y0, x1, y1, starts_run)])]."""
    layers, cur = [], None
    was_extruding = False

    def comment(raw):
        nonlocal cur, was_extruding
        if raw.startswith(";LAYER_CHANGE"):  # then ;Z: (the layer's top); ours and PrusaSlicer's
            cur = []
            layers.append([None, cur])
        elif raw.startswith(";Z:"):
            if layers and layers[-1][0] is None:
                layers[-1][0] = float(raw[3:])
        elif raw.startswith(";TYPE:"):
            was_extruding = False

    for kind, x, y, nx, ny, de in gcode_moves.moves(path, comment):
        moved = (nx, ny) != (x, y)
        if de > 0 and moved and cur is not None:
            cur.append((kind, x, y, nx, ny, not was_extruding))
            was_extruding = True
        elif moved:
            was_extruding = False
    # A layer's bottom: the previous layer's top (the first one's: the bed).
    out, below = [], 0.0
    for top, moves in layers:
        top = below if top is None else top
        out.append((below, top, moves))
        below = top
    return out


def legend(ax, kinds):
    handles = [plt.Line2D([], [], color=COLOURS.get(k, "#606060"), lw=3, label=k) for k in kinds]
    ax.legend(handles=handles, loc="upper right", fontsize=7, framealpha=0.9)


def side(args):
    layers = read(args.gcode)
    fig, ax = plt.subplots(figsize=(8, 4.6))
    kinds = []
    for zb, zt, moves in layers:
        for kind, x0, y0, x1, y1, _ in moves:
            c = COLOURS.get(kind, "#606060")
            if abs(y0 - args.y) < BEAD / 2 and abs(y1 - args.y) < BEAD / 2:  # along the plane
                a, b = min(x0, x1), max(x0, x1)
            elif (y0 - args.y) * (y1 - args.y) <= 0 and y0 != y1:  # across it
                xm = x0 + (args.y - y0) / (y1 - y0) * (x1 - x0)
                a, b = xm - BEAD / 2, xm + BEAD / 2
            else:
                continue
            ax.add_patch(Rectangle((a, zb), b - a, zt - zb, facecolor=c, edgecolor="white", lw=0.3))
            if kind not in kinds:
                kinds.append(kind)
    if args.x:
        x0, x1 = (float(v) for v in args.x.split(","))
        ax.set_xlim(x0, x1)
    else:
        ax.autoscale()
    ax.set_ylim(0, max(zt for _, zt, _ in layers) + 0.5)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("z (mm)")
    ax.set_title(args.title or f"section at y = {args.y:g} mm")
    legend(ax, kinds)
    fig.tight_layout()
    fig.savefig(args.out, dpi=args.dpi)


def draw_layer(ax, moves, seams=True):
    kinds = []
    for kind, x0, y0, x1, y1, _ in moves:
        ax.plot([x0, x1], [y0, y1], color=COLOURS.get(kind, "#606060"), lw=0.9, solid_capstyle="round")
        if kind not in kinds:
            kinds.append(kind)
    if seams:
        pts = [(x0, y0) for kind, x0, y0, _, _, start in moves if kind == "External perimeter" and start]
        if pts:
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "o", color="black", ms=4, zorder=5)
    return kinds


def frame(ax, box, title):
    if box:
        x0, y0, x1, y1 = (float(v) for v in box.split(","))
        ax.set_xlim(x0, x1)
        ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=9)
    ax.tick_params(labelsize=7)


def top(args):
    layers = read(args.gcode)
    wanted = [int(v) for v in args.layers.split(",")]
    fig, axs = plt.subplots(1, len(wanted), figsize=(4 * len(wanted), 4.2), squeeze=False)
    kinds = []
    for ax, li in zip(axs[0], wanted):
        if not 0 <= li < len(layers):
            sys.exit(f"example-pictures: no layer {li} (the G-code has {len(layers)})")
        zb, zt, moves = layers[li]
        kinds += [k for k in draw_layer(ax, moves) if k not in kinds]
        frame(ax, args.box, f"layer {li}: z {zt:g} mm, {zt - zb:.2f} mm high")
    legend(axs[0][-1], kinds)
    fig.tight_layout()
    fig.savefig(args.out, dpi=args.dpi)


def panels(args):
    specs = []
    for p in args.panels:
        parts = p.rsplit(":", 2)
        if len(parts) != 3:
            sys.exit(f"example-pictures: '{p}' is not GCODE:LAYER:TITLE")
        specs.append((parts[0], int(parts[1]), parts[2]))
    cols = min(len(specs), args.columns)
    rows = (len(specs) + cols - 1) // cols
    aspect = 1.0
    if args.box:
        x0, y0, x1, y1 = (float(v) for v in args.box.split(","))
        aspect = (y1 - y0) / (x1 - x0)
    fig, axs = plt.subplots(rows, cols, figsize=(3.2 * cols, (3.2 * aspect + 0.35) * rows), squeeze=False)
    for ax in axs.flat:
        ax.set_visible(False)
    for ax, (path, li, title) in zip(axs.flat, specs):
        layers = read(path)
        if not 0 <= li < len(layers):
            sys.exit(f"example-pictures: no layer {li} in {path} ({len(layers)} layers)")
        ax.set_visible(True)
        draw_layer(ax, layers[li][2], seams=False)
        frame(ax, args.box, title)
        ax.set_xticks([])
        ax.set_yticks([])
    fig.tight_layout()
    fig.savefig(args.out, dpi=args.dpi)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="view", required=True)
    s = sub.add_parser("side")
    s.add_argument("gcode")
    s.add_argument("out")
    s.add_argument("--y", type=float, required=True)
    s.add_argument("--x")
    s.add_argument("--title")
    t = sub.add_parser("top")
    t.add_argument("gcode")
    t.add_argument("out")
    t.add_argument("--layers", required=True)
    t.add_argument("--box")
    p = sub.add_parser("panels")
    p.add_argument("out")
    p.add_argument("panels", nargs="+")
    p.add_argument("--box")
    p.add_argument("--columns", type=int, default=4)
    for q in (s, t, p):
        q.add_argument("--dpi", type=int, default=80)
    args = ap.parse_args()
    {"side": side, "top": top, "panels": panels}[args.view](args)


if __name__ == "__main__":
    main()
