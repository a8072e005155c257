"""fdsc.plotting: the run's band and the modes' shares, with names and colours, and bad input by
name."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.colors as mcolors  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import fdsc  # noqa: E402
from fdsc.plotting import plot_modes, plot_run  # noqa: E402

PLANT = fdsc.Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
                   [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
GAINS = [np.array([[-21.85, -22.27]]), np.array([[0.495, -1.473]])]


@pytest.fixture(scope="module")
def run():
    """A switched run that visits both modes (a law on x1² against x2²)."""
    loops = [PLANT.closed_loop(K) for K in GAINS]
    W = [np.diag([0.0, 0.0, 1.0, 0.0]), np.diag([0.0, 0.0, 0.0, 1.0])]
    r = fdsc.simulate(loops, fdsc.Sinusoids([1.0], [0.7]), fdsc.time_grid(20.0, 1e-2), law_weights=W)
    assert set(np.unique(r.sigma)) == {0, 1}
    return r


def test_plot_modes_names_and_colours_the_modes(run):
    ax = plot_modes(run, names=["LF gain", "HF gain"], colors=["tab:red", "goldenrod"], bins=50)
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels == ["LF gain", "HF gain"]
    faces = [mcolors.to_hex(c.get_facecolor()[0]) for c in ax.collections]
    assert faces == [mcolors.to_hex("tab:red"), mcolors.to_hex("goldenrod")]
    plt.close("all")


@pytest.mark.parametrize("kw, name", [({"names": ["only one"]}, "names"), ({"names": "LF"}, "names"),
                                      ({"colors": ["k"]}, "colors")])
def test_plot_modes_refuses_too_few_names_or_colours_by_name(run, kw, name):
    with pytest.raises(ValueError, match=f"{name} must give one entry per mode of the run"):
        plot_modes(run, **kw)
    plt.close("all")


def test_plot_run_takes_a_colour(run):
    ax = plot_run(run, label="z", color="tab:purple", bins=50)
    assert mcolors.to_hex(ax.collections[0].get_facecolor()[0]) == mcolors.to_hex("tab:purple")
    plt.close("all")
