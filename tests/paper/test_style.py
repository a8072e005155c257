"""fdsc.paper.shared.style: one colour, marker and line style per controller, gain and band."""

import pytest

from fdsc.paper.shared.style import BAND_CONTROLLER, GAIN_CONTROLLER, STYLES, band_color, style


def test_paper_colours():
    # the paper's text on its Figs. 4-6: PassC-LF red, PassC-HF yellow, FDSC purple
    assert style("PassC-LF")["color"] == "tab:red"
    assert style("PassC-HF")["color"] == "goldenrod"
    assert style("FDSC")["color"] == "tab:purple"


def test_gains_and_bands_are_drawn_like_their_controllers():
    for gain, name in GAIN_CONTROLLER.items():
        assert style(gain) == style(name)
    for band, name in BAND_CONTROLLER.items():
        assert band_color(band) == style(name)["color"]


def test_every_controller_is_distinct():
    assert len({(c, m, ls) for c, m, ls in STYLES.values()}) == len(STYLES)
    assert len({c for c, _, _ in STYLES.values()}) == len(STYLES)


def test_unknown_names_stay_apart():
    assert style("law A", 0) != style("law B", 1)


def test_unknown_band():
    with pytest.raises(KeyError):
        band_color("XF")
