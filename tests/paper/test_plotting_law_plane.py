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


def test_every_family_is_drawn_and_a_family_without_a_style_is_refused():
    import pytest

    from fdsc.paper.shared.style import FAMILY_STYLES

    # one point of every family the stored study has: each is drawn (a marker in its family's colour)
    pts = {f"p{k}": (fam, 0.3 + 0.1 * k, 0.5) for k, fam in enumerate(FAMILY_STYLES)}
    fig, ax = plt.subplots()
    plot_fixed_plane(pts, "p0", ax)
    drawn = {line.get_label() for line in ax.lines}
    assert set(FAMILY_STYLES) <= drawn
    plt.close(fig)
    fig, ax = plt.subplots()
    with pytest.raises(KeyError, match=r"points: the families \['adaptive'\] have no style"):
        plot_fixed_plane({"a": ("adaptive", 0.4, 0.4)}, "a", ax)
    plt.close(fig)


def test_the_stored_studys_families_all_have_a_style():
    from fdsc.paper.pays.stored_study import load_full
    from fdsc.paper.shared.style import FAMILY_STYLES

    full = load_full()
    for example in ("aircraft", "generic"):
        assert {v["family"] for v in full[example]["fixed_controllers"].values()} <= set(FAMILY_STYLES)
