"""What a reader needs of a figure, checked on the matplotlib objects: no legend covers a
plotted point or line of any panel."""

import numpy as np
from matplotlib.collections import Collection
from matplotlib.lines import Line2D
from matplotlib.patches import Rectangle


def _display_points(ax) -> np.ndarray:
    """Every plotted point of a panel in display coordinates: line vertices (with points
    along each segment, so that a legend over a segment between markers counts), scatter
    offsets, the tops of bars."""
    points = []
    for artist in ax.get_children():
        if isinstance(artist, Line2D) and artist.get_visible() and len(artist.get_xdata()):
            xy = np.column_stack([np.asarray(artist.get_xdata(), float),
                                  np.asarray(artist.get_ydata(), float)])
            xy = artist.get_transform().transform(xy)
            xy = xy[np.all(np.isfinite(xy), axis=1)]
            if len(xy) > 1:  # 20 points along each segment
                t = np.linspace(0.0, 1.0, 20)[:, None, None]
                xy = (xy[:-1] * (1 - t) + xy[1:] * t).reshape(-1, 2)
            points.append(xy)
        elif isinstance(artist, Collection) and artist.get_visible():
            offsets = artist.get_offsets()
            if len(offsets):
                points.append(artist.get_offset_transform().transform(offsets))
        elif isinstance(artist, Rectangle) and artist.get_visible() and artist is not ax.patch:
            box = artist.get_window_extent()
            if box.width > 0 and box.height > 0:
                points.append(np.array([[box.x0, box.y1], [box.x1, box.y1],
                                        [0.5 * (box.x0 + box.x1), box.y1]]))
    return np.concatenate(points) if points else np.empty((0, 2))


def assert_legends_cover_no_data(fig) -> None:
    fig.canvas.draw()
    legends = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None] + list(fig.legends)
    assert legends, "the figure has no legend"
    for ax in fig.axes:
        inside = ax.get_window_extent()  # only what is drawn inside the panel shows
        points = _display_points(ax)
        points = points[(points[:, 0] >= inside.x0) & (points[:, 0] <= inside.x1)
                        & (points[:, 1] >= inside.y0) & (points[:, 1] <= inside.y1)]
        for lg in legends:
            box = lg.get_window_extent()
            covered = points[(points[:, 0] > box.x0) & (points[:, 0] < box.x1)
                             & (points[:, 1] > box.y0) & (points[:, 1] < box.y1)]
            assert not len(covered), (f"the legend {[t.get_text() for t in lg.get_texts()]} covers "
                                      f"{len(covered)} plotted points of the panel "
                                      f"{ax.get_title()!r}")


def assert_tick_labels_apart(fig) -> None:
    """No two tick labels of an axis overlap (a log axis over less than a decade labelled
    its minor ticks, 3×10⁻³4×10⁻³6×10⁻³, one over the next)."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            boxes = [t.get_window_extent(renderer) for t in axis.get_ticklabels(minor=False)
                     + axis.get_ticklabels(minor=True) if t.get_visible() and t.get_text()]
            for i, a in enumerate(boxes):
                for b in boxes[i + 1:]:
                    assert not a.overlaps(b), (ax.get_title(), axis.axis_name,
                                               [t.get_text() for t in axis.get_ticklabels()])
