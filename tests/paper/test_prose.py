"""fdsc.paper.shared.prose: the one number formatter of the book's prose."""

import numpy as np
import pytest

from fdsc.paper.shared.prose import count, excess, num, pct, span, times


@pytest.mark.parametrize(("x", "digits", "text"), [
    (7.0, 3, "7.00"),               # .3g would drop the zeros ("0.436 to 7 times")
    (0.43593, 3, "0.436"),
    (1.0, 3, "1.00"),
    (118.82, 3, "119"),
    (99999.5, 3, "1.00 × 10⁵"),     # rounds up across the switch to powers of ten
    (1092.79, 3, "1,093"),          # more integer digits than asked: the whole number
    (999.7, 3, "1,000"),
    (1.149e7, 3, "1.15 × 10⁷"),
    (2.7e-26, 2, "2.7 × 10⁻²⁶"),
    (-0.0128, 3, "−0.0128"),
    (0.0, 3, "0.00"),
    (np.float64(22.534), 3, "22.5"),
    (float("nan"), 3, "n/a"),
    (float("-inf"), 3, "−∞"),
])
def test_num(x, digits, text):
    assert num(x, digits) == text


def test_integers_print_in_full():
    assert num(37493) == "37,493" and num(np.int64(20)) == "20" and count(-1200) == "−1,200"


def test_times_and_span():
    assert times(1.0) == "×1.00"
    assert span(1.3601, 1.3649) == "1.36"          # equal ends print once ("1.36 – 1.36")
    assert span(0.436, 7.0) == "0.436–7.00"
    assert span(0.5, 2.0, fmt=times) == "×0.500–×2.00"
    assert pct(0.04) == "4 %" and pct(1.0) == "100 %"


def test_excess_is_a_percentage_within_one_percent_else_a_factor():
    # the printed bounds of Sec. IV: K_f2's band peak 0.40279 against 0.4025, K_f3's 1.6051
    # against 0.1714
    assert excess(0.40279, 0.4025) == "0.07 % above"
    assert excess(1.6051, 0.1714) == "×9.36"
    assert excess(1.0101, 1.0) == "×1.01"     # 1.01 % above: a factor


@pytest.mark.parametrize(("call", "error", "match"), [
    (lambda: num(True), TypeError, "x must be a real number"),
    (lambda: num("0.5"), TypeError, "x must be a real number"),
    (lambda: num(0.5, 0), ValueError, "digits must be at least 1"),
    (lambda: count(2.0), TypeError, "n must be an integer"),
    (lambda: count(np.True_), TypeError, "n must be an integer"),
    (lambda: pct(1.2), ValueError, r"share must lie in \[0, 1\]"),
    (lambda: pct(float("nan")), ValueError, r"share must lie in \[0, 1\]"),
    (lambda: times(None), TypeError, "x must be a real number"),
    (lambda: excess(0.3, 0.4), ValueError, "quantity must lie above a positive bound"),
    (lambda: excess(0.3, 0.0), ValueError, "quantity must lie above a positive bound"),
])
def test_bad_inputs(call, error, match):
    with pytest.raises(error, match=match):
        call()


def test_glued_text_reads_back_as_printed(monkeypatch):
    # MyST-NB's {glue:text} evaluates the glued text/plain form with ast.literal_eval: a str's repr
    # reads back as the str, digits and separators kept
    import myst_nb
    from IPython.core.formatters import PlainTextFormatter
    from myst_nb.core.variables import format_plain_text

    from fdsc.paper.shared import prose

    glued = {}
    monkeypatch.setattr(myst_nb, "glue", lambda name, value, display: glued.update({name: value}))
    texts = {"a": count(37493), "b": num(1.0), "c": times(0.759), "d": span(0.436, 7.0), "e": pct(0.04)}
    # nothing is returned, so that a cell ending in the call shows no list of names
    assert prose.glue_numbers(texts, "p_") is None
    assert list(glued) == [f"p_{k}" for k in texts]
    plain = PlainTextFormatter()
    for key, text in texts.items():
        assert format_plain_text(plain(glued[f"p_{key}"]), "") == text
    with pytest.raises(TypeError, match="numbers must be keyed by str"):
        prose.glue_numbers({1: "x"})


def test_a_share_short_of_whole_is_never_printed_whole():
    from fdsc.paper.shared.prose import pct

    assert pct(0.996) == "99.6 %" and pct(0.9996) == "99.96 %" and pct(0.004) == "0.4 %"
    assert pct(1.0) == "100 %" and pct(0.0) == "0 %" and pct(0.5) == "50 %"
    assert pct(0.99999999) == "100.000 %"        # three decimals at most: then it rounds
