"""The plane of band peaks of the fixed controllers: the inset and the named family."""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from fdsc.paper.pays.plotting_law import plot_fixed_plane  # noqa: E402

POINTS = {"A": ("comparator set", 0.40, 0.40), "B": ("comparator set", 0.401, 0.401),
          "C": ("comparator set", 2.0, 1.5), "far": ("comparator set", 50.0, 50.0),
          "t": ("tuned", 0.38, 0.45)}


def _labels(ax):
    return sorted(a.get_text() for a in ax.texts)


def test_named_members_are_labelled_once_and_coinciding_ones_share_a_label():
    fig, ax = plt.subplots()
    _ax, off = plot_fixed_plane(POINTS, "t", ax, top=10.0, named="comparator set")
    assert off == ["far"]
    assert _labels(ax) == ["A, B", "C"]
    plt.close(fig)


def test_a_member_shown_in_the_inset_is_labelled_there_only():
    fig, ax = plt.subplots()
    plot_fixed_plane(POINTS, "t", ax, top=10.0, zoom=(0.37, 0.41, 0.39, 0.46), named="comparator set")
    (inset,) = ax.child_axes
    assert _labels(inset) == ["A, B"] and _labels(ax) == ["C"]
    assert inset.get_xlim() == (0.37, 0.41)
    plt.close(fig)
