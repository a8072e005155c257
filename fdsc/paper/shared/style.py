"""The one style map of the book's figures: a colour, a marker and a line style per controller,
gain and band, the paper's own colours where it names them.

The paper's text on its Figs. 4–6 names three colours: PassC-LF is the red line, PassC-HF the
yellow one and FDSC the purple one; PassC-EF, which it does not name, is blue here. A gain is
drawn like the controller that uses it (K_f1 like PassC-LF, K_f3 like PassC-HF, K_e like PassC-EF)
and a band like the controller designed for it. Variants of FDSC keep a purple-family or an
earthy colour and differ by line style and marker, so that they stay apart in grey print.

This module holds data only (no matplotlib): every plotting module of the paper layer and every
chapter draws through :func:`style`.
"""

__all__ = ["STYLES", "GAIN_CONTROLLER", "BAND_CONTROLLER", "FAMILY_STYLES", "MARK_COLOR",
           "VERDICT_COLORS", "style", "band_color", "family_style"]

#: ``{name: (colour, marker, line style)}`` of every controller the book draws.
STYLES = {
    "open loop": ("0.45", "o", ":"),
    "PassC-EF": ("tab:blue", "s", "-"),
    "PassC-LF": ("tab:red", "^", "-"),
    "PassC-MF": ("tab:olive", "<", "-"),
    "PassC-HF": ("goldenrod", "v", "-"),
    "HF best": ("tab:orange", "D", "--"),
    "FDSC": ("tab:purple", "x", "-"),
    "FDSC (dwell)": ("tab:pink", "+", "--"),
    "FDSC (HF best)": ("tab:brown", "*", "-."),
    "FDSC (our Q)": ("tab:green", "P", "--"),
    "FDSC (candidate ẋ)": ("tab:cyan", "d", ":"),
    "ideal segment law": ("k", ".", "-."),
    "front 1": ("#08519c", "o", "--"),
    "front 2": ("#3182bd", "o", "--"),
    "front 3": ("#6baed6", "o", "--"),
    "law on ŵ": ("darkgreen", "o", "-"),
    "band-power law": ("#1b9e77", "d", "--"),
    "clairvoyant oracle": ("#7570b3", "*", ":"),
}

#: ``{family: (colour, marker)}`` of the fixed controllers of Part II (chapter 'ladder'):
#: one palette for families, apart from the paper's controllers' colours where they can meet.
FAMILY_STYLES = {
    "comparator set": ("0.45", "o"),
    "static front": ("#3182bd", "s"),
    "LQR": ("#e6550d", "P"),
    "dynamic front": ("#31a354", "D"),
    "H2": ("#756bb1", "^"),
    "tuned": ("k", "*"),
    "tuned (x, ŵ)": ("#e7298a", "X"),
    "optimal LTI": ("#a6761d", "h"),
}

#: Marks that are not data (the reference ratio 1, a limit, the ring of what was chosen): black,
#: never a controller's colour.
MARK_COLOR = "k"

#: A check that holds or fails (cases, not controllers): a palette apart from the controllers'.
VERDICT_COLORS = {True: "0.15", False: "#c51b7d"}

#: A printed gain → the controller it is (and is drawn as).
GAIN_CONTROLLER = {"K_f1": "PassC-LF", "K_f2": "PassC-MF", "K_f3": "PassC-HF", "K_e": "PassC-EF"}

#: A band → the controller designed for it.
BAND_CONTROLLER = {"LF": "PassC-LF", "MF": "PassC-MF", "HF": "PassC-HF", "EF": "PassC-EF"}

# further names (the generic example's designs, laws of the repair chapters) cycle through these
_EXTRA = (("tab:cyan", "o", "-"), ("tab:olive", "s", "--"), ("tab:gray", "^", "-."),
          ("tab:pink", "v", ":"))


def style(name, k=0):
    """The colour, marker and line style of a controller, gain or band.

    Parameters
    ----------
    name : str
        A key of :data:`STYLES`, a printed gain (``"K_f1"``, …) or a band (``"LF"``, …).
    k : int, optional
        Index of the name among those drawn together: a name the map does not know takes the
        ``k``-th of a few extra styles, so that a figure's unknown names stay apart.

    Returns
    -------
    dict
        ``{"color", "marker", "linestyle"}``, ready as keyword arguments of ``Axes.plot``.

    Examples
    --------
    >>> style("PassC-LF")["color"], style("K_f1") == style("PassC-LF"), style("HF")["color"]
    ('tab:red', True, 'goldenrod')
    """
    key = GAIN_CONTROLLER.get(name, BAND_CONTROLLER.get(name, name))
    color, marker, ls = STYLES.get(key, _EXTRA[k % len(_EXTRA)])
    return {"color": color, "marker": marker, "linestyle": ls}


def band_color(band):
    """The colour of a band (``"LF"``, ``"MF"``, ``"HF"`` or ``"EF"``): its controller's.

    Parameters
    ----------
    band : str

    Returns
    -------
    str

    Raises
    ------
    KeyError
        If the band is not one of the four.

    Examples
    --------
    >>> band_color("LF")
    'tab:red'
    """
    return STYLES[BAND_CONTROLLER[band]][0]


def family_style(family):
    """``{"color", "marker"}`` of a family of fixed controllers (:data:`FAMILY_STYLES`).

    Parameters
    ----------
    family : str

    Returns
    -------
    dict

    Examples
    --------
    >>> family_style("tuned")["marker"]
    '*'
    """
    color, marker = FAMILY_STYLES.get(family, ("tab:gray", "."))
    return {"color": color, "marker": marker}
