"""The paper's names in one place: gains, bands, controllers (the map between them).
"""


__all__ = [
    "GAIN_ORDER",
    "BAND_ORDER",
    "GAIN_BANDS",
    "CONTROLLERS",
    "CONTROLLER_GAINS",
    "FIGURE_IDS",
    "FDSC_IN_BAND",
]


GAIN_ORDER = ("K_f1", "K_f2", "K_f3", "K_e")


BAND_ORDER = ("LF", "MF", "HF", "EF")


#: Printed gain → the band it was designed for.
GAIN_BANDS = {"K_f1": "LF", "K_f2": "MF", "K_f3": "HF", "K_e": "EF"}


#: Controllers compared in paper Figs. 4-8 (the paper's names).
CONTROLLERS = ("PassC-EF", "PassC-LF", "PassC-HF", "FDSC")


#: The printed gain of each fixed-gain controller.
CONTROLLER_GAINS = {"PassC-EF": "K_e", "PassC-LF": "K_f1", "PassC-HF": "K_f3"}


#: The record's figure entries, named by content, with the number of the paper figure each
#: reproduces (numbers of the compiled tex, whose Fig. 2 is the code-availability box).
FIGURE_IDS = {"sigma_max": 3, "lf_outputs": 4, "hf_outputs": 5, "hf_l2": 6, "mixed_sweep": 7,
              "piecewise_sweep": 8}


#: Index of the in-band mode of the paper's FDSC (PassC-HF = K_f3 on Ω_3; the paper's example has
#: HF as its in-band range, Sec. IV).
FDSC_IN_BAND = 1
